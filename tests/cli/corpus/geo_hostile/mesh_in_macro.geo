// expect: 'Mesh' meshes or changes the mesh
Macro M
  Mesh 2;
Return
Call M;
