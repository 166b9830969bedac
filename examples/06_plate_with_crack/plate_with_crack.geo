// A plate with a central crack, pulled across the crack (examples/06_plate_with_crack).
// The whole plate is 2 m x 2 m with a crack 2a = 0.2 m long on y = 0 at its centre, ten
// crack lengths wide. By symmetry only its right half, x >= 0, is drawn: the plate's
// vertical centre line is held by rollers. The crack, from (0, 0) to (a, 0), is a plain curve
// named as a joint: it cuts the plate only along its length and ends inside it at the crack
// tip (a, 0). Units: metres.
a = 0.1;   // half-length of the crack
b = 1.0;   // half width and half height of the plate
Point(1) = {0, -b, 0};
Point(2) = {b, -b, 0};
Point(3) = {b,  b, 0};
Point(4) = {0,  b, 0};
Line(1) = {1, 2};  // bottom: pulled down
Line(2) = {2, 3};  // right: free
Line(3) = {3, 4};  // top: pulled up
Line(4) = {4, 1};  // the plate's centre line x = 0: rollers
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// The crack: not embedded in the surface; the cover mesher cuts the plate along it.
Point(10) = {0, 0, 0};
Point(11) = {a, 0, 0};
Line(10) = {10, 11};

// A point on the right edge, level with the crack, holds the vertical rigid motion (by
// symmetry about y = 0 it carries no force).
Point(20) = {b, 0, 0};

Physical Surface("plate") = {1};     // [materials.plate]
Physical Curve("crack") = {10};      // [joints.crack]
Physical Curve("bottom") = {1};      // [[load]] traction (0, -s)
Physical Curve("top") = {3};         // [[load]] traction (0, s)
Physical Curve("centre") = {4};      // [[boundary]] fix = "x"
Physical Point("side") = {20};       // [[boundary]] fix = "y"
