// A Gmsh script that runs a shell command when Gmsh interprets it: fsi must refuse it, never run it.
System "touch fsi_corpus_geo_script_was_executed";
Point(1) = {0, 0, 0, 1};
