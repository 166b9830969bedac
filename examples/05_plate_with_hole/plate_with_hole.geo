// A quarter of a square plate with a circular hole at its centre, pulled along x
// (examples/05_plate_with_hole). The hole has radius a = 0.1 m; the whole plate would be
// 4 m x 4 m, twenty hole diameters wide. By symmetry only x >= 0, y >= 0 is drawn: the plate's
// centre lines are held by rollers. Units: metres.
a = 0.1;   // hole radius
b = 2.0;   // half width of the whole plate
Point(1) = {0, 0, 0};      // the hole's centre (only for the arc)
Point(2) = {a, 0, 0};      // the hole's side: hoop stress -s
Point(3) = {b, 0, 0};
Point(4) = {b, b, 0};
Point(5) = {0, b, 0};
Point(6) = {0, a, 0};      // the hole's top: hoop stress 3 s
Line(1) = {2, 3};          // bottom: on the centre line y = 0, a roller
Line(2) = {3, 4};          // right: pulled
Line(3) = {4, 5};          // top: free
Line(4) = {5, 6};          // left: on the centre line x = 0, a roller
Circle(5) = {6, 1, 2};     // the quarter of the hole
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

Physical Surface("plate") = {1};    // [materials.plate]
Physical Curve("bottom") = {1};     // [[boundary]] fix = "y"
Physical Curve("left") = {4};       // [[boundary]] fix = "x"
Physical Curve("right") = {2};      // [[load]] traction along x
Physical Curve("hole") = {5};
