// A joint drawn inside a surface as a plain curve: not embedded ("In Surface") on purpose.
Point(1) = {0, 0, 0};
Point(2) = {4, 0, 0};
Point(3) = {4, 2, 0};
Point(4) = {0, 2, 0};
Point(5) = {1, 0.5, 0};
Point(6) = {3, 1.5, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("rock") = {1};
Physical Curve("joint") = {5};
