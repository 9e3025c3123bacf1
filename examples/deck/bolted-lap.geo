// Bolted lap joint (mm): two steel plates 100 x 30 x 5 mm overlapping by 30 mm, joined
// by one M8-like bolt (shank d = 8 mm through 9 mm clearance holes, head and nut as
// cylinders d = 13 mm). Plates and bolt are separate volumes meshed separately, so the
// plate-plate interface and the two bearing rings are non-conforming surface pairs.
// Quadratic tetrahedra with straight edges (C3D10).
//
// Mesh and deck mesh file (Gmsh writes its physical surfaces as CPS6 facets, which
// the deck cannot hold; the converter turns them into element-face surfaces):
//   gmsh -3 -format inp -o bolted-lap-gmsh.inp bolted-lap.geo
//   jointlin deck from-gmsh bolted-lap-gmsh.inp --out bolted-lap-mesh.inp
SetFactory("OpenCASCADE");

t = 5;        // plate thickness
w = 30;       // plate width (y)
len = 100;    // plate length (x)
lap = 30;     // overlap
xb = len - lap / 2;  // bolt axis x
yb = w / 2;          // bolt axis y
r_hole = 4.5; // clearance hole d_h = 9 mm (ISO 273, medium)
r_shank = 4;  // M8 shank
r_ring = 5.8; // bearing ring: d_w = 11.6 mm (ISO 4017 M8 head, min.)
r_head = 6.5; // head and nut d = 13 mm (across flats)
h_head = 5.5;
h_nut = 6.5;

// Lower plate z in [0, t], x in [0, len]; upper plate z in [t, 2t], x in [len - lap,
// 2 len - lap]. Each plate is its free block, its overlap block with the hole, and the
// ring r_hole < r < r_ring around the hole, fragmented so that they share their mesh;
// the lap faces and the bearing rings are then faces of their own.
Box(1) = {0, 0, 0, len - lap, w, t};
Box(2) = {len - lap, 0, 0, lap, w, t};
Cylinder(3) = {xb, yb, 0, 0, 0, t, r_ring};
Cylinder(4) = {xb, yb, 0, 0, 0, t, r_ring};
Cylinder(5) = {xb, yb, 0, 0, 0, t, r_hole};
BooleanDifference(6) = { Volume{2}; Delete; }{ Volume{3}; Delete; };
BooleanDifference(7) = { Volume{4}; Delete; }{ Volume{5}; Delete; };
lower() = BooleanFragments{ Volume{1, 6, 7}; Delete; }{};

Box(11) = {len, 0, t, len - lap, w, t};
Box(12) = {len - lap, 0, t, lap, w, t};
Cylinder(13) = {xb, yb, t, 0, 0, t, r_ring};
Cylinder(14) = {xb, yb, t, 0, 0, t, r_ring};
Cylinder(15) = {xb, yb, t, 0, 0, t, r_hole};
BooleanDifference(16) = { Volume{12}; Delete; }{ Volume{13}; Delete; };
BooleanDifference(17) = { Volume{14}; Delete; }{ Volume{15}; Delete; };
upper() = BooleanFragments{ Volume{11, 16, 17}; Delete; }{};

// Bolt: nut z in [-h_nut, 0], shank, head z in [2t, 2t + h_head]; one volume.
Cylinder(20) = {xb, yb, -h_nut, 0, 0, 2 * t + h_nut + h_head, r_shank};
Cylinder(21) = {xb, yb, 2 * t, 0, 0, h_head, r_head};
Cylinder(22) = {xb, yb, -h_nut, 0, 0, h_nut, r_head};
bolt() = BooleanUnion{ Volume{20}; Delete; }{ Volume{21, 22}; Delete; };

// Surfaces by position: every boundary face of a volume list whose bounding box lies in
// {x0, y0, z0, x1, y1, z1} (grown by e) is appended to faces().
e = 1e-3;
Macro FacesIn
  faces() = {};
  b() = Boundary{ Volume{vols()}; };
  For k In {0:#b()-1}
    bb() = BoundingBox Surface{ Abs(b(k)) };
    If (bb(0) > box(0) - e && bb(1) > box(1) - e && bb(2) > box(2) - e &&
        bb(3) < box(3) + e && bb(4) < box(4) + e && bb(5) < box(5) + e)
      faces() += Abs(b(k));
    EndIf
  EndFor
Return

vols() = lower(); box() = {len - lap, 0, t, len, w, t}; Call FacesIn;
Physical Surface("LAP_LOWER") = faces();
vols() = upper(); box() = {len - lap, 0, t, len, w, t}; Call FacesIn;
Physical Surface("LAP_UPPER") = faces();
vols() = lower(); box() = {xb - r_ring, yb - r_ring, 0, xb + r_ring, yb + r_ring, 0}; Call FacesIn;
Physical Surface("RING_LOWER") = faces();
vols() = upper(); box() = {xb - r_ring, yb - r_ring, 2 * t, xb + r_ring, yb + r_ring, 2 * t}; Call FacesIn;
Physical Surface("RING_UPPER") = faces();
vols() = bolt(); box() = {xb - r_head, yb - r_head, 0, xb + r_head, yb + r_head, 0}; Call FacesIn;
Physical Surface("NUT_BEARING") = faces();
vols() = bolt(); box() = {xb - r_head, yb - r_head, 2 * t, xb + r_head, yb + r_head, 2 * t}; Call FacesIn;
Physical Surface("HEAD_BEARING") = faces();
vols() = lower(); box() = {0, 0, 0, 0, w, t}; Call FacesIn;
Physical Surface("CLAMP") = faces();

// The free end: a node at the centre of the upper plate's end face (load and output).
vols() = upper(); box() = {2 * len - lap, 0, t, 2 * len - lap, w, 2 * t}; Call FacesIn;
Point(100) = {2 * len - lap, yb, 1.5 * t};
Point{100} In Surface{ faces(0) };
Physical Point("TIP") = {100};

Physical Volume("LOWER") = lower();
Physical Volume("UPPER") = upper();
Physical Volume("BOLT") = bolt();

// The plates' hole and ring edges are 16-gons: the two hole edges of the lap faces then
// have the same nodes, so that the slave face's hole edge lies on the master face's (a
// curved edge meshed twice would not), and the bearing rings' faceted area is known,
// 8 sin(pi/8) (r_ring^2 - r_hole^2) (bolted-lap.inp uses it for the preload pressure).
circles() = {};
b() = Boundary{ Volume{lower(), upper()}; };
c() = Boundary{ Surface{b()}; };
For k In {0:#c()-1}
  bb() = BoundingBox Curve{ Abs(c(k)) };
  If (bb(5) - bb(2) < e && bb(0) > xb - r_ring - e && bb(3) < xb + r_ring + e)
    circles() += Abs(c(k));
  EndIf
EndFor
Transfinite Curve{ circles() } = 17;

Mesh.CharacteristicLengthMax = 6;
// Finer on the bolt: its head and nut faces are the ties' master faces.
MeshSize{ PointsOf{ Volume{bolt()}; } } = 3;
Mesh.ElementOrder = 2;
// Mid-edge nodes on the straight edges: curved C3D10 on the holes can have a negative
// Jacobian at quadrature points (the reader rejects inverted elements).
Mesh.SecondOrderLinear = 1;
Mesh.SaveGroupsOfNodes = 1;
