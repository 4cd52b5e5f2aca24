// expect: opt_file.geo.opt:1: 'SystemCall' runs a program
Point(1) = {0, 0, 0};
