// The wetted outside of the wedge of wedge.geo (the fluid's wall "structure", fsi-map's target):
// the two bottom faces and the deck, meshed at map.mesh_size. The loop runs clockwise round the
// wedge so that the normal (the left side of each curve) points out of it, into the fluid.
Point(1) = {0, 1.25, 0};
Point(2) = {-0.47, 1.469164599, 0};
Point(3) = {0.47, 1.469164599, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
