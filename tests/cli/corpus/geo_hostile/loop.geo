// expect: 'Printf' writes a file
For i In {1:2}
  Printf("x") >> Sprintf("@WATCH@/p%g.txt", i);
EndFor
