// A cylinder pressed on a block (examples/17_hertz_contact): Hertz's line contact. Units:
// metres. By symmetry only x >= 0 is drawn: a quarter of the cylinder (radius R, centre
// (0, R), touching the block at the origin) loaded on its horizontal radius, on a block
// W wide and D deep whose top is y = 0. Every straight or curved side is a polyline of
// points spaced h = a / n within xf of the contact and growing by g beyond, up to hmax:
// nmm's gmsh cover mesh takes every polygon vertex as a mesh node and grows the triangles
// from the boundary spacing up to [cover_mesh] size, so these points grade the mesh.
R = 1.0;          // cylinder radius
W = 2.0;          // block half width
D = 2.0;          // block depth
a = 0.020845;     // Hertz half width of the contact (README): only sets the mesh
n = 20;           // boundary edges across a (bench/hertz.py changes this line)
h = a / n;        // spacing in the contact zone
xf = 2.0 * a;     // extent of the fine zone from the contact
g = 1.2;          // growth of the spacing beyond it
hmax = 0.1;       // largest spacing

// Positions 0 = s_0 < s_1 < ... < s_last = glen along a side from the contact: spacing h
// up to xf, then growing by g up to hmax.
Macro Graded
  gs[] = {0};
  gpos = 0;
  gstep = h;
  // At most xf / h fine steps, log(hmax / h) / log(g) growing ones, glen / hmax coarse ones.
  For gi In {1:Ceil(xf / h + Log(hmax / h) / Log(g) + glen / hmax) + 2}
    If (gpos < glen)
      If (gpos >= xf)
        gstep = gstep * g;
      EndIf
      If (gstep > hmax)
        gstep = hmax;
      EndIf
      gpos = gpos + gstep;
      If (gpos > glen - 0.5 * gstep)
        gpos = glen;
      EndIf
      gs[] += {gpos};
    EndIf
  EndFor
Return

Point(1) = {0, 0, 0};   // the contact: shared by the cylinder and the block

// Cylinder: the arc from the contact to (R, R), the loaded radius, the axis back down.
glen = Pi / 2 * R;
Call Graded;
arc_points[] = {1};
For i In {1:#gs[] - 1}
  t = gs[i] / R;
  p = newp;
  x = R * Sin(t);
  y = R * (1 - Cos(t));
  If (i == #gs[] - 1)
    x = R; // exactly: 1 - Cos(Pi / 2) leaves y 6e-17 low, which tilts the loaded
           // radius (README, "Files")
    y = R;
  EndIf
  Point(p) = {x, y, 0};
  arc_points[] += {p};
EndFor
cylinder_lines[] = {};
For i In {0:#arc_points[] - 2}
  l = newl;
  Line(l) = {arc_points[i], arc_points[i + 1]};
  cylinder_lines[] += {l};
EndFor
p_centre = newp;
Point(p_centre) = {0, R, 0};
load_line = newl;
Line(load_line) = {arc_points[#arc_points[] - 1], p_centre};
cylinder_lines[] += {load_line};
glen = R;
Call Graded;
axis_points[] = {};
For i In {#gs[] - 2:1:-1}
  p = newp;
  Point(p) = {0, gs[i], 0};
  axis_points[] += {p};
EndFor
axis_points[] = {p_centre, axis_points[], 1};
cylinder_axis[] = {};
For i In {0:#axis_points[] - 2}
  l = newl;
  Line(l) = {axis_points[i], axis_points[i + 1]};
  cylinder_axis[] += {l};
EndFor
Curve Loop(1) = {cylinder_lines[], cylinder_axis[]};
Plane Surface(1) = {1};

// Block: the axis down from the contact, the base, the far side, the top back to the
// contact.
glen = D;
Call Graded;
block_axis_points[] = {1};
For i In {1:#gs[] - 1}
  p = newp;
  Point(p) = {0, -gs[i], 0};
  block_axis_points[] += {p};
EndFor
block_axis[] = {};
For i In {0:#block_axis_points[] - 2}
  l = newl;
  Line(l) = {block_axis_points[i], block_axis_points[i + 1]};
  block_axis[] += {l};
EndFor
p_corner = newp;
Point(p_corner) = {W, -D, 0};
p_top = newp;
Point(p_top) = {W, 0, 0};
base = newl;
Line(base) = {block_axis_points[#block_axis_points[] - 1], p_corner};
side = newl;
Line(side) = {p_corner, p_top};
glen = W;
Call Graded;
top_points[] = {p_top};
For i In {#gs[] - 2:1:-1}
  p = newp;
  Point(p) = {gs[i], 0, 0};
  top_points[] += {p};
EndFor
top_points[] += {1};
block_top[] = {};
For i In {0:#top_points[] - 2}
  l = newl;
  Line(l) = {top_points[i], top_points[i + 1]};
  block_top[] += {l};
EndFor
Curve Loop(2) = {block_axis[], base, side, block_top[]};
Plane Surface(2) = {2};

Physical Surface("cylinder") = {1};
Physical Surface("block") = {2};
Physical Curve("load") = {load_line};                    // the cylinder's horizontal radius
Physical Curve("symmetry") = {cylinder_axis[], block_axis[]};   // x = 0: rollers
Physical Curve("base") = {base};                         // y = -D: held
Physical Curve("arc") = {cylinder_lines[{0:#cylinder_lines[] - 2}]};  // the cylinder's face
Physical Curve("top") = {block_top[]};                   // the block's face
