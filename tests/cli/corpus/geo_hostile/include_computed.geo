// expect: 'Include' needs a literal
Include StrCat("@WATCH@", "/x.geo");
