// 1D Signorini bar (Doyen, Ern & Piperno 2011) as a thin 2D strip [0,1] x [0,h]:
// one row of N quadrilaterals of length 1/N, thickness H = 0.025 (transfinite, recombined;
// the deck asks for Mesh->recombine = true). Physical groups: surface "bar"; curves "left"
// (x = 0, contact), "right" (x = 1, fixed), "bottom", "top".
// Refinement: change N here (Mesh->size does not act on a transfinite mesh);
// tests/system/test_contact_verification.cpp writes copies with N = 20, 40, 80.
N = DefineNumber[40, Name "Parameters/N"];
H = 0.025;
h = 1.0 / N;

Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, H, 0, h};
Point(4) = {0, H, 0, h};
Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // right
Line(3) = {3, 4};  // top
Line(4) = {4, 1};  // left
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = N + 1;
Transfinite Curve{2, 4} = 2;
Transfinite Surface{1};
Recombine Surface{1};

Physical Surface("bar") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
