// expect: 'Field' of type ExternalProcess runs a program
Field[1] = ExternalProcess;
