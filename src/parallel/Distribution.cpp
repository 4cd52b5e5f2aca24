#include "parallel/Distribution.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <utility>

#include "mesh/MeshComm.hpp"
#include "parallel/RawComm.hpp"

namespace stentor {

namespace {

// Morton (Z-order) key of x in the box [lo, hi]: 21 bits per axis, interleaved.
std::uint64_t morton_key(const double* x, const double* lo, const double* hi) {
  std::uint64_t key = 0;
  std::uint64_t q[3];
  for (int d = 0; d < 3; ++d) {
    const double span = hi[d] - lo[d];
    const double t = span > 0.0 ? (x[d] - lo[d]) / span : 0.0;
    q[d] = static_cast<std::uint64_t>(std::min(std::max(t, 0.0), 1.0) * ((1u << 21) - 1));
  }
  for (int bit = 20; bit >= 0; --bit)
    for (int d = 0; d < 3; ++d) key = (key << 1) | ((q[d] >> bit) & 1u);
  return key;
}

// Axis-aligned bounding box of points.
struct Box {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  void add(const double* x) {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], x[d]);
      hi[d] = std::max(hi[d], x[d]);
    }
  }
};

// Sorts items along the Morton curve of box: xyz(item) gives an item's point.
template <class T, class Xyz>
void morton_sort(std::vector<T>& items, const Box& box, Xyz xyz) {
  std::vector<std::pair<std::uint64_t, T>> key;
  key.reserve(items.size());
  for (const T& it : items) key.emplace_back(morton_key(xyz(it), box.lo, box.hi), it);
  std::sort(key.begin(), key.end());
  for (std::size_t i = 0; i < items.size(); ++i) items[i] = key[i].second;
}

// The part of each stored cell, block by block: a rank's part of the mesh carries them
// (mesh/MeshPart.hpp); a whole mesh is partitioned here, rank 0 running METIS and
// broadcasting the parts (one METIS run per job). Collective.
std::vector<std::vector<int>> cell_parts(const Mesh& mesh, int nranks, MPI_Comm comm) {
  std::vector<std::vector<int>> parts;
  if (mesh.partial) {
    for (const auto& b : mesh.volumes) parts.push_back(b.part);
    return parts;
  }
  const std::vector<int> whole = partition_cells_on_root(mesh, nranks, comm);
  for (const auto& b : mesh.volumes) {
    parts.emplace_back();
    for (GId id : b.cell_id) parts.back().push_back(whole[static_cast<std::size_t>(id)]);
  }
  return parts;
}

// This rank's owned and ghost nodes, each in the Morton (Z-order) curve of their
// coordinates, so that the nodes of a cell, and therefore the matrix rows an element
// kernel touches, are close in memory (gmsh numbers large Delaunay meshes with poor
// locality; this halved the tangent assembly at 200k dofs, docs/performance.md). A node's
// owner is the smallest part among the cells around it, which are all stored for the
// nodes this rank's cells touch; nodes of no volume cell (of boundary or point groups
// only) carry no dof.
void split_nodes(const Mesh& mesh, const std::vector<std::vector<int>>& parts, int rank, std::vector<GId>& owned,
                 std::vector<GId>& ghost) {
  const std::size_t ns = mesh.num_stored_nodes();
  std::vector<int> owner(ns, INT_MAX);
  std::vector<char> touched(ns, 0);
  for (std::size_t bi = 0; bi < mesh.volumes.size(); ++bi) {
    const CellBlock& b = mesh.volumes[bi];
    for (std::size_t c = 0; c < b.num_cells(); ++c) {
      const int p = parts[bi][c];
      for (int a = 0; a < b.nodes_per_cell; ++a) {
        const auto i = static_cast<std::size_t>(mesh.stored_index(b.conn[c * b.nodes_per_cell + a]));
        owner[i] = std::min(owner[i], p);
        if (p == rank) touched[i] = 1;
      }
    }
  }
  for (std::size_t i = 0; i < ns; ++i) {
    if (owner[i] == rank)
      owned.push_back(mesh.stored_node(i));
    else if (touched[i])
      ghost.push_back(mesh.stored_node(i));
  }
  auto x = [&mesh](GId g) { return mesh.coord(g); };
  Box box;
  for (const auto* v : {&owned, &ghost})
    for (GId g : *v) box.add(x(g));
  morton_sort(owned, box, x);
  morton_sort(ghost, box, x);
}

}  // namespace

Distribution::Distribution(const Mesh& mesh, const la::RCP<const la::Comm>& comm)
    : dim_(mesh.dim), rank_(comm->getRank()), nranks_(comm->getSize()), comm_(comm) {
  const std::vector<std::vector<int>> parts = cell_parts(mesh, nranks_, raw_mpi_comm(*comm));
  std::vector<GId> owned, ghost;
  split_nodes(mesh, parts, rank_, owned, ghost);
  set_local_nodes(mesh, owned, ghost);
  for (std::size_t bi = 0; bi < mesh.volumes.size(); ++bi) blocks_.push_back(local_block(mesh, bi, parts[bi]));
}

