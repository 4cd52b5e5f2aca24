// Results for ParaView (its three XDMF readers) and meshio: one HDF5 file with the heavy
// data and an XDMF file describing it.
//
// Serial or parallel. Serial (the constructor without a communicator, or a communicator
// of one rank): the HDF5 file is opened with the default (sec2) driver and the caller
// passes whole datasets. Parallel (a communicator of several ranks): every rank of it
// creates the writer and makes every call, in the same order; the file is opened with
// MPI-IO (H5Pset_fapl_mpio), datasets and attributes are created collectively, and each
// rank writes one contiguous block of rows of each dataset (collective H5Dwrite): node
// datasets rows node_rows(), cell datasets (and /mesh/topology, /mesh/cell_block, the
// blocks' connectivity) rows cell_rows() of the block-ordered cells, both block_rows() of
// the row count. Rank 0 alone writes the .xdmf. The file's datasets are the same whatever
// the number of ranks.
// The mesh comes as an XdmfMesh: the whole mesh's outline (node count, blocks and their
// cell counts; the same on every rank) and this rank's rows of the coordinates and of the
// blocks' connectivity only (xdmf_rows says which; run/OutputRows.hpp xdmf_mesh_on_rows
// builds them from what a rank of a distributed run holds), or as a whole Mesh (xdmf_mesh
// takes the rows out of it). The writer reads nothing else of the mesh.
//
// <dir>/<basename>.h5
//   /mesh/coordinates            num_nodes x 3 doubles (z = 0 in 2D; 0 for the nodes of no
//                                volume cell: no cell refers to them, and a rank of a
//                                distributed run does not have them)
//   /mesh/topology               every volume cell, blocks in order, XDMF/VTK node order
//                                (= meshio's; gmsh tet10 differs: its nodes 8 and 9 are
//                                swapped): num_cells x nodes_per_cell int64 when all cells
//                                have one type, else XDMF's 1-D "Mixed" list (per cell its
//                                XDMF type number, then its nodes); attribute "topology"
//   /mesh/cell_block             num_cells int64: the volume block of each cell (0, 1, ...)
//   /mesh/block_<i>/connectivity num_cells_i x nodes_per_cell int64 (the same node order);
//                                attributes "name" (physical group), "topology"
//   /step_<k>                    one group per step, attribute "time" (double)
//   /step_<k>/coordinates        a moving mesh only (geometry()): the step's node positions
//   /step_<k>/<field>            (characters other than [A-Za-z0-9_.+-] replaced by '_';
//                                the XDMF Attribute keeps the name as given)
//                                num_nodes x ncomp (node field) or num_cells x ncomp
//                                (cell field, cells in block order); scalars are 1-D.
//                                Symmetric tensors (ncomp 6, given as xx,yy,zz,xy,yz,xz)
//                                are stored expanded to full 3x3 row-major (9 components),
//                                which every ParaView XDMF reader interprets alike.
// <dir>/<basename>.xdmf (XDMF 3)
//   <Domain>: an Information "cell_block" ("0: <block name>; 1: ...") and a Temporal
//   collection with one Uniform grid per step: <Time>, the whole mesh (Topology on
//   /mesh/topology, Geometry on /mesh/coordinates), the cell attribute "cell_block", then
//   the step's fields, each a plain HDF DataItem on its whole dataset.
//   Why one Uniform grid per step, not a Spatial collection of one grid per block (as
//   written before): meshio's TimeSeriesReader reads the mesh from one Uniform grid and takes a
//   step's Attributes only from the step's own element (Attributes of nested grids are
//   skipped, HyperSlab DataItems are not understood): it failed with "Unknown section
//   'Grid'" or found no data. (meshio.read() reads single-grid files only, no time series
//   of anyone's; meshio documents TimeSeriesReader for these.) A temporal collection of Uniform grids whose
//   DataItems reference HDF5 datasets is the plain XDMF 2/3 pattern (FEniCS, meshio write
//   it) that ParaView's "XDMF Reader" (Xdmf 2) and Xdmf3ReaderS/T read: the blocks now come
//   as one unstructured grid, told apart by "cell_block" (Threshold on it in ParaView).
//   "Mixed" (bodies of different cell types, e.g. triangles and quadrilaterals) is read by
//   ParaView's readers; meshio 5.0 (Debian 12) knows only linear types in a Mixed list.
//   Rewritten (write to .tmp + rename) by every end_step() after the .h5 was flushed, so
//   the pair is consistent whenever end_step() has returned.
//
// Every failure throws std::runtime_error naming the file; a failed write (any failed
// HDF5 call, the .xdmf) throws WriteError with the reason (e.g. "No space left on device").
// Parallel: a failed write may throw on some ranks only (the .xdmf, rank 0's test hook in
// end_step): the caller makes the ranks agree (parallel/Agreement.hpp). A writer destroyed
// while an exception unwinds leaves its file open (closing is collective, and the other
// ranks may be elsewhere); HDF5 closes it at MPI_Finalize.
#pragma once
#include <mpi.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

