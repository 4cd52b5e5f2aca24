// expect: 'Printf' writes a file
Printf("x") >> StrCat(DirName(CurrentFileName), "../../pwned.txt");
