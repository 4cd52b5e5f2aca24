// expect: 'ListFromFile' reads a file
a() = ListFromFile("/etc/passwd");
