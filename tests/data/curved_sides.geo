// A region bounded by straight lines below, two ellipse arcs on the right, a B-spline on top
// and a Catmull-Rom spline on the left: general curves for the adaptive sampling.
Point(1) = {0, 0, 0};
Point(2) = {4, 0, 0};
Point(3) = {4, 2, 0};
Point(4) = {0, 2, 0};
Point(5) = {3, 2.8, 0};
Point(6) = {1, 1.2, 0};
Point(7) = {2, 0, 0};
Point(8) = {4.5, 1, 0};
Point(9) = {-0.4, 1.3, 0};
Point(10) = {-0.2, 0.6, 0};
Point(11) = {4, 1, 0};
Line(1) = {1, 7};
Line(2) = {7, 2};
Ellipse(3) = {2, 11, 3, 8};
Ellipse(4) = {8, 11, 3, 3};
BSpline(5) = {3, 5, 6, 4};
Spline(6) = {4, 9, 10, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Surface("rock") = {1};
Physical Curve("top") = {5};
Physical Curve("bottom") = {1, 2};
