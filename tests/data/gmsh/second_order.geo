// rectangle.geo with 6-node triangles, which fsi refuses.
Include "rectangle.geo";
Mesh.ElementOrder = 2;
