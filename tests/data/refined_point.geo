// A 10 m square whose mesh a size field refines to 0.1 m within 0.5 m of the point (2, 2)
// and grades to 1 m at 4 m from it (the point is not on any curve: as at a crack tip).
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {10, 10, 0};
Point(4) = {0, 10, 0};
Point(5) = {2, 2, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {5};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.1;
Field[2].SizeMax = 1.0;
Field[2].DistMin = 0.5;
Field[2].DistMax = 4.0;
Background Field = 2;
Physical Surface("rock") = {1};
