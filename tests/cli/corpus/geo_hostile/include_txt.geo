// expect: hostile_inc.txt:2: 'Printf' writes a file
Include "hostile_inc.txt";
