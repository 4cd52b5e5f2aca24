// expect: 'Save' writes files
Save StrCat("@WATCH@", "/s.msh");
