// Shoe with a slot (stadium, kidney-like) inlet pocket along phi.
// Plane (phi [rad], z = Z/R0): arc [-0.5, 0.5], half width 0.4; slot centre
// (0, 0), end-circle centres at phi = -0.2 and 0.2 (length 0.4), width 0.1
// (end radius 0.05); area 0.4*0.1 + pi*0.05^2 = 0.047854.
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

Point(5) = {-0.2, -0.05, 0, lc};   // bottom edge start
Point(6) = { 0.2, -0.05, 0, lc};   // bottom edge end
Point(7) = { 0.2,  0.05, 0, lc};   // top edge start
Point(8) = {-0.2,  0.05, 0, lc};   // top edge end
Point(9) = {-0.2,  0.0,  0, lc};   // centre of the left end circle
Point(10) = { 0.2, 0.0,  0, lc};   // centre of the right end circle
Point(11) = { 0.25, 0.0, 0, lc};   // tip of the right end
Point(12) = {-0.25, 0.0, 0, lc};   // tip of the left end
// Each semicircle is drawn as two quarter arcs: a 180-degree arc given by
// start, centre and end is ambiguous (gmsh may bend it into the slot).
Line(5) = {5, 6};
Circle(6) = {6, 10, 11};
Circle(7) = {11, 10, 7};
Line(8) = {7, 8};
Circle(9) = {8, 9, 12};
Circle(10) = {12, 9, 5};
Curve Loop(2) = {5, 6, 7, 8, 9, 10};
Plane Surface(1) = {1, 2};

Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("arc_start") = {4};
Physical Curve("arc_end") = {2};
Physical Curve("side") = {1, 3};
Physical Curve("inlet") = {5, 6, 7, 8, 9, 10};
Physical Surface("film") = {1};
