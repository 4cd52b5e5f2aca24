// Scene S3: the S1 ring (annulus Ro = 1, Ri = 0.8, centre (0, 1.1), plane strain) above
// a deformable foundation block [-1.5, 3.5] x [-0.5, 0] (its top is the plane y = 0 of
// S1). Physical groups: surfaces "ring", "foundation"; curves "outer", "inner" (ring),
// "foundation_top", "foundation_base", "foundation_sides".
// h: ring element size; hf: foundation element size (the interface meshes differ).
h = DefineNumber[0.05, Name "Parameters/h"];
hf = DefineNumber[0.1, Name "Parameters/hf"];
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
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};

Point(11) = {-1.5, -0.5, 0, hf};
Point(12) = {3.5, -0.5, 0, hf};
Point(13) = {3.5, 0, 0, hf};
Point(14) = {-1.5, 0, 0, hf};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(3) = {11, 12, 13, 14};
Plane Surface(2) = {3};

Physical Surface("ring") = {1};
Physical Surface("foundation") = {2};
Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("inner") = {5, 6, 7, 8};
Physical Curve("foundation_top") = {13};
Physical Curve("foundation_base") = {11};
Physical Curve("foundation_sides") = {12, 14};
