#include "mesh/MeshPart.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "deck/Config.hpp"
#include "fem/Shape.hpp"
#include "mesh/MeshComm.hpp"

namespace stentor {
namespace {

// Vertex count of a facet (dimension dim-1): 2 in 2D, 3 or 4 in 3D.
int facet_vertices(int dim, CellType t) { return dim == 2 ? 2 : (t == CellType::Quad4 || t == CellType::Quad8 ? 4 : 3); }

// Reference normal direction (unnormalised) of facet f at its parametric centre, following
// fem/Geometry.hpp's convention: 2D n = (t_y, -t_x), 3D n = x_xi x x_eta.
std::array<double, 3> facet_normal(const Mesh& m, const CellBlock& b, std::size_t f) {
  double xi[3] = {0, 0, 0};
  if (b.type == CellType::Tri3 || b.type == CellType::Tri6) xi[0] = xi[1] = 1.0 / 3.0;
  double N[kMaxCellNodes], dN[kMaxCellNodes][3];
  shape_functions(b.type, xi, N, dN);
  double t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0};
  for (int a = 0; a < b.nodes_per_cell; ++a) {
    const double* x = m.coord(b.conn[f * static_cast<std::size_t>(b.nodes_per_cell) + static_cast<std::size_t>(a)]);
    for (int d = 0; d < 3; ++d) {
      t1[d] += dN[a][0] * x[d];
      t2[d] += dN[a][1] * x[d];
    }
  }
  if (m.dim == 2) return {t1[1], -t1[0], 0.0};
  return {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
}

// Volume cells around the first vertex of each facet of `facets` (compressed rows over
// those nodes only: the memory is the surface's, not the mesh's).
struct CellsAroundFacetNodes {
  std::vector<GId> node;                          // sorted first-vertex nodes
  std::vector<std::size_t> start;                 // node i's cells: [start[i], start[i+1])
  std::vector<std::pair<int, std::size_t>> cell;  // (volume block, index)
  CellsAroundFacetNodes(const Mesh& m, const CellBlock& facets) {
    for (std::size_t f = 0; f < facets.num_cells(); ++f) node.push_back(facets.conn[f * static_cast<std::size_t>(facets.nodes_per_cell)]);
    std::sort(node.begin(), node.end());
    node.erase(std::unique(node.begin(), node.end()), node.end());
    start.assign(node.size() + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::size_t> at(start.begin(), start.end() - 1);
      for (std::size_t bi = 0; bi < m.volumes.size(); ++bi) {
        const CellBlock& b = m.volumes[bi];
        for (std::size_t c = 0; c < b.num_cells(); ++c)
          for (int a = 0; a < b.nodes_per_cell; ++a) {
            const auto it = std::lower_bound(node.begin(), node.end(), b.conn[c * static_cast<std::size_t>(b.nodes_per_cell) + static_cast<std::size_t>(a)]);
            if (it == node.end() || *it != b.conn[c * static_cast<std::size_t>(b.nodes_per_cell) + static_cast<std::size_t>(a)]) continue;
            const auto i = static_cast<std::size_t>(it - node.begin());
            if (pass == 0) ++start[i + 1];
            else cell[at[i]++] = {static_cast<int>(bi), c};
          }
      }
      if (pass == 0) {
        for (std::size_t i = 0; i < node.size(); ++i) start[i + 1] += start[i];
        cell.resize(start.back());
      }
    }
  }
};

// A block with b's name, tag and cell type, and no cells.
CellBlock empty_like(const CellBlock& b) {
  CellBlock q;
  q.name = b.name;
  q.physical_tag = b.physical_tag;
  q.type = b.type;
  q.nodes_per_cell = b.nodes_per_cell;
  return q;
}

// Appends cell c of b (nodes and id) to q.
void append_cell(const CellBlock& b, std::size_t c, CellBlock& q) {
  const auto npc = static_cast<std::size_t>(b.nodes_per_cell);
  q.conn.insert(q.conn.end(), b.conn.begin() + static_cast<std::ptrdiff_t>(c * npc), b.conn.begin() + static_cast<std::ptrdiff_t>((c + 1) * npc));
  if (!b.cell_id.empty()) q.cell_id.push_back(b.cell_id[c]);
}

}  // namespace

FacetSides facet_sides(const Mesh& m, const CellBlock& facets) {
  FacetSides out;
  const CellsAroundFacetNodes around(m, facets);
  const auto npf = static_cast<std::size_t>(facets.nodes_per_cell);
  const int nv = facet_vertices(m.dim, facets.type);
  for (std::size_t f = 0; f < facets.num_cells(); ++f) {
    const GId* fn = &facets.conn[f * npf];
    const auto i = static_cast<std::size_t>(std::lower_bound(around.node.begin(), around.node.end(), fn[0]) - around.node.begin());
    const CellBlock* vb = nullptr;  // a volume cell holding all vertices of the facet
    std::size_t cc = 0;
    for (std::size_t j = around.start[i]; j < around.start[i + 1] && !vb; ++j) {
      const auto& [bi, c] = around.cell[j];
      const CellBlock& b = m.volumes[static_cast<std::size_t>(bi)];
      const GId* cn = &b.conn[c * static_cast<std::size_t>(b.nodes_per_cell)];
      bool all = true;
      for (int v = 1; v < nv && all; ++v) all = std::find(cn, cn + b.nodes_per_cell, fn[v]) != cn + b.nodes_per_cell;
      if (all) vb = &b, cc = c;
    }
    if (!vb) {
      out.side.push_back(0);
      out.adjacent.push_back(-1);
      continue;
    }
    double xc[3] = {0, 0, 0}, xf[3] = {0, 0, 0};
    for (int a = 0; a < vb->nodes_per_cell; ++a) {
      const double* x = m.coord(vb->conn[cc * static_cast<std::size_t>(vb->nodes_per_cell) + static_cast<std::size_t>(a)]);
      for (int d = 0; d < 3; ++d) xc[d] += x[d] / vb->nodes_per_cell;
    }
    for (std::size_t a = 0; a < npf; ++a)
      for (int d = 0; d < 3; ++d) xf[d] += m.coord(fn[a])[d] / static_cast<double>(npf);
    const auto n = facet_normal(m, facets, f);
    const double s = n[0] * (xf[0] - xc[0]) + n[1] * (xf[1] - xc[1]) + n[2] * (xf[2] - xc[2]);
    out.side.push_back(s >= 0 ? 1 : -1);
    out.adjacent.push_back(vb->cell_id[cc]);
  }
  return out;
}

Mesh mesh_part(const Mesh& m, const std::vector<int>& cell_part, int r, const std::vector<std::string>& whole_groups) {
  const std::size_t nn = m.num_nodes();
  std::vector<char> touched(nn, 0), on_cells(nn, 0), stored(nn, 0);  // root only: the whole mesh is here anyway
  for (const auto& b : m.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c)
      if (cell_part[static_cast<std::size_t>(b.cell_id[c])] == r)
        for (int a = 0; a < b.nodes_per_cell; ++a) touched[static_cast<std::size_t>(b.conn[c * static_cast<std::size_t>(b.nodes_per_cell) + static_cast<std::size_t>(a)])] = 1;
  Mesh p;
  p.dim = m.dim;
  p.source = m.source;
  p.partial = true;
  p.whole_nodes = nn;
  p.whole_box = m.bounding_box();
  for (const auto& b : m.volumes) {
    CellBlock q = empty_like(b);
    q.whole_cells = b.num_cells();
    const auto npc = static_cast<std::size_t>(b.nodes_per_cell);
    for (std::size_t c = 0; c < b.num_cells(); ++c) {
      const int owner = cell_part[static_cast<std::size_t>(b.cell_id[c])];
      bool keep = owner == r;
      for (std::size_t a = 0; a < npc && !keep; ++a) keep = touched[static_cast<std::size_t>(b.conn[c * npc + a])] != 0;
      if (!keep) continue;
      append_cell(b, c, q);
      q.part.push_back(owner);
      for (std::size_t a = 0; a < npc; ++a) on_cells[static_cast<std::size_t>(b.conn[c * npc + a])] = 1;
    }
    p.volumes.push_back(std::move(q));
  }
  stored = on_cells;
  for (const auto& b : m.boundaries) {
    const bool whole = std::find(whole_groups.begin(), whole_groups.end(), b.name) != whole_groups.end();
    CellBlock q = empty_like(b);
    const auto npc = static_cast<std::size_t>(b.nodes_per_cell);
    for (std::size_t c = 0; c < b.num_cells(); ++c) {
      // Whole groups and facets that bound no volume cell (every rank reports those alike)
      // are kept; other cells when all their nodes lie on this part's volume cells.
      bool keep = whole || (!b.side.empty() && b.side[c] == 0);
      if (!keep) {
        keep = true;
        for (std::size_t a = 0; a < npc && keep; ++a) keep = on_cells[static_cast<std::size_t>(b.conn[c * npc + a])] != 0;
      }
      if (!keep) continue;
      append_cell(b, c, q);
      if (!b.side.empty()) {
        q.side.push_back(b.side[c]);
        q.adjacent.push_back(b.adjacent[c]);
      }
      for (std::size_t a = 0; a < npc; ++a) stored[static_cast<std::size_t>(b.conn[c * npc + a])] = 1;
    }
    p.boundaries.push_back(std::move(q));
  }
  for (std::size_t g = 0; g < nn; ++g)
    if (stored[g]) {
      p.node_ids.push_back(static_cast<GId>(g));
      p.x.insert(p.x.end(), m.x.begin() + static_cast<std::ptrdiff_t>(3 * g), m.x.begin() + static_cast<std::ptrdiff_t>(3 * g + 3));
    }
  return p;
}

void distribute_mesh(Mesh& m, MPI_Comm comm, const std::vector<std::string>& whole_groups, int root) {
  int rank = 0, nranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &nranks);
  if (nranks == 1) return;
  std::vector<int> cell_part;
  on_root(
      [&] {
        cell_part = partition_cells(m, nranks);
        for (auto& b : m.boundaries)
          if (cell_dim(b.type) == m.dim - 1) {
            FacetSides s = facet_sides(m, b);
            b.side = std::move(s.side);
            b.adjacent = std::move(s.adjacent);
          }
      },
      comm, root);
  if (rank != root) {
    m = deserialize_mesh(recv_bytes(root, comm));
    return;
  }
  for (int r = 0; r < nranks; ++r)
    if (r != root) send_bytes(serialize_mesh(mesh_part(m, cell_part, r, whole_groups)), r, comm);
  m = mesh_part(m, cell_part, root, whole_groups);
}

}  // namespace stentor
