// expect: 'Print' writes files
Print Sprintf("@WATCH@/p%g.png", 1);
