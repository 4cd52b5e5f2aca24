// Results for ParaView: one HDF5 file with the heavy data and an XDMF file describing it.
//
// Serial writer: the caller gathers the mesh and the fields on one rank (rank 0) and
// creates/uses the writer there only; the HDF5 file is opened with the default (sec2)
// driver, no MPI-IO.
//
// <dir>/<basename>.h5
//   /mesh/coordinates            num_nodes x 3 doubles (z = 0 in 2D)
//   /mesh/block_<i>/connectivity num_cells x nodes_per_cell int64, XDMF/VTK node order
//                                (gmsh tet10 differs: its nodes 8 and 9 are swapped);
//                                attributes "name" (physical group), "topology"
//   /step_<k>                    one group per step, attribute "time"
//   /step_<k>/<field>            (characters other than [A-Za-z0-9_.+-] replaced by '_';
//                                the XDMF Attribute keeps the name as given)
//                                num_nodes x ncomp (node field) or num_volume_cells x ncomp
//                                (cell field, cells in block order); scalars are 1-D.
//                                Symmetric tensors (ncomp 6, given as xx,yy,zz,xy,yz,xz)
//                                are stored expanded to full 3x3 row-major (9 components),
//                                which every ParaView XDMF reader interprets alike.
// <dir>/<basename>.xdmf
//   Temporal collection of steps; each step a spatial collection of one Uniform grid per
//   (non-empty) volume block, all sharing /mesh/coordinates. Node fields reference the
//   whole dataset, cell fields the block's rows (HyperSlab when there are several blocks).
//   Rewritten (write to .tmp + rename) by every end_step() after the .h5 was flushed, so
//   the pair is consistent whenever end_step() has returned.
//
// Every failure throws std::runtime_error naming the file; a failed write (any failed
// HDF5 call, the .xdmf) throws WriteError with the reason (e.g. "No space left on device").
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

// XDMF TopologyType of a cell type ("Tetrahedron_10", ...); nullptr when it has none here.
const char* xdmf_topology_name(CellType t);

// Node permutation gmsh -> XDMF: xdmf_conn[j] = gmsh_conn[perm[j]]. Returns the number of
// nodes (perm filled for j < n), 0 for types without an XDMF equivalent.
int xdmf_node_permutation(CellType t, int perm[kMaxCellNodes]);

class XdmfWriter {
 public:
  // Writes <dir>/<basename>.h5 with the mesh (dir must exist). Only mesh.volumes are
  // written; their cell types must have an XDMF topology.
  XdmfWriter(const std::string& dir, const std::string& basename, const Mesh& mesh);
  ~XdmfWriter();
  XdmfWriter(const XdmfWriter&) = delete;
  XdmfWriter& operator=(const XdmfWriter&) = delete;

  void begin_step(double time);
  // num_nodes*ncomp values, node-major; ncomp 1 (scalar), 3 (vector), 9 (tensor, row
  // major) or 6 (symmetric tensor: xx,yy,zz,xy,yz,xz).
  void node_field(const std::string& name, int ncomp, const std::vector<double>& data);
  // num_volume_cells*ncomp values, cells in block order (all of volumes[0], then ...).
  void cell_field(const std::string& name, int ncomp, const std::vector<double>& data);
  // Flushes the step's datasets to the .h5, then rewrites the .xdmf.
  void end_step();

  const std::string& h5_path() const;
  const std::string& xdmf_path() const;
  int num_steps() const;  // completed steps

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stentor
