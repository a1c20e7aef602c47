// Shoe with a central circular inlet pocket of 10 % of the outline area
// (paper 004's headline design: 10 % inlet region). Plane (phi [rad], z = Z/R0):
// arc [-0.5, 0.5], half width 0.4 (outline area 0.8); pocket centre (0, 0),
// radius sqrt(0.08/pi) = 0.15958 (area 0.08).
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

r = Sqrt(0.08 / Pi);
Circle(5) = {0, 0, 0, r};        // pocket contour
Curve Loop(2) = {5};
Plane Surface(1) = {1, 2};       // film = outline minus pocket

Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("arc_start") = {4};
Physical Curve("arc_end") = {2};
Physical Curve("side") = {1, 3};
Physical Curve("inlet") = {5};
Physical Surface("film") = {1};
