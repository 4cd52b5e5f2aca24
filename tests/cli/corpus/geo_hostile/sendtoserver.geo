// expect: 'SendToServer' runs a program
SendToServer View[0] "x";
