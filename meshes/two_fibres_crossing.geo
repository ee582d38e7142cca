// two_fibres_crossing: each fibre's chord with nodes at its supports, slices, loads
// and contact points (refined there). Mesh with: gmsh -1 two_fibres_crossing.geo
// fibre A
Point(1) = {0, 0, 0, 0.02};
Point(2) = {0.5, 0, 0, 0.0050000000000000001};
Point(3) = {1, 0, 0, 0.02};
Line(1) = {1, 2};
Line(2) = {2, 3};
Physical Curve("A", 1) = {1, 2};
Physical Point("A/start", 2) = {1};
Physical Point("A/end", 3) = {3};
// fibre B
Point(4) = {0.5, -0.5, 0.019, 0.02};
Point(5) = {0.5, 0, 0.019, 0.0050000000000000001};
Point(6) = {0.5, 0.5, 0.019, 0.02};
Line(3) = {4, 5};
Line(4) = {5, 6};
Physical Curve("B", 4) = {3, 4};
Physical Point("B/start", 5) = {4};
Physical Point("B/end", 6) = {6};
