// expect: 'View' sets an option that names a file or program (View.FileName)
View[0].FileName = "@WATCH@/v.pos";
