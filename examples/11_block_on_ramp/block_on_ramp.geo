// The sliding problem of Luo et al. 2021, section 5.2, Figure 7a
// (examples/11_block_on_ramp). Units: metres.
//
// A rectangular block on a triangular ramp whose top surface rises at 45 degrees. The ramp
// rises to the right, so the block slides down to the left: with that orientation a block at
// rest has its minor principal stress at -76.7 degrees, the paper's -76.6 (README.md). The
// paper gives no dimensions (its figure is not available); the sizes below are assumed:
// - the block's thickness across the slope, 0.3 * sqrt(2) = 0.4243 m, from the paper's
//   stresses of the block at rest (sigma1 = 2.22 kPa, sigma2 = -5.91 kPa for phi = 70
//   degrees: a block of thickness t at rest on a 45 degree slope has the mean stresses
//   sigma1 = 0.618 a, sigma2 = -1.618 a, a = rho g t cos45 / 2, so t = 0.42 m);
// - its length along the slope, 0.6 * sqrt(2) = 0.8485 m (twice the thickness);
// - the ramp, 2.5 m high and wide, long enough for the 1.24 m that the block slides in
//   35 steps of 0.02 s with phi = 15 degrees.
// Corners are on a 0.3 m grid, as a block drawn in a DDA input file would be.
//
// Ramp: the triangle (0, 0), (2.5, 0), (2.5, 2.5); its top surface is the line y = x.
Point(1) = {0.0, 0.0, 0};    // toe
Point(2) = {2.5, 0.0, 0};
Point(3) = {2.5, 2.5, 0};    // crest
// Block: its underside from (1.5, 1.5) to (2.1, 2.1) on the slope, 2.12 m up it from the toe.
Point(4) = {1.5, 1.5, 0};    // lower corner on the slope
Point(5) = {2.1, 2.1, 0};    // upper corner on the slope
Point(6) = {1.8, 2.4, 0};    // upper corner of the top face
Point(7) = {1.2, 1.8, 0};    // lower corner of the top face
Point(8) = {1.65, 1.95, 0};  // the block's centroid (not on any curve: only a named place)

Line(1) = {1, 2};   // ramp: underside (held)
Line(2) = {2, 3};   // ramp: vertical back (held)
Line(3) = {3, 5};   // slope above the block
Line(4) = {5, 4};   // slope under the block = the block's underside: the joint "slip"
Line(5) = {4, 1};   // slope below the block
Line(6) = {5, 6};   // block: upper side
Line(7) = {6, 7};   // block: top face
Line(8) = {7, 4};   // block: lower side

Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Curve Loop(2) = {-4, 6, 7, 8};
Plane Surface(2) = {2};

Physical Surface("ramp") = {1};
Physical Surface("block") = {2};
Physical Curve("slip") = {4};        // [joints.slip]: the block's underside on the slope
Physical Curve("base") = {1};        // [[boundary]]: held, with "back", so that all three
Physical Curve("back") = {2};        // vertices of the ramp are fixed as in the paper
Physical Point("centroid") = {8};   // the block's centroid: [[monitor]] "block" in the cases
