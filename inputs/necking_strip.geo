// Plane-strain necking of a strip (the 2D variant of inputs/necking_bar.geo, the fast
// ctest PlasticityFE.PlaneStrainNecking*): width 2 W = 12.826 mm, length L = 53.334 mm,
// width reduced by `imperfection` at mid-length (linear taper). One quarter: x >= 0
// (x = 0 the mid-length section), y >= 0 (y = 0 the centre line). Units: mm.
// Physical groups: surface "strip"; curves "mid" (x = 0), "axis" (y = 0), "end"
// (x = L/2, pulled), "edge" (the free tapered side).
// Structured triangles (a transfinite grid of nx x ny, each quad split in two),
// graded towards the mid section (Progression `grade` along x).
W = 6.413;
L = 53.334;
imperfection = DefineNumber[0.018, Name "Parameters/imperfection"];
nx = DefineNumber[16, Name "Parameters/nx"];
ny = DefineNumber[4, Name "Parameters/ny"];
grade = DefineNumber[1.1, Name "Parameters/grade"];

Point(1) = {0, 0, 0};
Point(2) = {L / 2, 0, 0};
Point(3) = {L / 2, W, 0};
Point(4) = {0, (1 - imperfection) * W, 0};
Line(1) = {1, 2};   // axis
Line(2) = {2, 3};   // end
Line(3) = {4, 3};   // edge (from the mid section to the end)
Line(4) = {1, 4};   // mid
Curve Loop(1) = {1, 2, -3, -4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1 Using Progression grade;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};

Physical Surface("strip") = {1};
Physical Curve("axis") = {1};
Physical Curve("end") = {2};
Physical Curve("edge") = {3};
Physical Curve("mid") = {4};
