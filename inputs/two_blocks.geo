// Two unit-wide blocks stacked at y = 0.5 with NON-matching meshes on the interface
// (plane strain, metres): the contact patch test of Taylor & Papadopoulos (1991).
// Physical groups: surfaces "lower", "upper"; curves "base" (y = 0), "lower_top" and
// "upper_bottom" (the two sides of the interface), "upper_top" (y = 1), "lower_left" and
// "upper_left" (x = 0, symmetry-plane variants); points
// "base_corner" (0, 0) and "top_corner" (0, 1) (rigid-body x motion is fixed there).
// nl, nu: divisions of the lower and upper block along x (the interface discretisations).
nl = DefineNumber[4, Name "Parameters/nl"];
nu = DefineNumber[5, Name "Parameters/nu"];
h = DefineNumber[0.25, Name "Parameters/h"];
// gl, gu: the growth ratio of the lower and upper interface divisions (1: uniform; a
// graded interface puts master kinks under the slave nodes, docs/contact.md "Facet hold").
gl = DefineNumber[1, Name "Parameters/gl"];
gu = DefineNumber[1, Name "Parameters/gu"];

Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 0.5, 0, h};
Point(4) = {0, 0.5, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Point(5) = {0, 0.5, 0, h};
Point(6) = {1, 0.5, 0, h};
Point(7) = {1, 1, 0, h};
Point(8) = {0, 1, 0, h};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};

Transfinite Curve{1} = nl + 1;
Transfinite Curve{3} = nl + 1 Using Progression gl;
Transfinite Curve{7} = nu + 1;
Transfinite Curve{5} = nu + 1 Using Progression gu;

Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("base") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("upper_bottom") = {5};
Physical Curve("upper_top") = {7};
Physical Curve("lower_left") = {4};
Physical Curve("upper_left") = {8};
Physical Point("base_corner") = {1};
Physical Point("top_corner") = {8};
