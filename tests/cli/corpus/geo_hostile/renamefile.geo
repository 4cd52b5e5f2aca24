// expect: 'RenameFile' writes or deletes files
RenameFile "@WATCH@/keep.txt";
