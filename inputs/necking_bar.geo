// Necking of a circular bar (Simo 1988; Simo & Armero 1992): radius R = 6.413 mm,
// length L = 53.334 mm, the radius reduced by 1.8% at mid-length (a linear taper from
// R at the ends to 0.982 R at the middle). One eighth of the bar: x >= 0, y >= 0,
// 0 <= z <= L/2 (z = 0 is the mid-length section). Units: mm (with MPa, N).
// Physical groups: volume "bar"; surfaces "xsym" (x = 0), "ysym" (y = 0), "mid" (z = 0,
// the symmetry plane at mid-length), "end" (z = L/2, pulled), "mantle" (free).
// Mesh size: a background field, h * refine near the middle (z < zf, where the neck
// forms) growing linearly to h at z = 2 zf. inputs/necking_bar.xml uses Mesh->size = 0
// (these sizes: h = 3, 1.5 mm at the neck); a Mesh->size > 0 would only cap them.
SetFactory("OpenCASCADE");
R = 6.413;
L = 53.334;
imperfection = DefineNumber[0.018, Name "Parameters/imperfection"];
refine = DefineNumber[0.5, Name "Parameters/refine"];
zf = DefineNumber[8.0, Name "Parameters/zf"];
h = DefineNumber[3.0, Name "Parameters/h"];

Cone(1) = {0, 0, 0, 0, 0, L / 2, (1 - imperfection) * R, R, Pi / 2};

e = 1e-3;  // OCC bounding boxes are padded by a small tolerance
s[] = Abs(Boundary{ Volume{1}; });
For i In {0:#s[]-1}
  bb[] = BoundingBox Surface{s[i]};
  If (Fabs(bb[2] - bb[5]) < e && Fabs(bb[2]) < e)
    mid = s[i];
  ElseIf (Fabs(bb[2] - bb[5]) < e)
    top = s[i];
  ElseIf (Fabs(bb[0] - bb[3]) < e)
    xs = s[i];
  ElseIf (Fabs(bb[1] - bb[4]) < e)
    ys = s[i];
  Else
    mantle = s[i];
  EndIf
EndFor

Physical Volume("bar") = {1};
Physical Surface("xsym") = {xs};
Physical Surface("ysym") = {ys};
Physical Surface("mid") = {mid};
Physical Surface("end") = {top};
Physical Surface("mantle") = {mantle};

// Finer near the middle: hneck for z < zf, growing linearly to h at z = 2 zf.
Field[1] = MathEval;
Field[1].F = Sprintf("%g * (%g + (1 - %g) * Min(1, Max(0, (z - %g) / %g)))", h, refine, refine, zf, zf);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
