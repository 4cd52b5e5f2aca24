// Two unit-square blocks stacked at z = 0.5 (hexahedra, structured, NON-matching on the
// interface): the 3D contact patch test. Lower block: nl x nl x 2 hex8, upper: nu x nu x 2.
// tet = 1: tetrahedra instead (unstructured inside, structured triangles on every face, so
// the interface facets are tri3, or tri6 with Mesh->order 2; nl = nu gives matching
// interface triangulations).
// Physical groups: volumes "lower", "upper"; surfaces "base" (z = 0), "lower_top" and
// "upper_bottom" (the interface sides), "upper_top" (z = 1), "sym_x" (x = 0, both
// blocks), "sym_y" (y = 0, both blocks).
SetFactory("OpenCASCADE");
nl = DefineNumber[3, Name "Parameters/nl"];
nu = DefineNumber[4, Name "Parameters/nu"];
tet = DefineNumber[1, Name "Parameters/tet"];
Box(1) = {0, 0, 0, 1, 1, 0.5};
Box(2) = {0, 0, 0.5, 1, 1, 0.5};   // no BooleanFragments: two separate bodies
For v In {1:2}
  n = nu;
  If (v == 1)
    n = nl;
  EndIf
  s[] = Abs(Boundary{ Volume{v}; });
  c[] = Abs(Boundary{ Surface{s[]}; });
  Transfinite Curve{c[]} = n + 1;
  For i In {0:#c[]-1}   // through-thickness edges: 2 layers
    bb[] = BoundingBox Curve{c[i]};
    If (Fabs(bb[5] - bb[2]) > 0.1)  // OCC boxes are padded by a tolerance
      Transfinite Curve{c[i]} = 3;
    EndIf
  EndFor
  Transfinite Surface{s[]};
  If (tet == 0)
    Recombine Surface{s[]};
    Transfinite Volume{v};
  EndIf
EndFor
// Faces by position, then by body.
e = 1e-3;  // OCC bounding boxes are padded by a small tolerance
For v In {1:2}
  s[] = Abs(Boundary{ Volume{v}; });
  For i In {0:#s[]-1}
    bb[] = BoundingBox Surface{s[i]};
    If (Fabs(bb[2] - bb[5]) < e)
      If (Fabs(bb[2]) < e)
        base = s[i];
      EndIf
      If (Fabs(bb[2] - 0.5) < e)
        If (v == 1)
          lower_top = s[i];
        Else
          upper_bottom = s[i];
        EndIf
      EndIf
      If (Fabs(bb[2] - 1) < e)
        upper_top = s[i];
      EndIf
    EndIf
    If (Fabs(bb[0]) < e && Fabs(bb[3]) < e)
      symx[] += s[i];
    EndIf
    If (Fabs(bb[1]) < e && Fabs(bb[4]) < e)
      symy[] += s[i];
    EndIf
  EndFor
EndFor
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
Physical Surface("base") = {base};
Physical Surface("lower_top") = {lower_top};
Physical Surface("upper_bottom") = {upper_bottom};
Physical Surface("upper_top") = {upper_top};
Physical Surface("sym_x") = {symx[]};
Physical Surface("sym_y") = {symy[]};
