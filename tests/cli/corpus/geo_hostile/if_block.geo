// expect: 'Printf' writes a file
If (1)
  Printf("x") > "@WATCH@/if.txt";
EndIf
