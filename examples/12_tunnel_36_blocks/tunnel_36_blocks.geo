// The surrounding rock problem of Luo et al. 2021, section 5.3, Figure 9
// (examples/12_tunnel_36_blocks). Units: metres; origin at the centre of the opening.
//
// 36 rock blocks around an opening, in three layers separated by two hoop joints; radial
// joints cut each layer into 12 blocks, staggered from layer to layer like masonry. The
// outermost boundary is held. The paper gives no dimensions and its figure is not
// available: everything below is assumed (README.md, "Assumed"), chosen so that
// - the inner layer has two blocks at the top and two at the bottom, side by side about the
//   vertical axis (a radial joint at the crown and one at the invert), as the paper reports
//   stresses for "the top two" and "the bottom two rocks in the inner layer";
// - there are convex and concave blocks: the 12 inner blocks are convex trapezoids; the 12
//   middle and 12 outer blocks are concave (a vertex of the polygonal hoop joint they sit on
//   points into them);
// - the stress level matches: a ring of voussoirs of mean radius R under its own weight is
//   compressed across its joints at the crown by about rho g R; with R = 4 m that is
//   about 110 kPa, the paper's sigma2 of the top blocks (-109.7 kPa with phi = 30 degrees).
//
//   opening:      a regular 12-gon, vertices at radius 3 m, at 0, 30, ..., 330 degrees
//   hoop joint 1: the 12-gon at radius 5 m (vertices at 30k degrees), with its edge midpoints
//                 (at 15 + 30k degrees), where the middle layer's radial joints end
//   hoop joint 2: a regular 24-gon at radius 7 m (vertices at 15k degrees)
//   outer boundary: the square |x|, |y| <= 10 m, held
//   radial joints: inner layer at 30k degrees (crown 90, invert 270), middle layer at
//                 15 + 30k, outer layer at 30k, out to the square.
r0 = 3.0;
r1 = 5.0;
r2 = 7.0;
h = 10.0;
d = Pi / 180;

// Opening and hoop joint 1: 12-gon vertices at 30k degrees; hoop 1 also at 15 + 30k.
For k In {0:11}
  a = 30 * k * d;
  op[k] = newp; Point(op[k]) = {r0 * Cos(a), r0 * Sin(a), 0};
  h1[2 * k] = newp; Point(h1[2 * k]) = {r1 * Cos(a), r1 * Sin(a), 0};
  b = (30 * k + 15) * d;
  h1[2 * k + 1] = newp; Point(h1[2 * k + 1]) = {r1 * Cos(15 * d) * Cos(b), r1 * Cos(15 * d) * Sin(b), 0};
EndFor
// Hoop joint 2: 24-gon at 15j degrees.
For j In {0:23}
  a = 15 * j * d;
  h2[j] = newp; Point(h2[j]) = {r2 * Cos(a), r2 * Sin(a), 0};
EndFor
// The square: where the outer radial joints (30k degrees) meet it, and its corners, in
// counter-clockwise order from (h, 0).
q = h * Tan(30 * d);
sq[] = {};
sx[] = {h, h, h, q, 0, -q, -h, -h, -h, -h, -h, -q, 0, q, h, h};
sy[] = {0, q, h, h, h, h, h, q, 0, -q, -h, -h, -h, -h, -h, -q};
For i In {0:15}
  sq[i] = newp; Point(sq[i]) = {sx[i], sy[i], 0};
EndFor
// Index in sq[] of the square point at 30k degrees (0, 30, 60, ..., 330).
sq_at[] = {0, 1, 3, 4, 5, 7, 8, 9, 11, 12, 13, 15};

// Boundaries of the rock: the square (held) and the opening (free).
For i In {0:15}
  outer[i] = newl; Line(outer[i]) = {sq[i], sq[(i + 1) % 16]};
EndFor
For k In {0:11}
  opening[k] = newl; Line(opening[k]) = {op[k], op[(k + 1) % 12]};
EndFor
// Hoop joints: closed polylines.
For i In {0:23}
  hoop1[i] = newl; Line(hoop1[i]) = {h1[i], h1[(i + 1) % 24]};
  hoop2[i] = newl; Line(hoop2[i]) = {h2[i], h2[(i + 1) % 24]};
EndFor
// Radial joints: inner layer at 30k (opening vertex to hoop 1 vertex), middle layer at
// 15 + 30k (hoop 1 edge midpoint to hoop 2 vertex), outer layer at 30k (hoop 2 vertex to
// the square).
For k In {0:11}
  radial_inner[k] = newl; Line(radial_inner[k]) = {op[k], h1[2 * k]};
  radial_middle[k] = newl; Line(radial_middle[k]) = {h1[2 * k + 1], h2[2 * k + 1]};
  radial_outer[k] = newl; Line(radial_outer[k]) = {h2[2 * k], sq[sq_at[k]]};
EndFor

loop_outer = newll; Curve Loop(loop_outer) = {outer[]};
loop_opening = newll; Curve Loop(loop_opening) = {opening[]};
rock = news; Plane Surface(rock) = {loop_outer, loop_opening};

Physical Surface("rock") = {rock};          // [materials.rock]: 36 DDA blocks, cut by the joints
Physical Curve("hoop") = {hoop1[], hoop2[]};  // [joints.hoop]: the two hoop joints
Physical Curve("radial") = {radial_inner[], radial_middle[], radial_outer[]};  // [joints.radial]
Physical Curve("outer") = {outer[]};        // [[boundary]]: the outermost boundary, held
Physical Curve("opening") = {opening[]};    // the free face of the opening (not used by the cases)
