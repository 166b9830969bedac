// A gravity dam on a foundation cut by a joint below its heel (examples/04_dam_on_jointed_
// foundation), after Sun et al. 2022, example 4 (Zheng et al. 2002): foundation 25 m x 10 m,
// dam 5 m high, the joint from (4, 10) to (10, 4). Units: metres.
// Foundation: 0 <= x <= 25, 0 <= y <= 10.
Point(1) = {0, 0, 0};
Point(2) = {25, 0, 0};
Point(3) = {25, 10, 0};
Point(4) = {9, 10, 0};     // dam toe (downstream)
Point(5) = {3, 10, 0};     // dam heel (upstream)
Point(6) = {0, 10, 0};
// Dam: vertical upstream face, crest 2 m wide, downstream face 1.2 : 1.
Point(7) = {3, 15, 0};
Point(8) = {5, 15, 0};

Line(1) = {1, 2};   // foundation bottom: held
Line(2) = {2, 3};   // right side
Line(3) = {3, 4};   // downstream ground
Line(4) = {4, 5};   // dam base = foundation top under the dam (bonded)
Line(5) = {5, 6};   // reservoir floor (upstream ground)
Line(6) = {6, 1};   // left side
Line(7) = {5, 7};   // upstream face of the dam
Line(8) = {7, 8};   // crest
Line(9) = {8, 4};   // downstream face

Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {7, 8, 9, 4};
Plane Surface(2) = {2};

// The joint: a plain curve, not part of the surfaces; the cover mesher cuts the foundation
// along it. It starts on the dam base, 1 m downstream of the heel, and ends inside the rock.
Point(20) = {4, 10, 0};
Point(21) = {10, 4, 0};
Line(20) = {20, 21};

Physical Surface("foundation") = {1};
Physical Surface("dam") = {2};
Physical Curve("crack") = {20};                 // [joints.crack]
Physical Curve("bottom") = {1};                 // held in x and y
Physical Curve("sides") = {2, 6};               // held in x
Physical Curve("water") = {7, 5};               // upstream face and reservoir floor
Physical Point("crest") = {8};
