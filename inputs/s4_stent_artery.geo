// Scene S4 (talk: "stent in an arterial tissue"), axial section in plane strain: x is the
// artery axis, y the radial direction. Two artery walls (the section of a tube of inner
// radius Ri and thickness T, length L) are lined on their inner surfaces with a row of n
// circular stent strut sections (radius rs, pitch p, first centre at x0), which rest on
// the wall. The balloon is a rigid capsule (the deck's contact pair "balloon"), inserted along
// x, inflated and extracted. Lengths in m (the talk's scale, as in S1-S3).
// Physical groups: surfaces "artery", "stent"; curves "lumen" (the walls' inner
// surfaces), "adventitia" (outer surfaces), "artery_ends" (the four end edges),
// "strut_in" (the struts' faces towards the axis), "strut_out" (faces against the wall).
// h, hs and n may be set before this file is included (tests/cli/decks/par_s4.geo: a
// coarse variant with fewer struts).
If (!Exists(h))
  h = DefineNumber[0.1, Name "Parameters/h"];     // artery element size
EndIf
If (!Exists(hs))
  hs = DefineNumber[0.04, Name "Parameters/hs"];  // strut element size
EndIf
If (!Exists(n))
  n = DefineNumber[6, Name "Parameters/n"];       // struts per wall
EndIf
Ri = 1.0; T = 0.5; L = 8.0;
rs = 0.1; p = 1.0; x0 = 1.55;  // strut centres half a wall element (h / 2) off the wall's nodes
// Segments on the 120-degree arcs facing the wall and the axis: odd, so that a facet, not a
// node, faces each (a strut squeezed node-to-node rolls off it; docs/scenes/README.md, S4).
nseg = 2 * Floor(2 * Pi * rs / 3 / hs / 2) + 1;
ang[] = {Pi / 6, 5 * Pi / 6, 7 * Pi / 6, 11 * Pi / 6};

// Walls: j = 0 upper (y in [Ri, Ri + T]), j = 1 lower (mirror).
For j In {0 : 1}
  sg = 1 - 2 * j;
  a = newp;
  Point(a) = {0, sg * Ri, 0, h};
  Point(a + 1) = {L, sg * Ri, 0, h};
  Point(a + 2) = {L, sg * (Ri + T), 0, h};
  Point(a + 3) = {0, sg * (Ri + T), 0, h};
  c = newc;
  Line(c) = {a, a + 1};
  Line(c + 1) = {a + 1, a + 2};
  Line(c + 2) = {a + 2, a + 3};
  Line(c + 3) = {a + 3, a};
  lumen[] += {c};
  ends[] += {c + 1, c + 3};
  adv[] += {c + 2};
  cl = newll;
  If (sg > 0)
    Curve Loop(cl) = {c, c + 1, c + 2, c + 3};
  Else
    Curve Loop(cl) = {-(c + 3), -(c + 2), -(c + 1), -c};  // counter-clockwise below the axis too
  EndIf
  sf = news;
  Plane Surface(sf) = {cl};
  wall[] += {sf};
EndFor

// Struts: circular sections of radius rs, centres at distance Ri - rs from the axis, so
// that each strut touches its wall at one point. Each circle is split into four arcs: the
// 120-degree arc towards the wall ("strut_out"), the one towards the axis ("strut_in")
// and two 60-degree side arcs (in no group, so that the groups share no node).
For j In {0 : 1}
  sg = 1 - 2 * j;
  For k In {0 : n - 1}
    xc = x0 + k * p;
    yc = sg * (Ri - rs);
    a = newp;
    Point(a) = {xc, yc, 0, hs};
    For q In {0 : 3}  // points at 30, 150, 210, 330 degrees
      Point(a + 1 + q) = {xc + rs * Cos(ang[q]), yc + rs * Sin(ang[q]), 0, hs};
    EndFor
    c = newc;
    Circle(c) = {a + 1, a, a + 2};      // top (30 -> 150)
    Circle(c + 1) = {a + 2, a, a + 3};  // left (150 -> 210)
    Circle(c + 2) = {a + 3, a, a + 4};  // bottom (210 -> 330)
    Circle(c + 3) = {a + 4, a, a + 1};  // right (330 -> 30)
    Transfinite Curve{c, c + 2} = nseg + 1;
    If (sg > 0)
      sout[] += {c};
      sins[] += {c + 2};
    Else
      sout[] += {c + 2};
      sins[] += {c};
    EndIf
    cl = newll;
    Curve Loop(cl) = {c, c + 1, c + 2, c + 3};
    sf = news;
    Plane Surface(sf) = {cl};
    struts[] += {sf};
  EndFor
EndFor

Physical Surface("artery") = {wall[]};
Physical Surface("stent") = {struts[]};
Physical Curve("lumen") = {lumen[]};
Physical Curve("adventitia") = {adv[]};
Physical Curve("artery_ends") = {ends[]};
Physical Curve("strut_in") = {sins[]};
Physical Curve("strut_out") = {sout[]};
