// A plate 0.079 × 0.005 × 0.03 m (x × y × z), built-in kernel, clamped at x = 0,
// wetted on y = 0. Lengths in metres.
lc = 0.004;
Point(1) = {0, 0, 0, lc};
Point(2) = {0.079, 0, 0, lc};
Point(3) = {0.079, 0.005, 0, lc};
Point(4) = {0, 0.005, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 0.03} { Surface{1}; };
// out[0]: top (z = 0.03), out[1]: volume, out[2..5]: sides on lines 1..4
Physical Surface("wetted") = {out[2]};   // y = 0 (from line 1)
Physical Surface("clamped") = {out[5]};  // x = 0 (from line 4)
Physical Volume("plate") = {out[1]};
