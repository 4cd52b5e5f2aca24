// expect: 'System' runs a program
System "touch @WATCH@/sc";
