// two_squares.geo: a unit square made of two physical surfaces (rock left, steel right)
// with named boundary curves, for yfdem's Gmsh reader tests and examples.
// Regenerate: gmsh -2 -format msh41 two_squares.geo -o two_squares.msh
// Parametric variant (two_squares_param.msh): add -setnumber Mesh.SaveParametric 1
lc = 0.25;
Point(1) = {0, 0, 0, lc};
Point(2) = {0.5, 0, 0, lc};
Point(3) = {1, 0, 0, lc};
Point(4) = {1, 1, 0, lc};
Point(5) = {0.5, 1, 0, lc};
Point(6) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Physical Surface("rock", 1) = {1};
Physical Surface("steel", 2) = {2};
Physical Curve("bottom", 3) = {1, 2};
Physical Curve("right", 4) = {3};
Physical Point("corner", 5) = {6};
Mesh.MshFileVersion = 4.1;
