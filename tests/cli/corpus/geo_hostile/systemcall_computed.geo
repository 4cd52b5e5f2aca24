// expect: 'SystemCall' runs a program
SystemCall StrCat("touch ", "@WATCH@/sc");
