// Bolted lap joint (mm): two 60 x 20 x 3 mm plates overlapping by 20 mm, each with
// a 6 mm bolt hole at the centre of the overlap; quadratic tetrahedra (C3D10).
// Mesh: gmsh -3 -format inp -o bolted-lap-mesh.inp bolted-lap.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 60, 20, 3};
Box(2) = {40, 0, 3, 60, 20, 3};
Cylinder(3) = {50, 10, -1, 0, 0, 8, 3};
BooleanDifference{ Volume{1}; Volume{2}; Delete; }{ Volume{3}; Delete; }
Physical Volume("LOWER") = {1};
Physical Volume("UPPER") = {2};
Mesh.CharacteristicLengthMax = 6;
Mesh.ElementOrder = 2;
// Mid-edge nodes on the straight edges: curved C3D10 on the coarse hole can have a
// negative Jacobian at quadrature points (the reader rejects inverted elements).
Mesh.SecondOrderLinear = 1;
