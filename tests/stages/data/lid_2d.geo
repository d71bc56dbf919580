// A lid across the 2-D test tank at y = 0.145 m, normal down (into the tank): the fluid side is
// below it. Lengths in metres.
Point(1) = {0.2, 0.145, 0};
Point(2) = {0.0, 0.145, 0};
Line(1) = {1, 2};
