// Artery cross-section: full annulus, inner radius 1.5e-3 m, outer radius
// 2.0e-3 m (wall thickness 0.5 mm), centred at the origin, plane strain.
// Physical groups: surface "artery"; curves "lumen" (inner circle) and
// "outer" (outer circle).
// The element size h is only a default: a deck's Mesh->size (> 0) replaces it.
h = DefineNumber[1.25e-4, Name "Parameters/h"];
ri = 1.5e-3;
ro = 2.0e-3;

Point(1) = {0, 0, 0, h};  // centre
Point(2) = {ro, 0, 0, h};
Point(3) = {0, ro, 0, h};
Point(4) = {-ro, 0, 0, h};
Point(5) = {0, -ro, 0, h};
Point(6) = {ri, 0, 0, h};
Point(7) = {0, ri, 0, h};
Point(8) = {-ri, 0, 0, h};
Point(9) = {0, -ri, 0, h};

Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 8};
Circle(7) = {8, 1, 9};
Circle(8) = {9, 1, 6};

Curve Loop(1) = {1, 2, 3, 4};  // outer circle, counter-clockwise
Curve Loop(2) = {5, 6, 7, 8};  // lumen (hole)
Plane Surface(1) = {1, 2};

Physical Surface("artery") = {1};
Physical Curve("lumen") = {5, 6, 7, 8};
Physical Curve("outer") = {1, 2, 3, 4};
