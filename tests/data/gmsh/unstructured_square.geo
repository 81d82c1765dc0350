// 1 x 1 square centred at the origin in z = 0, unstructured (mesh size 0.09): a fluid-side surface that does
// not match the structure's structured mesh (tests/unit/test_scene_interface.cpp). Physical surface "canopy".
SetFactory("OpenCASCADE");
Rectangle(1) = {-0.5, -0.5, 0, 1, 1};
Physical Surface("canopy") = {1};
Mesh.MeshSizeMax = 0.09;
