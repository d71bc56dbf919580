// The rigid wall the gate hangs from (Antoci et al. 2007): a 5 mm thick block above the gate,
// x ∈ [0.1, 0.105], y ∈ [0.079, 0.2]; its lower face is the gate's clamped edge. The curves run
// so that the fluid is on their left (outward normals). Lengths in metres.
Point(1) = {0.1, 0.079, 0};
Point(2) = {0.1, 0.2, 0};
Point(3) = {0.105, 0.2, 0};
Point(4) = {0.105, 0.079, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
