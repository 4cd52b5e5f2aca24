// expect: 'Printf' writes a file
Printf("x") > StrCat("@WATCH@", "/pwned.txt");
