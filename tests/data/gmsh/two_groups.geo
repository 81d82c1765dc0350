// rectangle.geo with the surface also in group "canopy_copy": MSH 2.2 writes each triangle twice.
Include "rectangle.geo";
Physical Surface("canopy_copy") = {1};
