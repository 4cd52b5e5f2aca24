// Free-flying L-shaped block (after Simo & Tarnow 1992, Gonzalez 2000), metres.
// The L lies in the x-y plane and is extruded 3 along z:
//   long leg  [0,10] x [0,3]  x [0,3]
//   short leg [0,3]  x [3,10] x [0,3]   (both legs have outer length 10, section 3 x 3)
// Volume 153; centroid (3.559, 3.559, 1.5).
// Physical groups: volume "lblock"; surfaces "end_x" (the x = 10 end face of the long
// leg, centroid (10, 1.5, 1.5)) and "end_y" (the y = 10 end face of the short leg,
// centroid (1.5, 10, 1.5)); both faces have area 9.
// The element size h is only a default: a deck's Mesh->size (> 0) replaces it.
h = DefineNumber[1.5, Name "Parameters/h"];

Point(1) = {0, 0, 0, h};
Point(2) = {10, 0, 0, h};
Point(3) = {10, 3, 0, h};
Point(4) = {3, 3, 0, h};
Point(5) = {3, 10, 0, h};
Point(6) = {0, 10, 0, h};

Line(1) = {1, 2};
Line(2) = {2, 3};  // x = 10: extrudes to the face "end_x"
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};  // y = 10: extrudes to the face "end_y"
Line(6) = {6, 1};

Curve Loop(1) = {1, 2, 3, 4, 5, 6};  // counter-clockwise
Plane Surface(1) = {1};

// out[0]: top (z = 3), out[1]: the volume, out[2 + i]: the side swept by Line(1 + i).
out[] = Extrude {0, 0, 3} { Surface{1}; };

Physical Volume("lblock") = {out[1]};
Physical Surface("end_x") = {out[3]};
Physical Surface("end_y") = {out[6]};
