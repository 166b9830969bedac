// A road cut through a jointed rock mass (examples/18_road_cut_joint_sets). Units: metres.
// The ground is at y = 20 on the left; the cut face dips 63.4 degrees towards the road, from
// the crest (20, 20) down to the toe (26, 8); the road runs at y = 8 to x = 40; the base is
// at y = 0. No joint is drawn: the case file's two [[joint_set]] tables generate them.
Point(1) = {0, 0, 0};
Point(2) = {40, 0, 0};
Point(3) = {40, 8, 0};
Point(4) = {26, 8, 0};   // toe
Point(5) = {20, 20, 0};  // crest
Point(6) = {0, 20, 0};
Line(1) = {1, 2};        // base
Line(2) = {2, 3};        // right side
Line(3) = {3, 4};        // road
Line(4) = {4, 5};        // face
Line(5) = {5, 6};        // ground
Line(6) = {6, 1};        // left side
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Surface("rock") = {1};
Physical Curve("base") = {1};
Physical Curve("sides") = {2, 6};
