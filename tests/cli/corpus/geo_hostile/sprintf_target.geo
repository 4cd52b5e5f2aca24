// expect: 'Printf' writes a file
Printf("%g", 1) > Sprintf("@WATCH@/p%g.txt", 2);
