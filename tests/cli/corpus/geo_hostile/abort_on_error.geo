// expect: 'General' sets General.AbortOnError
General.AbortOnError = 4;
Error("x");
