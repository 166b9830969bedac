// The rotating triangular block of Luo et al. 2021, section 5.1, Figure 6a
// (examples/10_rotating_triangle). Units: metres.
//
// A triangular block (points 5, 6, 7) stands on a rectangular foundation (points 1, 2, 3, 4);
// a horizontal point load P at the apex, point 5, tips it clockwise about its right-hand
// corner, point 7, which stays in contact with the foundation's top edge, "edge 14".
// The gmsh point tags are the paper's point numbers. The paper gives no dimensions (its
// figure is not available): the sizes below are assumed (README.md, "Assumed"); the
// triangle is sized so that its angular acceleration about point 7 under P, 21.4 rad/s^2,
// matches the per-step rotations r0 of Table 1 (about 0.00215 rad more each step of 0.01 s).
//
// Foundation: 3.0 m x 0.5 m, its top edge 1-4 at y = 0.
Point(1) = {0.0, 0.0, 0};      // top left      (edge 14 runs from 1 to 4)
Point(2) = {0.0, -0.5, 0};     // bottom left
Point(3) = {3.0, -0.5, 0};     // bottom right
Point(4) = {3.0, 0.0, 0};      // top right
// Triangle: isosceles, base 0.9 m on the foundation (6-7), height 0.9 m, apex 5 above the
// middle of the base. Counter-clockwise 5, 6, 7 as in DDA's numbering.
Point(5) = {1.5, 0.9, 0};      // apex: the load P acts here
Point(6) = {1.05, 0.0, 0};     // bottom left corner of the block
Point(7) = {1.95, 0.0, 0};     // bottom right corner: the pivot, in contact with edge 14

Line(1) = {1, 2};   // foundation: left side (held)
Line(2) = {2, 3};   // foundation: underside (held)
Line(3) = {3, 4};   // foundation: right side (held)
Line(4) = {4, 7};   // edge 14, right of the block
Line(5) = {7, 6};   // edge 14 under the block = the block's base: the joint "block_base"
Line(6) = {6, 1};   // edge 14, left of the block
Line(7) = {7, 5};   // block: right side
Line(8) = {5, 6};   // block: left side

Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-5, 7, 8};
Plane Surface(2) = {2};

Physical Surface("foundation") = {1};
Physical Surface("block") = {2};
Physical Curve("block_base") = {5};     // [joints.block_base]: cuts the block off the foundation
Physical Curve("base") = {2};           // [[boundary]]: the foundation is held on its underside
Physical Curve("sides") = {1, 3};       // ... and on its two ends, so all of 1, 2, 3, 4 are fixed
Physical Point("point5") = {5};         // [[load]]: P = 10 kN, horizontal
Physical Point("point7") = {7};         // the contact vertex of Table 1 (monitored in case.toml)
