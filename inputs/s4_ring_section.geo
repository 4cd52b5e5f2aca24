// Scene S4, cross-section variant (plane strain): a closed zig-zag stent ring, crimped,
// inside an artery annulus; a rigid circular balloon at the centre (the deck's contact pair
// "balloon") inflates radially, unfolds the ring against the wall, and deflates.
// Lengths in m at the talk's scale (as S1-S4); the artery wall is the axial S4's
// (inner radius Ri = 1, thickness T = 0.5).
//
// Stent: the strut's centre line is r(th) = Rm + a cos(N th) (N crowns towards the wall,
// N towards the axis), and the strut has the width w measured along the centre line's
// normal (both faces are the centre line offset by +-w/2 along its normal, so the strut
// is equally thick on the crowns and the straight legs). With the defaults the crimped
// ring spans r = 0.54 ... 0.90 and its centre line is 7.09 long: fully straightened it
// would be a circle of radius 1.13, so the ring can open the lumen by up to ~15%.
// The offset stays free of cusps while w/2 is below the centre line's smallest radius
// of curvature (0.032 at the inner crowns with the defaults).
//
// Physical groups: surfaces "artery", "stent"; curves "lumen" (the artery's inner circle),
// "adventitia" (outer circle), "stent_in" (the ring's face towards the axis), "stent_out"
// (the face towards the wall); points "pins_x" (where the outer circle crosses the y axis)
// and "pins_y" (where it crosses the x axis): a deck fixes x at the first and y at the
// second to remove the artery's rigid-body modes without resisting its radial expansion.
h  = DefineNumber[0.1,  Name "Parameters/h"];    // artery element size
w  = DefineNumber[0.04, Name "Parameters/w"];    // strut width
hs = DefineNumber[0.02, Name "Parameters/hs"];   // stent element size (w/2: two P2 cells across)
N  = DefineNumber[8,    Name "Parameters/N"];    // crowns on each side
Rm = DefineNumber[0.72, Name "Parameters/Rm"];   // mean radius of the crimped ring
a  = DefineNumber[0.16, Name "Parameters/a"];    // crown amplitude
Ri = 1.0; T = 0.5;
M = 24 * N;                                       // spline points per face

// Artery annulus.
o = newp;
Point(o) = {0, 0, 0, h};
For q In {0 : 3}
  Point(o + 1 + q) = {(Ri + T) * Cos(q * Pi / 2), (Ri + T) * Sin(q * Pi / 2), 0, h};
  Point(o + 5 + q) = {Ri * Cos(q * Pi / 2), Ri * Sin(q * Pi / 2), 0, h};
EndFor
c = newc;
For q In {0 : 3}
  Circle(c + q) = {o + 1 + q, o, o + 1 + (q + 1) % 4};
  Circle(c + 4 + q) = {o + 5 + q, o, o + 5 + (q + 1) % 4};
EndFor
lo = newll;
Curve Loop(lo) = {c, c + 1, c + 2, c + 3};
li = newll;
Curve Loop(li) = {c + 4, c + 5, c + 6, c + 7};
art = news;
Plane Surface(art) = {lo, li};

// Stent faces: the centre line offset by -+w/2 along its unit normal (outward).
pin[] = {};
pout[] = {};
For i In {0 : M - 1}
  th = 2 * Pi * i / M;
  r = Rm + a * Cos(N * th);
  dr = -a * N * Sin(N * th);
  tx = dr * Cos(th) - r * Sin(th);
  ty = dr * Sin(th) + r * Cos(th);
  tl = Sqrt(tx * tx + ty * ty);
  nx = ty / tl;
  ny = -tx / tl;
  p = newp;
  Point(p) = {r * Cos(th) - 0.5 * w * nx, r * Sin(th) - 0.5 * w * ny, 0, hs};
  pin[] += {p};
  Point(p + 1) = {r * Cos(th) + 0.5 * w * nx, r * Sin(th) + 0.5 * w * ny, 0, hs};
  pout[] += {p + 1};
EndFor
si = newc;
Spline(si) = {pin[], pin[0]};
so = newc;
Spline(so) = {pout[], pout[0]};
lso = newll;
Curve Loop(lso) = {so};
lsi = newll;
Curve Loop(lsi) = {si};
st = news;
Plane Surface(st) = {lso, lsi};

Physical Surface("artery") = {art};
Physical Surface("stent") = {st};
Physical Curve("lumen") = {c + 4, c + 5, c + 6, c + 7};
Physical Curve("adventitia") = {c, c + 1, c + 2, c + 3};
Physical Curve("stent_in") = {si};
Physical Curve("stent_out") = {so};
Physical Point("pins_x") = {o + 2, o + 4};
Physical Point("pins_y") = {o + 1, o + 3};
