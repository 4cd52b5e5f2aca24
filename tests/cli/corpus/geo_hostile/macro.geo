// expect: 'Printf' writes a file
Macro W
  Printf("x") > StrCat("@WATCH@", "/m.txt");
Return
Call W;
