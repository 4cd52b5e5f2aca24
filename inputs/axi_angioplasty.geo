// Balloon angioplasty of a stenosed coronary artery, as a meridian section for
// Problem->kinematics = axisymmetric (docs/axisymmetric.md): x = r, y = z (the axis of
// revolution), lengths in mm (inputs/axi_angioplasty.xml, docs/scenes/axi_angioplasty_summary.md).
//
// Artery: a straight segment of healthy lumen radius Ri, length L (z = -L/2 .. L/2), three
// layers of the thicknesses of inputs/artery_layers.xml (intima ti, media tm, adventitia ta).
// Plaque: a concentric stenosis of area reduction "stenosis" (1 - (r_throat / Ri)^2) with a
// raised-cosine axial profile of length Lp centred on z = 0:
//     r_lumen(z) = Ri - h(z),  h(z) = hmax (1 + cos(2 pi z / Lp)) / 2  for |z| <= Lp/2, else 0,
//     hmax = Ri (1 - sqrt(1 - stenosis)).
// The mesh is structured: columns of axial length L / nz (nz = round(L / dz), even, so that
// z = 0, the throat, is a node line). In each column the innermost zone, from the lumen to
// r = Ri + ti, holds nin cells of equal radial size; its cells whose centroid lies inside the
// healthy lumen (r < Ri) are the plaque, the others the intima (the plaque-intima interface is
// a staircase, finer with more cells; as Mesh->Artery's plaque, docs/artery.md). The media
// holds nm cells, the adventitia na.
// Balloon: a thin tube (wall tb, outer radius Rb) inside the throat, centred on z = 0 and
// about 1 mm longer than the artery, so that its ends (held by the catheter) lie beyond the
// artery's and every lumen node lies over its straight part; nb cells through its wall, cells
// of the artery's axial size whose nodes lie midway between the lumen's (a lumen node does not
// start on a vertex of the balloon's outer line, where the contact normal jumps).
//
// Physical groups: surfaces "plaque", "intima", "media", "adventitia", "balloon"; curves
// "lumen" (the artery's inner line, plaque profile included), "outer" (r = Ri + ti + tm + ta),
// "artery_ends" (z = -L/2 and L/2), "balloon_inner" (its inner line, where the inflation
// pressure acts), "balloon_outer" (its outer line, in contact with the lumen), "balloon_ends"
// (its end lines).
dz = DefineNumber[0.05, Name "Parameters/dz"];            // axial cell length [mm]
nin = DefineNumber[6, Name "Parameters/nin"];             // cells through plaque + intima
nm = DefineNumber[2, Name "Parameters/nm"];               // cells through the media
na = DefineNumber[2, Name "Parameters/na"];               // cells through the adventitia
nb = DefineNumber[2, Name "Parameters/nb"];               // cells through the balloon wall
stenosis = DefineNumber[0.6, Name "Parameters/stenosis"]; // area reduction at the throat
Lp = DefineNumber[4.0, Name "Parameters/Lp"];             // plaque length [mm]

Ri = 1.5; ti = 0.27; tm = 0.21; ta = 0.34;  // inputs/artery_layers.xml
L = 10.0;
Rb = 0.9; tb = 0.05;                        // balloon: outer radius, wall

If (stenosis < 0 || stenosis >= 0.95)
  Error("Parameters/stenosis = %g: the area reduction must lie in [0, 0.95)", stenosis);
EndIf
If (Lp <= 0 || Lp > L - 1)
  Error("Parameters/Lp = %g: the plaque length must lie in (0, %g] mm", Lp, L - 1);
EndIf
If (dz <= 0 || dz > 0.5 || nin < 2 || nm < 1 || na < 1 || nb < 1)
  Error("Parameters: dz = %g must lie in (0, 0.5] mm, nin >= 2, nm, na, nb >= 1", dz);
EndIf
hmax = Ri * (1 - Sqrt(1 - stenosis));
If (Ri - hmax <= Rb + 0.01)
  Error("Parameters/stenosis = %g: the throat radius %g mm leaves the balloon (outer radius %g mm) no room",
        stenosis, Ri - hmax, Rb);
EndIf
nz = 2 * Round(0.5 * L / dz);
Rm = Ri + ti; Ra = Rm + tm; Ro = Ra + ta;

// Node lines z_k, k = 0 .. nz: nin + 1 points through the innermost zone, then the
// media-adventitia interface and the outer surface.
For k In {0 : nz}
  z = -L / 2 + k * L / nz;
  hk = 0;
  If (Fabs(z) < Lp / 2)
    hk = hmax * (1 + Cos(2 * Pi * z / Lp)) / 2;
  EndIf
  r0 = Ri - hk;
  For j In {0 : nin}
    rr[] += {r0 + j * (Rm - r0) / nin};
    p = newp;
    Point(p) = {r0 + j * (Rm - r0) / nin, z, 0};
    pin[] += {p};
  EndFor
  p = newp; Point(p) = {Ra, z, 0}; pm[] += {p};
  p = newp; Point(p) = {Ro, z, 0}; po[] += {p};
