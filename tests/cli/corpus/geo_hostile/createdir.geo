// expect: 'CreateDir' writes or deletes files
CreateDir StrCat("@WATCH@", "/d");
