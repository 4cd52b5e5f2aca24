// Meridian section of a solid cylinder (radius 1, height 1) for an axisymmetric deck:
// x = r, y = z; curves "axis" (x = 0), "bottom", "mantle" (x = 1), "top".
Point(1) = {0, 0, 0, 0.2};
Point(2) = {1, 0, 0, 0.2};
Point(3) = {1, 1, 0, 0.2};
Point(4) = {0, 1, 0, 0.2};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("plug") = {1};
Physical Curve("bottom") = {1};
Physical Curve("mantle") = {2};
Physical Curve("top") = {3};
Physical Curve("axis_line") = {4};
