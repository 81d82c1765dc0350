// Two unit squares, x in [0,1] (group "canopy") and x in [2,3] (group "other"), for readInterface groups.
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 1};
Rectangle(2) = {2, 0, 0, 1, 1};
Mesh.MeshSizeMax = 0.25;
Physical Surface("canopy") = {1};
Physical Surface("other") = {2};
