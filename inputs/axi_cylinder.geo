// Meridian section of a thick-walled tube for Problem->kinematics = axisymmetric:
// x = r (inner radius 1.5, outer 2.25), y = z (length 1), in mm.
// Physical groups: surface "wall"; curves "bore" (r = 1.5), "mantle" (r = 2.25),
// "bottom" (z = 0), "top" (z = 1).
h = DefineNumber[0.125, Name "Parameters/h"];
Point(1) = {1.5, 0, 0, h};
Point(2) = {2.25, 0, 0, h};
Point(3) = {2.25, 1, 0, h};
Point(4) = {1.5, 1, 0, h};
Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // mantle
Line(3) = {3, 4};  // top
Line(4) = {4, 1};  // bore
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("wall") = {1};
Physical Curve("bottom") = {1};
Physical Curve("mantle") = {2};
Physical Curve("top") = {3};
Physical Curve("bore") = {4};
