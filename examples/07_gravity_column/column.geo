// A rock column 1 m wide and 10 m high under its own weight (examples/07_gravity_column).
// It stands on a smooth base (a roller) between two smooth walls (rollers): the state of a
// column cut out of a wide layer, where the ground cannot expand sideways. Units: metres.
W = 1.0;   // width
H = 10.0;  // height
Point(1) = {0, 0, 0};
Point(2) = {W, 0, 0};
Point(3) = {W, H, 0};
Point(4) = {0, H, 0};
Line(1) = {1, 2};  // base: a roller (held in y)
Line(2) = {2, 3};  // right side: a roller (held in x)
Line(3) = {3, 4};  // top: free
Line(4) = {4, 1};  // left side: a roller (held in x)
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Surface("column") = {1};   // [materials.column]
Physical Curve("base") = {1};       // [[boundary]] fix = "y"
Physical Curve("sides") = {2, 4};   // [[boundary]] fix = "x"
