// expect: 'Printf' writes a file
Printf("%g", (1 + (2 * 3))) > StrCat(StrCat("@WATCH@", "/"), StrSub("xpwned.txt", 1, 9));
