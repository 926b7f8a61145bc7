// A 2 m wide, 4 m high column of two layers (sand over clay, the interface at y = 1.5 m), meshed
// by Gmsh (gmsh -2 two-layer-column.geo -format msh41 -o two-layer-column.msh; Gmsh 4.8.4) for
// tests/geometry/gmsh_mesh_test.cpp: the layers share their interface curve, so its nodes are
// common to both; the bottom curve is the physical curve "base".
lc = 0.25;
Point(1) = {0, 0, 0, lc};
Point(2) = {2, 0, 0, lc};
Point(3) = {2, 1.5, 0, lc};
Point(4) = {0, 1.5, 0, lc};
Point(5) = {2, 4, 0, lc};
Point(6) = {0, 4, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};
Physical Surface("clay") = {1};
Physical Surface("sand") = {2};
Physical Curve("base") = {1};
