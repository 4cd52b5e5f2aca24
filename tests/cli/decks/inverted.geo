// Unit square meshed from a clockwise curve loop: the surface normal points to -z,
// so every triangle is clockwise in the xy plane (det J < 0). Groups as block2d.geo.
h = 0.25;
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // right
Line(3) = {3, 4};  // top
Line(4) = {4, 1};  // left
Curve Loop(1) = {-4, -3, -2, -1};  // clockwise
Plane Surface(1) = {1};
Physical Surface("block") = {1};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
