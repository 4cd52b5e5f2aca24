// expect: 'Solver' sets an option that names a file or program
Solver.Executable0 = StrCat("/bin/", "sh");
