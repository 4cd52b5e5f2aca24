// Quarter of a thick-walled cylinder (plane strain), inner radius 1, outer
// radius 2 (metres), first quadrant.
// Physical groups: surface "wall"; curves "inner" (r=1), "outer" (r=2),
// "xsym" (the edge on the x-axis, y=0) and "ysym" (the edge on the y-axis, x=0).
// The element size h is only a default: a deck's Mesh->size (> 0) replaces it.
h = DefineNumber[0.1, Name "Parameters/h"];
ri = 1;
ro = 2;

Point(1) = {0, 0, 0, h};   // centre
Point(2) = {ri, 0, 0, h};
Point(3) = {ro, 0, 0, h};
Point(4) = {0, ro, 0, h};
Point(5) = {0, ri, 0, h};

Line(1) = {2, 3};          // y = 0
Circle(2) = {3, 1, 4};     // outer arc, counter-clockwise
Line(3) = {4, 5};          // x = 0
Circle(4) = {5, 1, 2};     // inner arc, clockwise

Curve Loop(1) = {1, 2, 3, 4};  // counter-clockwise
Plane Surface(1) = {1};

Physical Surface("wall") = {1};
Physical Curve("inner") = {4};
Physical Curve("outer") = {2};
Physical Curve("xsym") = {1};
Physical Curve("ysym") = {3};
