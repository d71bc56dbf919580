// Cross-section of the stiffened wedge of paper §4.6 (Hosseinzadeh et al.), 2-D: a V of
// deadrise 25° and breadth 0.94 m closed by a deck at the chine height, all plates 10 mm thick
// (an equivalent thickness for the 4 mm plating and its T-stiffeners; README). The keel is at
// x = 0, y = 1.25 m (0.25 m above the still water at y = 1.0 m); the chines at x = ±0.47 m,
// y = 1.469165 m; the hollow inside is the deck-to-bottom space (the fluid sees only the
// outside: wedge_outer.geo). Lengths in metres.
Point(1) = {0, 1.25, 0};
Point(2) = {0.47, 1.469164599, 0};
Point(3) = {-0.47, 1.469164599, 0};
Point(4) = {0, 1.261033779, 0};
Point(5) = {0.424892915, 1.459164599, 0};
Point(6) = {-0.424892915, 1.459164599, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 4};
Curve Loop(1) = {1, 2, 3};
Curve Loop(2) = {4, 5, 6};
Plane Surface(1) = {1, 2};
