// A semicircular arch of 11 voussoirs on a base slab (examples/09_block_arch). Units: metres.
// Centreline radius 2 m, thickness 0.4 m (t/R = 0.2): intrados radius 1.8 m, extrados
// 2.2 m, centre at the origin. The voussoirs have straight faces (trapezoids) between the
// radial joints k = 0 .. 11 at 180 k / 11 degrees from the right springing; joints 0 and
// 11 are the springings, where the arch stands on the slab. The arch is one gmsh geometry
// with the slab: the Physical Curve "joints" (all twelve radial lines) cuts it into blocks.
n = 11;
ri = 1.8;
re = 2.2;

// Joint k from its intrados point inner[k] to its extrados point outer[k]; the springings lie
// exactly on y = 0 (Sin(Pi) is not 0 in floating point).
For k In {0:n}
  a = Pi * k / n;
  x = Cos(a);
  y = Sin(a);
  If (k == 0 || k == n)
    y = 0;
  EndIf
  inner[k] = newp; Point(inner[k]) = {ri * x, ri * y, 0};
  outer[k] = newp; Point(outer[k]) = {re * x, re * y, 0};
  joint[k] = newl; Line(joint[k]) = {inner[k], outer[k]};
EndFor

// Voussoir b between joints b and b + 1: extrados and intrados faces.
For b In {0:n-1}
  top[b] = newl; Line(top[b]) = {outer[b], outer[b + 1]};
  bottom[b] = newl; Line(bottom[b]) = {inner[b + 1], inner[b]};
  loop = newll; Curve Loop(loop) = {joint[b], top[b], -joint[b + 1], bottom[b]};
  voussoir[b] = news; Plane Surface(voussoir[b]) = {loop};
EndFor

// The base slab, 6 m x 0.4 m under the arch; its top runs through the springings.
p1 = newp; Point(p1) = {-3.0, -0.4, 0};
p2 = newp; Point(p2) = {3.0, -0.4, 0};
p3 = newp; Point(p3) = {3.0, 0, 0};
p4 = newp; Point(p4) = {-3.0, 0, 0};
ground = newl; Line(ground) = {p1, p2};
right = newl; Line(right) = {p2, p3};
outside_right = newl; Line(outside_right) = {p3, outer[0]};
under_arch = newl; Line(under_arch) = {inner[0], inner[n]};
outside_left = newl; Line(outside_left) = {outer[n], p4};
left = newl; Line(left) = {p4, p1};
loop = newll;
Curve Loop(loop) = {ground, right, outside_right, -joint[0], under_arch, joint[n], outside_left, left};
slab = news; Plane Surface(slab) = {loop};

// The load point: the middle of the key block's extrados face.
crown = newp; Point(crown) = {0, re * Cos(Pi / (2 * n)), 0};

Physical Surface("arch") = {voussoir[]};
Physical Surface("base") = {slab};
Physical Curve("joints") = {joint[]};   // [joints.joints]: the arch's joints and springings
Physical Curve("ground") = {ground};    // [[boundary]]: the slab is held here
Physical Point("crown") = {crown};      // [[load]]: the point force on the key block
