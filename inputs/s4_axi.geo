// Scene S4-axi: the talk's stent-artery procedure as a meridian section for
// Problem->kinematics = axisymmetric (docs/axisymmetric.md): x = r, y = z (the axis of
// revolution), lengths in mm. A straight coronary artery (inner radius Ri, wall T, length
// L, centred on z = 0) and a coil stent whose n wire turns are rings of square section w x w
// (pitch p, centred on z = 0), crimped at inner radius rc on the rigid balloon (the deck's
// capsule "balloon").
// Physical groups: surfaces "artery", "stent"; curves "lumen" (r = Ri), "adventitia"
// (r = Ri + T), "artery_ends" (z = +-L/2), "strut_in" (the rings' faces towards the axis),
// "strut_out" (their faces towards the wall); the rings' end faces are in no group, so that
// the two stent groups share no node.
// h (lumen), ho (adventitia), hs (stent) and n may be set before this file is included
// (tests/cli/decks/s4_axi_coarse.geo).
If (!Exists(h))
  h = DefineNumber[0.05, Name "Parameters/h"];    // artery element size at the lumen
EndIf
If (!Exists(ho))
  ho = DefineNumber[0.15, Name "Parameters/ho"];  // at the adventitia and the far ends
EndIf
If (!Exists(ns))
  ns = DefineNumber[4, Name "Parameters/ns"];     // cells along each side of a wire section
EndIf
If (!Exists(n))
  n = DefineNumber[8, Name "Parameters/n"];       // wire turns (rings)
EndIf
Ri = 1.5; T = 0.75; L = 8.0;
w = 0.1; p = 0.5; rc = 1.35;

// Artery wall: the lumen line carries points at the stent's ends so that its fine size h
// spans the stent, and the size grows to ho towards the far ends and the adventitia.
zs = 0.5 * ((n - 1) * p + w) + 0.5;  // the fine span: the stent and 0.5 mm beyond
Point(1) = {Ri, -L / 2, 0, ho};
Point(2) = {Ri, -zs, 0, h};
Point(3) = {Ri, zs, 0, h};
Point(4) = {Ri, L / 2, 0, ho};
Point(5) = {Ri + T, L / 2, 0, ho};
Point(6) = {Ri + T, -L / 2, 0, ho};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};  // top end
Line(5) = {5, 6};  // adventitia
Line(6) = {6, 1};  // bottom end
Curve Loop(1) = {-6, -5, -4, -3, -2, -1};  // counter-clockwise in (r, z)
Plane Surface(1) = {1};

// Wire turns: squares [rc, rc + w] x [zc - w/2, zc + w/2], structured ns x ns.
For k In {0 : n - 1}
  zc = (k - 0.5 * (n - 1)) * p;
  a = newp;
  Point(a) = {rc, zc - w / 2, 0, w / ns};
  Point(a + 1) = {rc + w, zc - w / 2, 0, w / ns};
  Point(a + 2) = {rc + w, zc + w / 2, 0, w / ns};
  Point(a + 3) = {rc, zc + w / 2, 0, w / ns};
  c = newc;
  Line(c) = {a, a + 1};          // lower end face
  Line(c + 1) = {a + 1, a + 2};  // outer face (towards the wall)
  Line(c + 2) = {a + 2, a + 3};  // upper end face
  Line(c + 3) = {a + 3, a};      // inner face (towards the axis)
  Transfinite Curve{c, c + 1, c + 2, c + 3} = ns + 1;
  cl = newll;
  Curve Loop(cl) = {c, c + 1, c + 2, c + 3};
  sf = news;
  Plane Surface(sf) = {cl};
  Transfinite Surface{sf};
  sout[] += {c + 1};
  sins[] += {c + 3};
  wires[] += {sf};
EndFor

Physical Surface("artery") = {1};
Physical Surface("stent") = {wires[]};
Physical Curve("lumen") = {1, 2, 3};
Physical Curve("adventitia") = {5};
Physical Curve("artery_ends") = {4, 6};
Physical Curve("strut_in") = {sins[]};
Physical Curve("strut_out") = {sout[]};
