// expect: 'NonBlockingSystemCall' runs a program
NonBlockingSystemCall "touch @WATCH@/sc";
