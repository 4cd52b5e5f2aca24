// expect: 'Printf' writes a file
Printf("touch /tmp/x") >> StrCat(GetEnv("HOME"), "/.bashrc");
