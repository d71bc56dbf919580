// An open 2-D tank 1.0 × 0.6 m: bottom and two sides, normals into the fluid (the curves run
// so that the fluid is on their left). Lengths in metres.
Point(1) = {0, 0.6, 0};
Point(2) = {0, 0, 0};
Point(3) = {1.0, 0, 0};
Point(4) = {1.0, 0.6, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Physical Curve("bottom") = {2};
Physical Curve("sides") = {1, 3};
