// A rock slope with a tunnel and two joint sets, for `nmm mesh` (examples/02_jointed_slope).
// Units: metres. The joints are plain curves, not embedded in the surface: the cover mesher
// cuts the material with them wherever they lie inside it.

// Outline: base 80 m, toe at (50, 15), crest at (30, 40), 53 degree face.
Point(1) = {0, 0, 0};
Point(2) = {80, 0, 0};
Point(3) = {80, 15, 0};
Point(4) = {50, 15, 0};
Point(5) = {30, 40, 0};
Point(6) = {0, 40, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};

// A horseshoe-free circular tunnel of radius 3 m under the crest.
Point(10) = {18, 14, 0};
Point(11) = {21, 14, 0};
Point(12) = {18, 17, 0};
Point(13) = {15, 14, 0};
Point(14) = {18, 11, 0};
Circle(10) = {11, 10, 12};
Circle(11) = {12, 10, 13};
Circle(12) = {13, 10, 14};
Circle(13) = {14, 10, 11};
Curve Loop(2) = {10, 11, 12, 13};
Plane Surface(1) = {1, 2};

// Bedding: dipping 20 degrees out of the slope. The upper two run out of the rock on both
// sides; the lower ones end inside it (partial joints, crack tips).
b = Tan(20 * Pi / 180);
Point(100) = {-5, 44 + 5 * b, 0};   Point(101) = {60, 44 - 60 * b, 0};
Point(102) = {-5, 36 + 5 * b, 0};   Point(103) = {70, 36 - 70 * b, 0};
Point(104) = {6, 28 - 6 * b, 0};    Point(105) = {48, 28 - 48 * b, 0};
Point(106) = {25, 22 - 25 * b, 0};  Point(107) = {62, 22 - 62 * b, 0};
Point(108) = {35, 8 - 35 * b, 0};   Point(109) = {85, 8 - 85 * b, 0};
Line(100) = {100, 101};
Line(101) = {102, 103};
Line(102) = {104, 105};
Line(103) = {106, 107};
Line(104) = {108, 109};

// Cross joints: steep (70 degrees), short, some crossing the bedding, one ending in the
// tunnel's crown region.
c = 1 / Tan(70 * Pi / 180);
Point(200) = {30, 42, 0};  Point(201) = {30 + 16 * c, 26, 0};
Point(202) = {40, 36, 0};  Point(203) = {40 + 22 * c, 14, 0};
Point(204) = {12, 30, 0};  Point(205) = {12 + 12 * c, 18, 0};
Point(206) = {60, 16, 0};  Point(207) = {60 + 12 * c, 4, 0};
Point(208) = {24, 26, 0};  Point(209) = {24 + 7 * c, 19, 0};
Line(200) = {200, 201};
Line(201) = {202, 203};
Line(202) = {204, 205};
Line(203) = {206, 207};
Line(204) = {208, 209};

Physical Surface("rock") = {1};
Physical Curve("bedding") = {100, 101, 102, 103, 104};
Physical Curve("cross") = {200, 201, 202, 203, 204};
Physical Curve("base") = {1};
Physical Curve("face") = {4};
Physical Curve("tunnel") = {10, 11, 12, 13};
Physical Point("crest") = {5};
