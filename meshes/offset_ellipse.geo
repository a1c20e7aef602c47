// Shoe with an off-centre elliptical inlet pocket. Plane (phi [rad], z = Z/R0):
// arc [-0.5, 0.5], half width 0.4; ellipse centre (0.2, 0.1), semi-axes
// 0.12 (along its own axis) x 0.07, axis tilted 30 degrees from phi
// (area pi*0.12*0.07 = 0.026389).
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

Ellipse(5) = {0.2, 0.1, 0, 0.12, 0.07};            // major axis along phi ...
Rotate {{0, 0, 1}, {0.2, 0.1, 0}, Pi/6} { Curve{5}; }  // ... then tilted 30 deg
Curve Loop(2) = {5};
Plane Surface(1) = {1, 2};

Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("arc_start") = {4};
Physical Curve("arc_end") = {2};
Physical Curve("side") = {1, 3};
Physical Curve("inlet") = {5};
Physical Surface("film") = {1};
