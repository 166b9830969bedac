// A rock slope whose upper part slides on a bedding joint, cut into five blocks by cross
// joints (examples/08_multi_block_slope), after Shi's Figure 9.5 ("slope sliding of rock
// blocks"). Units: metres. The valley is on the right: the slope face dips 60 degrees
// towards it from the crest (y = 20) to the toe (30, 5); the bedding dips 30 degrees the
// same way and daylights on the face at y = 8; four cross joints, normal to the bedding,
// cut the mass above it into five blocks.
Point(1) = {0, 0, 0};
Point(2) = {45, 0, 0};
Point(3) = {45, 5, 0};
Point(4) = {30, 5, 0};                          // toe
Point(5) = {30 - 15 / Tan(60 * Pi / 180), 20, 0}; // crest
Point(6) = {0, 20, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

// Bedding: from 0.5 m out of the face (in the air) through the daylight point up to 0.5 m
// above the top surface, in segments that meet the cross joints at shared points, so that
// each cross joint ends exactly on it (a T junction: a joint that stopped short would leave
// the blocks joined).
xb = 30 - 3 / Tan(60 * Pi / 180);   // where the bedding daylights on the face, y = 8
c = Cos(30 * Pi / 180);
s = Sin(30 * Pi / 180);
Point(10) = {xb + 0.5 * c, 8 - 0.5 * s, 0};
For k In {1:4}
  Point(20 + 2 * k) = {xb - 4.8 * k * c, 8 + 4.8 * k * s, 0};   // 4.8 k m up the bedding
EndFor
Point(11) = {xb - 25 * c, 8 + 25 * s, 0};   // past the top surface (reached at 24 m)
Line(10) = {10, 22};
Line(11) = {22, 24};
Line(12) = {24, 26};
Line(13) = {26, 28};
Line(14) = {28, 11};

// Cross joints: normal to the bedding (up and towards the valley at 60 degrees), from the
// bedding through the face (the lower two) or the top surface (the upper two), 9 m long so
// that each ends in the air.
For k In {1:4}
  Point(21 + 2 * k) = {xb - 4.8 * k * c + 9 * s, 8 + 4.8 * k * s + 9 * c, 0};
  Line(20 + k) = {20 + 2 * k, 21 + 2 * k};
EndFor

Physical Surface("rock") = {1};
Physical Curve("bedding") = {10, 11, 12, 13, 14};
Physical Curve("cross") = {21, 22, 23, 24};
Physical Curve("base") = {1};
Physical Curve("sides") = {2, 6};
