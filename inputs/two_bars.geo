// Two identical bars, L = 1 m long and H = 0.1 m high, 0.01 m apart along x (plane
// strain): the impact test of Carpenter, Taylor & Katona (1991).
// Physical groups: surfaces "left", "right"; curves "left_tip" (x = L, the left bar's
// front), "right_tip" (x = L + g, the right bar's front).
// n: elements along each bar (2 through the height). H2, y2: the right bar's height and
// the height of its base (default: identical bars face to face; the tests make the right
// bar taller for an oblique impact whose slave face stays on the master face).
L = 1.0; H = 0.1; g = 0.01;
n = DefineNumber[40, Name "Parameters/n"];
h = DefineNumber[0.05, Name "Parameters/h"];
H2 = DefineNumber[0.1, Name "Parameters/H2"];
y2 = DefineNumber[0, Name "Parameters/y2"];
Point(1) = {0, 0, 0, h};
Point(2) = {L, 0, 0, h};
Point(3) = {L, H, 0, h};
Point(4) = {0, H, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point(5) = {L + g, y2, 0, h};
Point(6) = {2 * L + g, y2, 0, h};
Point(7) = {2 * L + g, y2 + H2, 0, h};
Point(8) = {L + g, y2 + H2, 0, h};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
Transfinite Curve{1, 3, 5, 7} = n + 1;
Transfinite Curve{2, 4, 6, 8} = 3;
Transfinite Surface{1};
Transfinite Surface{2};
Physical Surface("left") = {1};
Physical Surface("right") = {2};
Physical Curve("left_tip") = {2};
Physical Curve("right_tip") = {8};