// Local numbering (owned first: Tpetra's FE assembly needs owned rows to be a prefix of
// the overlap map), the lookup from global ids, the DOF maps and the coordinates.
void Distribution::set_local_nodes(const Mesh& mesh, const std::vector<GId>& owned, const std::vector<GId>& ghost) {
  num_owned_ = static_cast<la::LO>(owned.size());
  local_nodes_ = owned;
  local_nodes_.insert(local_nodes_.end(), ghost.begin(), ghost.end());
  if (mesh.partial) {  // sized by this rank's nodes, not the mesh's
    for (std::size_t l = 0; l < local_nodes_.size(); ++l) sparse_g2l_.emplace_back(local_nodes_[l], static_cast<la::LO>(l));
    std::sort(sparse_g2l_.begin(), sparse_g2l_.end());
  } else {
    node_g2l_.assign(mesh.num_stored_nodes(), -1);
    for (std::size_t l = 0; l < local_nodes_.size(); ++l) node_g2l_[static_cast<std::size_t>(local_nodes_[l])] = static_cast<la::LO>(l);
  }
  auto dof_gids = [this](const std::vector<GId>& nodes) {
    std::vector<la::GO> g;
    g.reserve(nodes.size() * dim_);
    for (GId n : nodes)
      for (int c = 0; c < dim_; ++c) g.push_back(static_cast<la::GO>(n * dim_ + c));
    return g;
  };
  const auto inv = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  const auto owned_g = dof_gids(owned);
  const auto overlap_g = dof_gids(local_nodes_);
  owned_map_ = Teuchos::rcp(new la::Map(inv, Teuchos::ArrayView<const la::GO>(owned_g), 0, comm_));
  overlap_map_ = Teuchos::rcp(new la::Map(inv, Teuchos::ArrayView<const la::GO>(overlap_g), 0, comm_));
  importer_ = Teuchos::rcp(new la::Import(owned_map_, overlap_map_));

  coords_ = Kokkos::View<double* [3], Kokkos::LayoutRight, la::ExecSpace>("coords", local_nodes_.size());
  auto ch = Kokkos::create_mirror_view(coords_);
  for (std::size_t l = 0; l < local_nodes_.size(); ++l)
    for (int d = 0; d < 3; ++d) ch(l, d) = mesh.coord(local_nodes_[l])[d];
  Kokkos::deep_copy(coords_, ch);
}

// This rank's cells of volume block bi, in the Morton order of their centroids (same
// reason as the nodes), with their local connectivity.
LocalBlock Distribution::local_block(const Mesh& mesh, std::size_t bi, const std::vector<int>& part) const {
  const CellBlock& b = mesh.volumes[bi];
  LocalBlock lb;
  lb.volume_block = static_cast<int>(bi);
  lb.type = b.type;
  lb.nodes_per_cell = b.nodes_per_cell;
  std::vector<std::size_t> mine;
  std::vector<std::array<double, 3>> centroid(b.num_cells());
  Box box;
  for (std::size_t c = 0; c < b.num_cells(); ++c)
    if (part[c] == rank_) {
      std::array<double, 3>& xc = centroid[c];
      xc = {0.0, 0.0, 0.0};
      for (int a = 0; a < b.nodes_per_cell; ++a)
        for (int d = 0; d < 3; ++d)
          xc[static_cast<std::size_t>(d)] += mesh.coord(b.conn[c * b.nodes_per_cell + a])[d] / b.nodes_per_cell;
      box.add(xc.data());
      mine.push_back(c);
    }
  morton_sort(mine, box, [&centroid](std::size_t c) { return centroid[c].data(); });
  for (std::size_t c : mine) {
    lb.cell_ids.push_back(b.cell_id[c]);
    lb.cell_index.push_back(static_cast<GId>(c));
  }
  lb.conn = Kokkos::View<int**, Kokkos::LayoutRight, la::ExecSpace>("conn", lb.cell_ids.size(), b.nodes_per_cell);
  auto h = Kokkos::create_mirror_view(lb.conn);
  for (std::size_t lc = 0; lc < lb.cell_index.size(); ++lc)
    for (int a = 0; a < b.nodes_per_cell; ++a)
      h(lc, a) = local_node(b.conn[static_cast<std::size_t>(lb.cell_index[lc]) * b.nodes_per_cell + a]);
  Kokkos::deep_copy(lb.conn, h);
  return lb;
}

la::LO Distribution::local_node(GId g) const {
  if (sparse_g2l_.empty()) return g >= 0 && static_cast<std::size_t>(g) < node_g2l_.size() ? node_g2l_[static_cast<std::size_t>(g)] : -1;
  const auto it = std::lower_bound(sparse_g2l_.begin(), sparse_g2l_.end(), std::make_pair(g, la::LO{-1}));
  return it != sparse_g2l_.end() && it->first == g ? it->second : -1;
}

std::vector<double> Distribution::owned_coordinates() const {
  auto ch = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), coords_);
  std::vector<double> xyz(3 * static_cast<std::size_t>(num_owned_));
  for (la::LO n = 0; n < num_owned_; ++n)
    for (int k = 0; k < 3; ++k) xyz[3 * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)] = ch(n, k);
  return xyz;
}

std::size_t Distribution::num_local_cells() const {
  std::size_t n = 0;
  for (const auto& b : blocks_) n += b.cell_ids.size();
  return n;
}

}  // namespace stentor
