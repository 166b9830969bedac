// A 16 m x 16 m block of rock with a 6 m tunnel (radius 3 m) at its centre, drawn as four
// quarter arcs; no mesh sizes (gmsh's default .msh of it makes the tunnel a 12-gon).
r = 3;
Point(1) = {0, 0, 0};
Point(2) = {16, 0, 0};
Point(3) = {16, 16, 0};
Point(4) = {0, 16, 0};
Point(5) = {8, 8, 0};
Point(6) = {8 + r, 8, 0};
Point(7) = {8, 8 + r, 0};
Point(8) = {8 - r, 8, 0};
Point(9) = {8, 8 - r, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Circle(5) = {6, 5, 7};
Circle(6) = {7, 5, 8};
Circle(7) = {8, 5, 9};
Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Surface("rock") = {1};
Physical Curve("base") = {1};
Physical Curve("tunnel") = {5, 6, 7, 8};
