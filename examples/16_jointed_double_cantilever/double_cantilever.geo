// Two cantilevers on top of each other (examples/16_jointed_double_cantilever), after Shi's
// Figure 9.8 ("deformation of jointed double cantilever beams"). Units: metres. One beam
// 10 m long and 1 m deep, its axis on y = 0, held at x = 0 and loaded on its top face; a
// frictionless joint along the axis, 0.2 m into the air past both ends, splits it into two
// layers 0.5 m deep that slide on each other.
L = 10.0;  // length
c = 0.5;   // half depth = depth of one layer
Point(1) = {0, -c, 0};
Point(2) = {L, -c, 0};
Point(3) = {L, c, 0};
Point(4) = {0, c, 0};
Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // free end, x = L
Line(3) = {3, 4};  // top: loaded
Line(4) = {4, 1};  // fixed end, x = 0
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// The joint between the layers, along y = 0.
Point(10) = {-0.2, 0, 0};
Point(11) = {L + 0.2, 0, 0};
Line(10) = {10, 11};

Physical Surface("beam") = {1};
Physical Curve("layers") = {10};      // [joints.layers]: splits the beam into two layers
Physical Curve("fixed_end") = {4};    // [[boundary]]
Physical Curve("top") = {3};          // [[load]]: the uniform load on the upper layer
