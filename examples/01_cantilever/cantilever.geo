// A cantilever beam, 10 m long and 2 m deep, its axis on y = 0 (examples/01_cantilever).
// Fixed at x = 0, loaded by an end shear at x = 10. Units: metres.
L = 10.0;  // length
c = 1.0;   // half depth
Point(1) = {0, -c, 0};
Point(2) = {L, -c, 0};
Point(3) = {L,  c, 0};
Point(4) = {0,  c, 0};
Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // loaded end, x = L
Line(3) = {3, 4};  // top
Line(4) = {4, 1};  // fixed end, x = 0
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Surface("beam") = {1};      // the material: [materials.beam]
Physical Curve("fixed_end") = {4};   // [[boundary]] curve = "fixed_end"
Physical Curve("loaded_end") = {2};  // [[load]] curve = "loaded_end"
