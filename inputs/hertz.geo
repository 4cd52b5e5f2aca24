// Hertz (plane strain): the lower half of a disk of radius R = 1, centre (0, R), touching the
// plane y = 0 at the origin. Flat top "top" (y = R, pushed down by the deck), arc "arc"
// (the contact surface), surface "disk".
// hc: element size at the contact point (graded to h away from it). Refinement: change hc
// here (tests/system/test_contact_verification.cpp writes copies with other hc).
hc = DefineNumber[0.004, Name "Parameters/hc"];
h = DefineNumber[0.1, Name "Parameters/h"];
R = 1.0;

Point(1) = {0, R, 0, h};      // centre
Point(2) = {R, R, 0, h};
Point(3) = {0, 0, 0, hc};     // lowest point
Point(4) = {-R, R, 0, h};
Circle(1) = {4, 1, 3};        // arc: left half
Circle(2) = {3, 1, 2};        // arc: right half
Line(3) = {2, 4};             // top
Curve Loop(1) = {1, 2, 3};    // counter-clockwise
Plane Surface(1) = {1};

// Fine band around the contact zone: size hc within 0.15 R of the lowest point.
Field[1] = Distance;
Field[1].PointsList = {3};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = h;
Field[2].DistMin = 0.15 * R;
Field[2].DistMax = 0.6 * R;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Surface("disk") = {1};
Physical Curve("arc") = {1, 2};
Physical Curve("top") = {3};
