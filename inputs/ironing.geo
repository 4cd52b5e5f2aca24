// Ironing (plane strain), after the 2D half-ring problem of Yang, Laursen & Meng (2005):
// a slab 9 x 3 (body "slab", x in [-4.5, 4.5], y in [-3, 0], base "slab_base" clamped, top
// "slab_top" the contact surface) and a half-ring die (body "die", inner radius 2.8, outer
// radius 3, centre (xc, yc): its lowest point 0.03 above the slab; outer arc "die_arc" the
// master surface, its two end faces "die_ends" driven by the deck).
// Structured quads: nx x ny on the slab, nd x 1 on the die (a stiff thin ring: one layer).
nx = DefineNumber[36, Name "Parameters/nx"];
ny = DefineNumber[12, Name "Parameters/ny"];
nd = DefineNumber[60, Name "Parameters/nd"];
Ri = 2.8;
Ro = 3.0;
xc = -2.7;
yc = 3.03;

Point(1) = {-4.5, -3, 0};
Point(2) = {4.5, -3, 0};
Point(3) = {4.5, 0, 0};
Point(4) = {-4.5, 0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};

// Die: the lower half of the ring, counter-clockwise (outer arc left -> bottom -> right).
Point(10) = {xc, yc, 0};
Point(11) = {xc - Ro, yc, 0};
Point(12) = {xc, yc - Ro, 0};
Point(13) = {xc + Ro, yc, 0};
Point(14) = {xc + Ri, yc, 0};
Point(15) = {xc, yc - Ri, 0};
Point(16) = {xc - Ri, yc, 0};
Circle(11) = {11, 10, 12};
Circle(12) = {12, 10, 13};
Line(13) = {13, 14};
Circle(14) = {14, 10, 15};
Circle(15) = {15, 10, 16};
Line(16) = {16, 11};
Curve Loop(2) = {11, 12, 13, 14, 15, 16};
Plane Surface(2) = {2};
Transfinite Curve{11, 12, 14, 15} = nd / 2 + 1;
Transfinite Curve{13, 16} = 2;
Transfinite Surface{2} = {11, 13, 14, 16};
Recombine Surface{2};

Physical Surface("slab") = {1};
Physical Surface("die") = {2};
Physical Curve("slab_base") = {1};
Physical Curve("slab_top") = {3};
Physical Curve("die_arc") = {11, 12};
Physical Curve("die_ends") = {13, 16};
