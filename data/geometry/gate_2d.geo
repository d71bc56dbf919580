// Elastic gate of Antoci et al. (2007), 2-D: 0.005 m thick (x) × 0.079 m high (y), clamped at
// the top edge; the faces x = 0 and x = 0.005 are wetted. Lengths in metres.
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 0.005, 0.079};
Physical Curve("clamped") = {3};      // y = 0.079
Physical Curve("wetted") = {2, 4};    // x = 0.005 and x = 0
Physical Surface("gate") = {1};