// XDMF TopologyType of a cell type ("Tetrahedron_10", ...); nullptr when it has none here.
// Line2 cells (rigid obstacles' outlines) are "Polyline" with NodesPerElement 2, in a mesh
// of line cells only.
const char* xdmf_topology_name(CellType t);

// Node permutation gmsh -> XDMF: xdmf_conn[j] = gmsh_conn[perm[j]]. Returns the number of
// nodes (perm filled for j < n), 0 for types without an XDMF equivalent.
int xdmf_node_permutation(CellType t, int perm[kMaxCellNodes]);

// XDMF's number of a cell type in a "Mixed" topology (0x26 for Tetrahedron_10, ...);
// -1 for types without an XDMF topology here.
int xdmf_mixed_type_id(CellType t);

// Rows [begin, end) of a dataset.
struct RowRange {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};

// Rank `rank`'s share of n rows split over `nranks` ranks in contiguous blocks, in rank
// order, the first n % nranks ranks one row more (Tpetra's uniform contiguous map).
RowRange block_rows(std::size_t n, int rank, int nranks);

// The mesh as the writer takes it (only volume blocks are written): the whole mesh's
// outline, the same on every rank, and this rank's rows of its data (xdmf_rows).
struct XdmfMesh {
  struct Block {
    std::string name;                   // physical group
    CellType type = CellType::Invalid;  // must have an XDMF topology
    std::size_t num_cells = 0;          // in the whole mesh
    // The block's cells among this rank's cell rows (XdmfRows::blocks), in order:
    // cell_num_nodes(type) node ids each, gmsh node order.
    std::vector<long long> conn;
  };
  std::size_t num_nodes = 0;  // in the whole mesh
  std::vector<Block> blocks;  // Mesh::volumes order
  std::vector<double> x;      // this rank's node rows: 3 coordinates each (see /mesh/coordinates)
};

// Rank `rank`'s rows (of `nranks`) of the datasets of a mesh with the outline of `mesh`
// (num_nodes, the blocks' num_cells; nothing else is read): the node rows, the cell rows
// (blocks in order), and per block its cells among the cell rows, numbered within the
// block (empty ranges for blocks outside them).
struct XdmfRows {
  RowRange nodes, cells;
  std::vector<RowRange> blocks;
};
XdmfRows xdmf_rows(const XdmfMesh& mesh, int rank, int nranks);

// A whole mesh as XdmfMesh for rank `rank` of `nranks` (its rows read from the mesh).
// Throws std::runtime_error when the mesh is a part (Mesh::partial), its coordinates are
// not 3 per node, a block's connectivity does not match its cell type or names a node out
// of range.
XdmfMesh xdmf_mesh(const Mesh& whole, int rank, int nranks);

class XdmfWriter {
 public:
  // Writes <dir>/<basename>.h5 with the mesh (dir must exist). Only mesh.volumes are
  // written; their cell types must have an XDMF topology. Serial; a whole mesh.
  XdmfWriter(const std::string& dir, const std::string& basename, const Mesh& mesh);
  // Collective over `comm` (see above; serial when it has one rank); a whole mesh on
  // every rank (xdmf_mesh).
  XdmfWriter(const std::string& dir, const std::string& basename, const Mesh& mesh, MPI_Comm comm);
  // Collective over `comm`: `mesh` holds this rank's rows, xdmf_rows(mesh, rank, nranks)
  // of comm (MPI_COMM_NULL: serial, all rows). Throws std::runtime_error on every rank
  // when the rows of any rank do not match the outline (sizes, node ids out of range, a
  // cell type without XDMF topology).
  XdmfWriter(const std::string& dir, const std::string& basename, const XdmfMesh& mesh, MPI_Comm comm);
  ~XdmfWriter();
  XdmfWriter(const XdmfWriter&) = delete;
  XdmfWriter& operator=(const XdmfWriter&) = delete;

  // This rank's rows of the node datasets and of the cell datasets (all of them serially).
  RowRange node_rows() const;
  RowRange cell_rows() const;

  void begin_step(double time);
  // node_rows().size()*ncomp values (this rank's nodes), node-major; ncomp 1 (scalar),
  // 3 (vector), 9 (tensor, row major) or 6 (symmetric tensor: xx,yy,zz,xy,yz,xz).
  void node_field(const std::string& name, int ncomp, const std::vector<double>& data);
  // cell_rows().size()*ncomp values, cells in block order (all of volumes[0], then ...).
  // The name "cell_block" is reserved (the writer's own block index).
  void cell_field(const std::string& name, int ncomp, const std::vector<double>& data);
  // A moving mesh: this step's node positions (node_rows() x 3) as /step_<k>/coordinates,
  // the step grid's Geometry instead of /mesh/coordinates (meshio's TimeSeriesReader reads
  // the first step's points only: write a displacement field too).
  void geometry(const std::vector<double>& x);
  // Flushes the step's datasets to the .h5, then (rank 0) rewrites the .xdmf.
  void end_step();

  const std::string& h5_path() const;
  const std::string& xdmf_path() const;
  int num_steps() const;  // completed steps

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stentor
