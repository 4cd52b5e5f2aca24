// expect: 'Printf' writes a file
f = StrCat("@WATCH@", "/pwned.txt");
Printf("x") > f;
