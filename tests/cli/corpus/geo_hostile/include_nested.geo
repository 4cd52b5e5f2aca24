// expect: hostile_inc2.txt:1: 'Save' writes files
Include "hostile_inc1.txt";
