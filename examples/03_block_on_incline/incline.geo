// A 1.0 m x 0.5 m block on a 45 degree ramp (examples/03_block_on_incline). Units: metres.
// The ramp is a band 0.5 m thick and 8.5 m long, held along its underside; the block sits
// 6.4 m up the slope. The block's underside is the joint "slip": the block and the ramp are
// one gmsh geometry, cut apart by the joint.
s = Sqrt(0.5);           // cos 45 = sin 45
// Ramp: from (0, 0) up to (6, 6), 0.5 m thick below that line.
Point(1) = {0, 0, 0};
Point(2) = {0.5 * s, -0.5 * s, 0};
Point(3) = {6 + 0.5 * s, 6 - 0.5 * s, 0};
Point(4) = {6, 6, 0};
// Block: its underside from (4.5, 4.5) to (4.5, 4.5) + 1.0 along the slope.
Point(5) = {4.5, 4.5, 0};
Point(6) = {4.5 + s, 4.5 + s, 0};
Point(7) = {4.5 + s - 0.5 * s, 4.5 + s + 0.5 * s, 0};
Point(8) = {4.5 - 0.5 * s, 4.5 + 0.5 * s, 0};

Line(1) = {1, 2};   // lower end of the ramp
Line(2) = {2, 3};   // underside of the ramp: held
Line(3) = {3, 4};   // upper end
Line(4) = {4, 6};   // ramp surface above the block
Line(5) = {6, 5};   // the block's underside = the ramp surface under it: the joint
Line(6) = {5, 1};   // ramp surface below the block
Line(7) = {6, 7};   // block: upper side
Line(8) = {7, 8};   // block: top
Line(9) = {8, 5};   // block: lower side

Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-5, 7, 8, 9};
Plane Surface(2) = {2};

Physical Surface("ramp") = {1};
Physical Surface("block") = {2};
Physical Curve("slip") = {5};       // [joints.slip]: friction between block and ramp
Physical Curve("base") = {2};       // [[boundary]]: the ramp is held here
