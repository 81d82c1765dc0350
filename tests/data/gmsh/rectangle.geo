// 2 x 1 rectangle in z = 0 (curve loop counter-clockwise: normal +z), structured: 9 x 5 nodes, 64 triangles.
// Physical surface "canopy", physical curve "edge" (y = 0: 8 lines, 9 nodes).
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 9;
Transfinite Curve{2, 4} = 5;
Transfinite Surface{1};
Physical Surface("canopy") = {1};
Physical Curve("edge") = {1};
