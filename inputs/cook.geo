// Cook's membrane (tapered cantilever), plane strain; the classical benchmark
// geometry (lengths as in the literature, e.g. mm): vertices (0,0), (48,44),
// (48,60), (0,44).
// Physical groups: surface "membrane"; curves "clamped" (x=0 edge) and
// "tip" (x=48 edge, where the shear load is applied).
// The element size h is only a default: a deck's Mesh->size (> 0) replaces it.
h = DefineNumber[4, Name "Parameters/h"];

Point(1) = {0, 0, 0, h};
Point(2) = {48, 44, 0, h};
Point(3) = {48, 60, 0, h};
Point(4) = {0, 44, 0, h};

Line(1) = {1, 2};  // lower edge
Line(2) = {2, 3};  // tip (x=48)
Line(3) = {3, 4};  // upper edge
Line(4) = {4, 1};  // clamped (x=0)

Curve Loop(1) = {1, 2, 3, 4};  // counter-clockwise
Plane Surface(1) = {1};

Physical Surface("membrane") = {1};
Physical Curve("clamped") = {4};
Physical Curve("tip") = {2};
