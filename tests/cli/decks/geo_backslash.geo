// block2d.geo with a command hidden from a screen that takes a backslash for an escape (gmsh has none).
Printf("\");
SystemCall "touch PWNED";
Printf("\");
// Physical groups: surface "block"; curves "left" (x=0), "right" (x=1),
// "bottom" (y=0), "top" (y=1).
// The element size h is only a default: a deck's Mesh->size (> 0) replaces it,
// and the deck's Mesh->order / Mesh->recombine choose P1/P2 and quads.
h = DefineNumber[0.1, Name "Parameters/h"];

Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};

Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // right
Line(3) = {3, 4};  // top
Line(4) = {4, 1};  // left

Curve Loop(1) = {1, 2, 3, 4};  // counter-clockwise: elements have det J > 0
Plane Surface(1) = {1};

Physical Surface("block") = {1};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
