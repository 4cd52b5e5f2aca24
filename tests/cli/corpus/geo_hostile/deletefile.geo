// expect: 'DeleteFile' writes or deletes files
DeleteFile StrCat("@WATCH@", "/keep.txt");
