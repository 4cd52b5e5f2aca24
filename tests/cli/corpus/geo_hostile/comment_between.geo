// expect: 'Printf' writes a file
Printf("x") /* a comment */
  // and another
  >> "@WATCH@/pwned.txt";
