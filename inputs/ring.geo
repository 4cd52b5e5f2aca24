// Annulus (2D ring, plane strain) for scene S1: outer radius Ro = 1, inner radius Ri = 0.8,
// centre (0, 1.1): the lowest point of the ring is 0.1 above the plane y = 0.
// Physical groups: surface "ring"; curves "outer", "inner".
// h is a default: a deck's Mesh->size (> 0) replaces it.
h = DefineNumber[0.05, Name "Parameters/h"];
Ro = 1.0; Ri = 0.8; cx = 0.0; cy = 1.1;

Point(1) = {cx, cy, 0, h};
Point(2) = {cx + Ro, cy, 0, h};
Point(3) = {cx, cy + Ro, 0, h};
Point(4) = {cx - Ro, cy, 0, h};
Point(5) = {cx, cy - Ro, 0, h};
Point(6) = {cx + Ri, cy, 0, h};
Point(7) = {cx, cy + Ri, 0, h};
Point(8) = {cx - Ri, cy, 0, h};
Point(9) = {cx, cy - Ri, 0, h};

Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 8};
Circle(7) = {8, 1, 9};
Circle(8) = {9, 1, 6};

Curve Loop(1) = {1, 2, 3, 4};   // counter-clockwise
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};

Physical Surface("ring") = {1};
Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("inner") = {5, 6, 7, 8};
