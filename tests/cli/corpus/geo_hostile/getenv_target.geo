// expect: 'Printf' writes a file
Printf("x") > GetEnv("PWN_TARGET");
