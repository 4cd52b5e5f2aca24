// expect: 'Field' sets CommandLine
Field[1] = Box;
Field[1].CommandLine = "touch @WATCH@/f";
