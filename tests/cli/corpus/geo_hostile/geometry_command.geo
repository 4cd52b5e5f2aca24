// expect: 'Geometry' sets an option that names a file or program
Geometry.DoubleClickedPointCommand = "touch x";
