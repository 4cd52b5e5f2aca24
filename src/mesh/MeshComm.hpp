// Reading the mesh on one rank, copying it to every rank, and partitioning its cells
// (METIS). A rank's part of the mesh instead of a copy: mesh/MeshPart.hpp.
#pragma once
#include <mpi.h>

#include <functional>
#include <vector>

#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Root's bytes on every rank of comm (sent in chunks below MPI's int count limit).
// Collective.
void broadcast_bytes(std::vector<char>& buf, MPI_Comm comm, int root = 0);

// Bytes from this rank to rank `to`, and their receipt on `to` (chunked alike).
void send_bytes(const std::vector<char>& buf, int to, MPI_Comm comm);
std::vector<char> recv_bytes(int from, MPI_Comm comm);

// Runs `work` on root only; an InputError it throws is rethrown with the same message on
// every rank, any other exception as std::runtime_error, so that no rank waits for root in
// vain. Collective.
void on_root(const std::function<void()>& work, MPI_Comm comm, int root = 0);

// Copies root's mesh to every rank of comm (all fields; other ranks' m is replaced).
void broadcast_mesh(Mesh& m, MPI_Comm comm, int root = 0);

// Rank root reads cfg (read_mesh) and, if check, runs check_mesh; the mesh is
// broadcast. An InputError on root is rethrown, with the same message, on every
// rank (so no rank hangs). Collective.
Mesh read_mesh_on_root(const MeshConfig& cfg, MPI_Comm comm, bool check = true, bool verbose = false,
                       int root = 0);
// The same without the broadcast: the mesh on root, an empty Mesh elsewhere (for
// distribute_mesh, mesh/MeshPart.hpp). Collective.
Mesh read_mesh_on_root_only(const MeshConfig& cfg, MPI_Comm comm, bool check = true, bool verbose = false, int root = 0);

// Part (0..nparts-1) of each global volume cell (index = CellBlock::cell_id),
// from METIS_PartMeshDual on the vertex nodes (2 shared nodes make neighbours
// in 2D, 3 in 3D), with a fixed seed: deterministic for a given mesh.
// nparts == 1 gives all zeros. Throws InputError if nparts > number of cells,
// std::runtime_error if METIS fails.
std::vector<int> partition_cells(const Mesh& m, int nparts);

// partition_cells on rank root only, the result broadcast to every rank of comm (one
// METIS run per job, not one per rank). An InputError on root is rethrown with the same
// message on every rank, any other failure as std::runtime_error (no rank hangs).
// Collective.
std::vector<int> partition_cells_on_root(const Mesh& m, int nparts, MPI_Comm comm, int root = 0);

// Owner of each node: the smallest part among the volume cells that contain it
// (so the owner always has a cell touching the node). Nodes in no volume cell
// (check_mesh rejects them on boundaries) get part 0.
std::vector<int> node_owners(const Mesh& m, const std::vector<int>& cell_part);

}  // namespace stentor
