// A missing closing brace on line 4, which gmsh reports as "line 4: syntax error (;)".
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Line(1) = {1, 2;
Point(3) = {1, 1, 0};
