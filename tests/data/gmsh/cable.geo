// Two cable segments of length 1 (4 lines each): (0,0,0)-(1,0,0) in group "cable", (1,0,0)-(1,0,-1) in the
// unnamed group 7; the end point (1,0,-1) in point group "anchor".
Point(1) = {0, 0, 0, 0.25}; Point(2) = {1, 0, 0, 0.25}; Point(3) = {1, 0, -1, 0.25};
Line(1) = {1, 2}; Line(2) = {2, 3};
Physical Curve("cable") = {1};
Physical Curve(7) = {2};
Physical Point("anchor") = {3};
