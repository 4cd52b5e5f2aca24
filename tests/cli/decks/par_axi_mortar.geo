// Meridian sections of two stacked annular blocks for an axisymmetric deck (x = r, y = z):
// lower r in [0.5, 1.5], z in [0, 1] (size 0.25), upper the same radii, z in [1, 2] (size
// 0.2): non-matching meshes on the interface z = 1.
Point(1) = {0.5, 0, 0, 0.25};
Point(2) = {1.5, 0, 0, 0.25};
Point(3) = {1.5, 1, 0, 0.25};
Point(4) = {0.5, 1, 0, 0.25};
Point(5) = {0.5, 1, 0, 0.2};
Point(6) = {1.5, 1, 0, 0.2};
Point(7) = {1.5, 2, 0, 0.2};
Point(8) = {0.5, 2, 0, 0.2};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("base") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("upper_base") = {5};
Physical Curve("upper_mantle") = {6};
Physical Curve("upper_top") = {7};