EndFor

// Radial lines on each node line.
For k In {0 : nz}
  For j In {0 : nin - 1}
    c = newc; Line(c) = {pin[k * (nin + 1) + j], pin[k * (nin + 1) + j + 1]}; rin[] += {c};
  EndFor
  c = newc; Line(c) = {pin[k * (nin + 1) + nin], pm[k]}; rme[] += {c};
  c = newc; Line(c) = {pm[k], po[k]}; rad[] += {c};
EndFor
Transfinite Curve{rin[]} = 2;
Transfinite Curve{rme[]} = nm + 1;
Transfinite Curve{rad[]} = na + 1;

// Axial lines of each column.
For k In {0 : nz - 1}
  For j In {0 : nin}
    c = newc; Line(c) = {pin[k * (nin + 1) + j], pin[(k + 1) * (nin + 1) + j]}; ain[] += {c};
  EndFor
  c = newc; Line(c) = {pm[k], pm[k + 1]}; ame[] += {c};
  c = newc; Line(c) = {po[k], po[k + 1]}; aad[] += {c};
EndFor
Transfinite Curve{ain[], ame[], aad[]} = 2;

// Cells: counter-clockwise loops in (r, z).
For k In {0 : nz - 1}
  For j In {0 : nin - 1}
    cl = newll;
    Curve Loop(cl) = {rin[k * nin + j], ain[k * (nin + 1) + j + 1], -rin[(k + 1) * nin + j], -ain[k * (nin + 1) + j]};
    s = news; Plane Surface(s) = {cl}; Transfinite Surface{s};
    rc = 0.25 * (rr[k * (nin + 1) + j] + rr[k * (nin + 1) + j + 1] + rr[(k + 1) * (nin + 1) + j] + rr[(k + 1) * (nin + 1) + j + 1]);
    If (rc < Ri)
      plaque[] += {s};
    Else
      intima[] += {s};
    EndIf
  EndFor
  cl = newll;
  Curve Loop(cl) = {rme[k], ame[k], -rme[k + 1], -ain[k * (nin + 1) + nin]};
  s = news; Plane Surface(s) = {cl}; Transfinite Surface{s}; media[] += {s};
  cl = newll;
  Curve Loop(cl) = {rad[k], aad[k], -rad[k + 1], -ame[k]};
  s = news; Plane Surface(s) = {cl}; Transfinite Surface{s}; adventitia[] += {s};
  lumen[] += {ain[k * (nin + 1)]};
EndFor
If (#plaque[] == 0)
  Error("Parameters/stenosis = %g: no cell of the innermost zone lies inside the healthy lumen (refine dz, nin)", stenosis);
EndIf

// Balloon: one structured surface.
mb = Round(0.5 * nz / L);  // columns in 0.5 mm
nbz = nz + 2 * mb + 1;
Lb = nbz * L / nz;
b = newp;
Point(b) = {Rb - tb, -Lb / 2, 0};
Point(b + 1) = {Rb, -Lb / 2, 0};
Point(b + 2) = {Rb, Lb / 2, 0};
Point(b + 3) = {Rb - tb, Lb / 2, 0};
c = newc;
Line(c) = {b, b + 1};          // lower end
Line(c + 1) = {b + 1, b + 2};  // outer line
Line(c + 2) = {b + 2, b + 3};  // upper end
Line(c + 3) = {b + 3, b};      // inner line
Transfinite Curve{c, c + 2} = nb + 1;
Transfinite Curve{c + 1, c + 3} = nbz + 1;
cl = newll;
Curve Loop(cl) = {c, c + 1, c + 2, c + 3};
sb = news;
Plane Surface(sb) = {cl};
Transfinite Surface{sb};

Physical Surface("plaque") = {plaque[]};
Physical Surface("intima") = {intima[]};
Physical Surface("media") = {media[]};
Physical Surface("adventitia") = {adventitia[]};
Physical Surface("balloon") = {sb};
Physical Curve("lumen") = {lumen[]};
Physical Curve("outer") = {aad[]};
Physical Curve("artery_ends") = {rin[{0 : nin - 1}], rme[0], rad[0],
                                 rin[{nz * nin : nz * nin + nin - 1}], rme[nz], rad[nz]};
Physical Curve("balloon_inner") = {c + 3};
Physical Curve("balloon_outer") = {c + 1};
Physical Curve("balloon_ends") = {c, c + 2};
