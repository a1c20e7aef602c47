// Shoe with a sharp-cornered rectangular recess (inlet pocket) at the centre.
// Plane (phi [rad], z = Z/R0): arc [-0.5, 0.5], half width 0.4; recess
// 0.4 (along phi) x 0.3 (along z), centre (0, 0), area 0.12. The pressure
// gradient is singular at the four re-entrant corners.
SetFactory("OpenCASCADE");
lc = 0.05;
Mesh.MeshSizeMax = lc;

Point(1) = {-0.5, -0.4, 0, lc};
Point(2) = { 0.5, -0.4, 0, lc};
Point(3) = { 0.5,  0.4, 0, lc};
Point(4) = {-0.5,  0.4, 0, lc};
Line(1) = {1, 2};                // z = -a   (side)
Line(2) = {2, 3};                // phi = alpha2 (arc_end)
Line(3) = {3, 4};                // z = +a   (side)
Line(4) = {4, 1};                // phi = alpha1 (arc_start)
Curve Loop(1) = {1, 2, 3, 4};

Point(5) = {-0.2, -0.15, 0, lc};
Point(6) = { 0.2, -0.15, 0, lc};
Point(7) = { 0.2,  0.15, 0, lc};
Point(8) = {-0.2,  0.15, 0, lc};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};

Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("arc_start") = {4};
Physical Curve("arc_end") = {2};
Physical Curve("side") = {1, 3};
Physical Curve("inlet") = {5, 6, 7, 8};
Physical Surface("film") = {1};
