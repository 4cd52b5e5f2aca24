// expect: 'OnelabRun' runs a program
OnelabRun("x", StrCat("touch ", "@WATCH@/o"));
