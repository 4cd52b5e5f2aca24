// expect: 'Save' writes files
Function "W2"
  Save StrCat("@WATCH@", "/m.msh");
Return
Call "W2";
