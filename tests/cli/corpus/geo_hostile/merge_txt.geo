// expect: hostile_inc.txt:2: 'Printf' writes a file
Merge "hostile_inc.txt";
