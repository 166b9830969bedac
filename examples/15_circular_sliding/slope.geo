// A slope that slides on a circular slip surface (examples/15_circular_sliding), after
// Shi's Figure 9.6 ("circular sliding"). Units: metres. The valley is on the right: the
// ground is 15 m high on the left (y = 0 to 15), the slope face drops from the crest
// (14, 15) to the toe (22, 5), and the valley floor runs at y = 5 to x = 40. The slip
// surface is the circle of radius R about O = (20, 30) through the toe, from the toe up to
// where it meets the top surface at C = (20 - sqrt(R^2 - 15^2), 15) = (-0.0998, 15); it is
// drawn as a polyline of n = 101 chords with their ends on the circle (0.25 m long), plus
// one chord into the air past each end. limit_equilibrium.py uses the same polygon.
xo = 20;
yo = 30;
xt = 22;   // toe
yt = 5;
R = Sqrt((xt - xo)^2 + (yt - yo)^2);
xc = xo - Sqrt(R^2 - (15 - yo)^2);
n = 101;

Point(1) = {-10, 0, 0};
Point(2) = {40, 0, 0};
Point(3) = {40, 5, 0};
Point(4) = {xt, yt, 0};   // toe
Point(5) = {14, 15, 0};   // crest
Point(6) = {-10, 15, 0};
Line(1) = {1, 2};   // base: held
Line(2) = {2, 3};   // right side: rollers
Line(3) = {3, 4};   // valley floor
Line(4) = {4, 5};   // slope face
Line(5) = {5, 6};   // top surface
Line(6) = {6, 1};   // left side: rollers
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

// The slip surface: angles from O, from C (about 216.7 degrees) to the toe (274.6 degrees).
a0 = Atan2(15 - yo, xc - xo);
If (a0 < 0)
  a0 += 2 * Pi;
EndIf
a1 = Atan2(yt - yo, xt - xo) + 2 * Pi;
da = (a1 - a0) / n;
For k In {-1:n+1}
  p = newp;
  Point(p) = {xo + R * Cos(a0 + k * da), yo + R * Sin(a0 + k * da), 0};
  arc[k + 1] = p;
EndFor
For k In {0:n+1}
  l = newl;
  Line(l) = {arc[k], arc[k + 1]};
  chord[k] = l;
EndFor

Physical Surface("soil") = {1};
Physical Curve("slip") = {chord[]};   // [joints.slip]: cuts the sliding mass off the ground
Physical Curve("base") = {1};
Physical Curve("sides") = {2, 6};
