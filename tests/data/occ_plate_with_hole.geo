// OpenCASCADE: a 2 x 1 plate minus a disk of radius 0.2 at (1, 0.5).
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 2, 1};
Disk(2) = {1, 0.5, 0, 0.2};
BooleanDifference(3) = {Surface{1}; Delete;}{Surface{2}; Delete;};
Physical Surface("plate") = {3};
Physical Curve("left") = {Curve In BoundingBox{-0.01, -0.01, -0.01, 0.01, 1.01, 0.01}};
Physical Curve("hole") = {Curve In BoundingBox{0.79, 0.29, -0.01, 1.21, 0.71, 0.01}};
