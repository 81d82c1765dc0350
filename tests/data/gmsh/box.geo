// Surface of the box [0,1] x [0,2] x [0,0.5] (area 7): six surfaces in several groups; the name "top" is a
// surface group (z = 0.5) and a curve group (two of its edges), whose nodes are merged. "corner": the point
// (0, 0, 0).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 2, 0.5};
Mesh.MeshSizeMax = 0.5;
Physical Surface("sides") = {1, 2, 3, 4};
Physical Surface(20) = {5};
Physical Surface("top") = {6};
Physical Curve("top") = {10, 12};
Physical Point("corner") = Point In BoundingBox{-0.01, -0.01, -0.01, 0.01, 0.01, 0.01};
