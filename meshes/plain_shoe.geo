// Plain shoe (no inlet pocket): the default support surface of bearingfe in
// the unwrapped non-dimensional plane (phi [rad], z = Z/R0):
// arc phi in [-0.5, 0.5], half width a = 0.4; outline 1.0 x 0.8, area 0.8.
SetFactory("OpenCASCADE");
lc = 0.05;                       // characteristic length (element size)
Mesh.MeshSizeMax = lc;

// outline, counter-clockwise from (alpha1, -a)
Point(1) = {-0.5, -0.4, 0, lc};
Point(2) = { 0.5, -0.4, 0, lc};
Point(3) = { 0.5,  0.4, 0, lc};
Point(4) = {-0.5,  0.4, 0, lc};
Line(1) = {1, 2};                // z = -a   (side)
Line(2) = {2, 3};                // phi = alpha2 (arc_end)
Line(3) = {3, 4};                // z = +a   (side)
Line(4) = {4, 1};                // phi = alpha1 (arc_start)
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("arc_start") = {4};
Physical Curve("arc_end") = {2};
Physical Curve("side") = {1, 3};
Physical Surface("film") = {1};
