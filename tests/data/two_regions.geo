// Two regions of the square [0,2]x[0,2] separated by a circular arc from (0,1) to (2,1)
// (centre (1,-1)) that both surfaces share, and that is also a Physical Curve.
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {2, 2, 0};
Point(5) = {0, 2, 0};
Point(6) = {0, 1, 0};
Point(7) = {1, -1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Circle(3) = {6, 7, 3};
Line(4) = {6, 1};
Line(5) = {3, 4};
Line(6) = {4, 5};
Line(7) = {5, 6};
Curve Loop(1) = {1, 2, -3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {3, 5, 6, 7};
Plane Surface(2) = {2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("interface") = {3};
