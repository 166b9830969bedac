// A batch script ending in Exit: gmsh 4.8 would call exit(0) and end the whole program.
// Exit; in a comment does not count, /* nor Exit; here */
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1}; Physical Surface("rock") = {1};
Mesh 2; Exit;
