// expect: 'Exit' ends the process
For i In {1:1}
  Exit;
EndFor
