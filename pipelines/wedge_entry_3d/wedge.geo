// The stiffened wedge of paper §4.6 (Hosseinzadeh et al.), 3-D, coarse: a prism 1.5 m long
// (y) of the 2-D section of ../wedge_entry (V of deadrise 25°, breadth 0.94 m, closed by a deck
// at the chine height 0.219 m), hollow, all plates and the two end plates 20 mm of
// aluminium (an equivalent thickness at this coarse resolution; README). Keel along
// x = 0, z = 0.85 m (0.25 m above the still water at z = 0.6 m). Lengths in metres.
SetFactory("OpenCASCADE");
Point(1) = {0, -0.75, 0.85};
Point(2) = {0.47, -0.75, 1.069164599};
Point(3) = {-0.47, -0.75, 1.069164599};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
outer[] = Extrude {0, 1.5, 0} { Surface{1}; };
Point(11) = {0, -0.73, 0.872067558};
Point(12) = {0.379785830, -0.73, 1.049164599};
Point(13) = {-0.379785830, -0.73, 1.049164599};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 11};
Curve Loop(11) = {11, 12, 13};
Plane Surface(11) = {11};
inner[] = Extrude {0, 1.46, 0} { Surface{11}; };
BooleanDifference{ Volume{outer[1]}; Delete; }{ Volume{inner[1]}; Delete; }
