// A 3 m embankment of fill on a 6 m clay layer, for examples/gmsh-embankment/case.yaml.
// Mesh it with: gmsh -2 embankment.geo -format msh41 -o embankment.msh
// The clay's top is split where the embankment's base begins and ends, so that both surfaces
// share the curve under the embankment (one node at each position, as rktsph requires).
lc = 0.5;
Point(1) = {0, 0, 0, lc};
Point(2) = {40, 0, 0, lc};
Point(3) = {40, 6, 0, lc};
Point(4) = {30, 6, 0, lc};
Point(5) = {10, 6, 0, lc};
Point(6) = {0, 6, 0, lc};
Point(7) = {26, 9, 0, lc};
Point(8) = {14, 9, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};   // under the embankment, shared by both surfaces
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {4, 7};   // the right slope
Line(8) = {7, 8};   // the crest
Line(9) = {8, 5};   // the left slope
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-4, 7, 8, 9};
Plane Surface(2) = {2};
Physical Surface("clay") = {1};
Physical Surface("fill") = {2};
Physical Curve("crest") = {8};
