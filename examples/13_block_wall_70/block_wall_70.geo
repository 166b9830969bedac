// The block wall failure problem of Luo et al. 2021, section 5.4, Figure 11
// (examples/13_block_wall_70). Units: metres; origin at the wall's bottom left corner.
//
// A wall of 70 blocks, 270 m wide and 180 m high (paper), no friction between the blocks; the
// outer vertices of the two base blocks are held (paper). The layout is assumed (its figure is
// not available; README.md, "Assumed"):
// - nine courses of 20 m;
// - the bottom course is the two base blocks, 135 m long each, meeting at the middle
//   (x = 135); each is held only at its two outer vertices (its outer end), so the middle of
//   the wall has no support under it and the base blocks carry the wall as cantilevers,
//   loaded mainly in shear (the paper's stress in the bottom right block, sigma1 = 560 kPa,
//   sigma2 = -880 kPa at -48 degrees, is nearly pure shear);
// - above them eight courses of bricks 33.75 m long (270 / 8) in running bond: courses 1, 3,
//   5, 7 have seven whole bricks and a half brick at each end (9 blocks), courses 2, 4, 6, 8
//   eight whole bricks (8 blocks). 2 + 4 x 9 + 4 x 8 = 70 blocks. Course 1 bridges the joint
//   between the base blocks with a whole brick.
// The wall is one surface; the joints (bed joints along the courses, head joints across
// them) cut it into the blocks. Every joint end is a point shared with the curve it ends on.
w = 270.0;
course = 20.0;      // course height
n_courses = 9;      // course 0 is the base
u = w / 16;         // 16.875 m: half a brick; head joints lie at x = u m, m = 1 .. 15

// Does course c (0 .. 8) have a head joint at x = u m?
//   base (c = 0): only in the middle (m = 8); odd courses: odd m; even courses: even m.
Macro HasJoint
  has = 0;
  If (c == 0 && m == 8)
    has = 1;
  EndIf
  If (c >= 1 && c % 2 == 1 && m % 2 == 1)
    has = 1;
  EndIf
  If (c >= 2 && c % 2 == 0 && m % 2 == 0)
    has = 1;
  EndIf
Return

// Level L (0 .. 9) is the line y = 20 L: the bottom, the eight bed joints, the top. Its points
// are the wall's sides and every head joint that ends on it, from below or from above; its
// lines join consecutive points.
bed[] = {};
bottom[] = {};
top[] = {};
For L In {0:n_courses}
  y = course * L;
  row[] = {};
  p = newp; Point(p) = {0, y, 0};
  left[L] = p;
  row[] += p;
  For m In {1:15}
    on = 0;
    If (L >= 1)
      c = L - 1;
      Call HasJoint;
      If (has)
        on = 1;
      EndIf
    EndIf
    If (L <= n_courses - 1)
      c = L;
      Call HasJoint;
      If (has)
        on = 1;
      EndIf
    EndIf
    If (on)
      p = newp; Point(p) = {u * m, y, 0};
      node[16 * L + m] = p;
      row[] += p;
    EndIf
  EndFor
  p = newp; Point(p) = {w, y, 0};
  right[L] = p;
  row[] += p;
  For i In {0:#row[] - 2}
    l = newl; Line(l) = {row[i], row[i + 1]};
    If (L == 0)
      bottom[] += l;
    EndIf
    If (L == n_courses)
      top[] += l;
    EndIf
    If (L > 0 && L < n_courses)
      bed[] += l;
    EndIf
  EndFor
EndFor

// Head joints: course c from level c up to level c + 1.
head[] = {};
For c In {0:n_courses - 1}
  For m In {1:15}
    Call HasJoint;
    If (has)
      l = newl; Line(l) = {node[16 * c + m], node[16 * (c + 1) + m]};
      head[] += l;
    EndIf
  EndFor
EndFor

// The wall's two ends, course by course.
For L In {0:n_courses - 1}
  left_side[L] = newl; Line(left_side[L]) = {left[L], left[L + 1]};
  right_side[L] = newl; Line(right_side[L]) = {right[L], right[L + 1]};
EndFor

// Outline, counter-clockwise: the bottom left to right, the right end upwards, the top right
// to left, the left end downwards.
outline[] = {bottom[], right_side[]};
For i In {#top[] - 1:0:-1}
  outline[] += -top[i];
EndFor
For L In {n_courses - 1:0:-1}
  outline[] += -left_side[L];
EndFor
loop = newll; Curve Loop(loop) = {outline[]};
wall = news; Plane Surface(wall) = {loop};

Physical Surface("wall") = {wall};               // [materials.wall]: 70 DDA blocks
Physical Curve("bed") = {bed[]};                 // [joints.bed]: the 8 bed joints
Physical Curve("head") = {head[]};               // [joints.head]: the head joints and the joint
                                                 // between the two base blocks
Physical Curve("base_left_end") = {left_side[0]};    // [[boundary]]: the outer vertices of the
Physical Curve("base_right_end") = {right_side[0]};  // two base blocks, (0, 0), (0, 20) and
                                                     // (270, 0), (270, 20), held
Physical Curve("top") = {top[]};                 // the wall's crest (not used by the case)
