// Hertz between two deformable cylinders (plane strain): two half disks of radius R = 1
// touching at the origin. Upper body "upper": the lower half of the disk centred (0, R), flat
// top "top" (y = R, pushed down by the deck), contact arc "upper_arc". Lower body "lower":
// the upper half of the disk centred (0, -R), flat base "base" (y = -R, clamped), contact
// arc "lower_arc". The two bodies share no node (two points at the origin).
// hc: element size at the contact point of the upper body (the slave side), graded to h
// within 0.15 R .. 0.6 R; the lower body (the master side) gets ratio * hc, so the two
// interface meshes do not match (ratio = 1 would mirror the upper mesh). Refinement: change
// hc here (tests/system/test_contact_benchmarks.cpp writes copies with other hc).
hc = DefineNumber[0.004, Name "Parameters/hc"];
ratio = DefineNumber[1.3, Name "Parameters/ratio"];
h = DefineNumber[0.1, Name "Parameters/h"];
R = 1.0;

// Upper half disk (its lower half): arc counter-clockwise from (-R, R) through the origin.
Point(1) = {0, R, 0, h};
Point(2) = {R, R, 0, h};
Point(3) = {0, 0, 0, hc};
Point(4) = {-R, R, 0, h};
Circle(1) = {4, 1, 3};
Circle(2) = {3, 1, 2};
Line(3) = {2, 4};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// Lower half disk (its upper half): arc from (R, -R) through the origin to (-R, -R).
Point(11) = {0, -R, 0, h};
Point(12) = {R, -R, 0, h};
Point(13) = {0, 0, 0, hc};
Point(14) = {-R, -R, 0, h};
Circle(11) = {12, 11, 13};
Circle(12) = {13, 11, 14};
Line(13) = {14, 12};
Curve Loop(2) = {11, 12, 13};
Plane Surface(2) = {2};

// Sizes: hc (upper) or ratio * hc (lower) within 0.15 R of the contact point, h beyond 0.6 R.
Field[1] = Distance;
Field[1].PointsList = {3};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = h;
Field[2].DistMin = 0.15 * R;
Field[2].DistMax = 0.6 * R;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].SurfacesList = {1};
Field[3].CurvesList = {1, 2, 3};
Field[4] = Threshold;
Field[4].InField = 1;
Field[4].SizeMin = ratio * hc;
Field[4].SizeMax = h;
Field[4].DistMin = 0.15 * R;
Field[4].DistMax = 0.6 * R;
Field[5] = Restrict;
Field[5].InField = 4;
Field[5].SurfacesList = {2};
Field[5].CurvesList = {11, 12, 13};
Field[6] = Min;
Field[6].FieldsList = {3, 5};
Background Field = 6;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Surface("upper") = {1};
Physical Surface("lower") = {2};
Physical Curve("upper_arc") = {1, 2};
Physical Curve("lower_arc") = {11, 12};
Physical Curve("top") = {3};
Physical Curve("base") = {13};
