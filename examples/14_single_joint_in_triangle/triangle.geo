// A triangular rock domain cut by a single joint (examples/14_single_joint_in_triangle),
// after Shi's Figure 9.1 ("single joint in a triangular shape domain"). Units: metres.
// An equilateral triangle with a 10 m base on y = 0 (held) and its apex at (5, 8.66); one
// straight joint dipping 30 degrees towards the right runs from the left face at y = 5 to
// the right face at y = 1.34, and on 0.3 m into the air at both ends. The joint is not
// part of the triangle's boundary: it is one Physical Curve across the one Physical
// Surface, and the cover mesher cuts the triangle into the wedge above it and the base
// below it.
base = 10;
dip = 30 * Pi / 180;
t = Tan(60 * Pi / 180);
Point(1) = {0, 0, 0};
Point(2) = {base, 0, 0};
Point(3) = {base / 2, base / 2 * t, 0};   // apex
Line(1) = {1, 2};   // base: held
Line(2) = {2, 3};   // right face
Line(3) = {3, 1};   // left face
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// The joint: through the left face at A = (5 / tan 60, 5), down at 30 degrees to the right
// face at B = (9.2265, 1.3397), 7.3205 m from A (README).
ax = 5 / t;
ay = 5;
bx = (base * t - ay - ax * Tan(dip)) / (t - Tan(dip));
extra = 0.3;
Point(10) = {ax - extra * Cos(dip), ay + extra * Sin(dip), 0};
Point(11) = {bx + extra * Cos(dip), ay - (bx - ax) * Tan(dip) - extra * Sin(dip), 0};
Line(10) = {10, 11};

Physical Surface("rock") = {1};
Physical Curve("joint") = {10};   // [joints.joint]: cuts the wedge off the base
Physical Curve("base") = {1};     // [[boundary]]: held in x and y
