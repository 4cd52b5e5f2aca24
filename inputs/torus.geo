// Torus (scene S2): major radius R = 1, tube radius r = 0.25, centre (0, 0, 0.8), its axis
// tilted by 30 degrees from z about the x axis: the lowest point is 0.05 above the plane z = 0.
// Physical groups: volume "torus"; surface "surface".
// h is a default: a deck's Mesh->size (> 0) replaces it.
SetFactory("OpenCASCADE");
h = DefineNumber[0.12, Name "Parameters/h"];
zc = 0.8;
Torus(1) = {0, 0, zc, 1.0, 0.25};
Rotate {{1, 0, 0}, {0, 0, zc}, Pi / 6} { Volume{1}; }
Mesh.MeshSizeMax = h;
Mesh.MeshSizeMin = 0.5 * h;
Mesh.MeshSizeFromCurvature = 12;

Physical Volume("torus") = {1};
Physical Surface("surface") = Boundary{ Volume{1}; };
