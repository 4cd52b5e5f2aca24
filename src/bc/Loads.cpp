#include "bc/Loads.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "fem/Shape.hpp"

namespace stentor {
namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "'" : ", '") + x + "'";
  return s.empty() ? "(none)" : s;
}

std::vector<const CellBlock*> boundary_blocks_named(const Mesh& mesh, const std::string& group, const std::string& where) {
  std::vector<const CellBlock*> r;
  for (const auto& b : mesh.boundaries)
    if (b.name == group) r.push_back(&b);
  if (r.empty())
    throw InputError(where + ": physical group '" + group + "' not found among the boundary groups of mesh " + mesh.source +
                     "; available: " + join(mesh.boundary_group_names()));
  return r;
}

// Reference unit normal direction (unnormalised) of a facet at its parametric centre,
// following fem/Geometry.hpp's convention: 2D n = (t_y, -t_x), 3D n = x_xi x x_eta.
std::array<double, 3> facet_normal(const Mesh& mesh, const CellBlock& b, std::size_t f) {
  double xi[3] = {0, 0, 0};
  if (b.type == CellType::Tri3 || b.type == CellType::Tri6) xi[0] = xi[1] = 1.0 / 3.0;
  double N[kMaxCellNodes], dN[kMaxCellNodes][3];
  shape_functions(b.type, xi, N, dN);
  double t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0};
  for (int a = 0; a < b.nodes_per_cell; ++a) {
    const double* x = &mesh.x[3 * static_cast<std::size_t>(b.conn[f * b.nodes_per_cell + a])];
    for (int d = 0; d < 3; ++d) {
      t1[d] += dN[a][0] * x[d];
      t2[d] += dN[a][1] * x[d];
    }
  }
  if (mesh.dim == 2) return {t1[1], -t1[0], 0.0};
  return {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
}

}  // namespace

NodeCells::NodeCells() = default;

const std::vector<std::pair<int, std::size_t>>& NodeCells::of(const Mesh& mesh, GId node) {
  if (cells_.empty()) {
    cells_.resize(mesh.num_nodes());
    for (std::size_t bi = 0; bi < mesh.volumes.size(); ++bi) {
      const auto& b = mesh.volumes[bi];
      for (std::size_t c = 0; c < b.num_cells(); ++c)
        for (int a = 0; a < b.nodes_per_cell; ++a)
          cells_[static_cast<std::size_t>(b.conn[c * b.nodes_per_cell + a])].push_back({static_cast<int>(bi), c});
    }
  }
  return cells_[static_cast<std::size_t>(node)];
}

// gmsh does not orient physical curves/surfaces consistently with the body they bound:
// each facet is oriented against the centroid of the volume cell that contains it.
std::vector<OrientedFacets> oriented_facets(const Mesh& mesh, const std::string& group, const std::string& where, NodeCells& node_cells) {
  std::vector<OrientedFacets> out;
  for (const CellBlock* b : boundary_blocks_named(mesh, group, where)) {
    if (cell_dim(b->type) != mesh.dim - 1)
      throw InputError(where + ": group '" + group + "' has cells of dimension " + std::to_string(cell_dim(b->type)) +
                       "; facets of dimension " + std::to_string(mesh.dim - 1) + " are needed");
    OrientedFacets of;
    of.type = b->type;
    of.nodes_per_facet = b->nodes_per_cell;
    of.conn = b->conn;
    const int nv = (mesh.dim == 2) ? 2 : (b->type == CellType::Quad4 || b->type == CellType::Quad8 ? 4 : 3);
    for (std::size_t f = 0; f < b->num_cells(); ++f) {
      const GId* fn = &b->conn[f * b->nodes_per_cell];
      // A volume cell containing all vertex nodes of the facet.
      int cb = -1;
      std::size_t cc = 0;
      for (const auto& [bi, c] : node_cells.of(mesh, fn[0])) {
        const auto& vb = mesh.volumes[static_cast<std::size_t>(bi)];
        const GId* cn = &vb.conn[c * vb.nodes_per_cell];
        bool all = true;
        for (int v = 1; v < nv && all; ++v) all = std::find(cn, cn + vb.nodes_per_cell, fn[v]) != cn + vb.nodes_per_cell;
        if (all) {
          cb = bi;
          cc = c;
          break;
        }
      }
      if (cb < 0) {
        std::ostringstream os;
        os << where << ": facet " << f << " of group '" << group << "' bounds no volume cell of the mesh";
        throw InputError(os.str());
      }
      const auto& vb = mesh.volumes[static_cast<std::size_t>(cb)];
      double xc[3] = {0, 0, 0}, xf[3] = {0, 0, 0};
      for (int a = 0; a < vb.nodes_per_cell; ++a)
        for (int d = 0; d < 3; ++d) xc[d] += mesh.x[3 * static_cast<std::size_t>(vb.conn[cc * vb.nodes_per_cell + a]) + d] / vb.nodes_per_cell;
      for (int a = 0; a < b->nodes_per_cell; ++a)
        for (int d = 0; d < 3; ++d) xf[d] += mesh.x[3 * static_cast<std::size_t>(fn[a]) + d] / b->nodes_per_cell;
      const auto n = facet_normal(mesh, *b, f);
      const double s = n[0] * (xf[0] - xc[0]) + n[1] * (xf[1] - xc[1]) + n[2] * (xf[2] - xc[2]);
      of.orientation.push_back(s >= 0 ? 1.0 : -1.0);
      of.adjacent_cell.push_back(vb.cell_id[cc]);
    }
    out.push_back(std::move(of));
  }
  return out;
}

std::vector<int> block_materials(const Config& cfg, const Mesh& mesh) {
  std::vector<int> mat(mesh.volumes.size(), -1);
  for (const auto& body : cfg.bodies) {
    int mi = -1;
    for (std::size_t m = 0; m < cfg.materials.size(); ++m)
      if (cfg.materials[m].name == body.material) mi = static_cast<int>(m);
    if (mi < 0) throw InputError(cfg.deck_path + ": Bodies->" + body.name + "->material: no material named '" + body.material + "'");
    bool found = false;
    for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
      if (mesh.volumes[b].name == body.group) {
        if (mat[b] >= 0 && mat[b] != mi)
          throw InputError(cfg.deck_path + ": Bodies->" + body.name + ": physical group '" + body.group + "' is already used by another body");
        mat[b] = mi;
        found = true;
      }
    if (!found)
      throw InputError(cfg.deck_path + ": Bodies->" + body.name + "->physical group: '" + body.group +
                       "' is not a physical group of dimension " + std::to_string(mesh.dim) + " in mesh " + mesh.source +
                       "; available: " + join(mesh.volume_group_names()));
  }
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
    if (mat[b] < 0)
      throw InputError(cfg.deck_path + ": the mesh's physical group '" + mesh.volumes[b].name +
                       "' belongs to no body; add a sublist to 'Bodies' with \"physical group\" = '" + mesh.volumes[b].name + "'");
  return mat;
}

Loads resolve_loads(const Config& cfg, const Mesh& mesh) {
  Loads loads;
  NodeCells node_cells;
  for (const auto& lc : cfg.loads) {
    const std::string where = cfg.deck_path + ": Boundary Conditions->" + lc.name;
    switch (lc.type) {
      case LoadConfig::Type::Dirichlet: {
        DirichletSet d;
        d.name = lc.name;
        d.group = lc.group;
        std::set<GId> nodes;
        for (const CellBlock* b : boundary_blocks_named(mesh, lc.group, where + "->boundary")) nodes.insert(b->conn.begin(), b->conn.end());
        d.nodes.assign(nodes.begin(), nodes.end());
        d.components = lc.components;
        d.values = lc.vector;
        d.field = lc.field;
        d.ramp = lc.ramp;
        if (mesh.dim == 2 && lc.all_components) d.components[2] = false;
        if (mesh.dim == 2 && d.components[2])
          throw InputError(where + "->components: 'z' is not a component of a 2D (plane strain) problem");
        loads.dirichlet.push_back(std::move(d));
        break;
      }
      case LoadConfig::Type::Traction:
      case LoadConfig::Type::Pressure: {
        for (OrientedFacets& of : oriented_facets(mesh, lc.group, where + "->boundary", node_cells)) {
          FacetLoad fl;
          fl.type = lc.type;
          fl.name = lc.name;
          fl.group = lc.group;
          fl.facet_type = of.type;
          fl.nodes_per_facet = of.nodes_per_facet;
          fl.conn = std::move(of.conn);
          fl.orientation = std::move(of.orientation);
          fl.adjacent_cell = std::move(of.adjacent_cell);
          fl.traction = lc.vector;
          fl.pressure = lc.value;
          fl.ramp = lc.ramp;
          loads.facet_loads.push_back(std::move(fl));
        }
        break;
      }
      case LoadConfig::Type::BodyForce: {
        BodyForce bf;
        bf.name = lc.name;
        bf.force = lc.vector;
        bf.field = lc.field;
        bf.ramp = lc.ramp;
        // The deck resolved "body" (a body name or its physical group) to the group.
        for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
          if (lc.group.empty() || mesh.volumes[b].name == lc.group) bf.volume_blocks.push_back(static_cast<int>(b));
        if (bf.volume_blocks.empty())
          throw InputError(where + "->body: '" + lc.group + "' is not a volume group of mesh " + mesh.source + "; available: " +
                           join(mesh.volume_group_names()));
        loads.body_forces.push_back(std::move(bf));
        break;
      }
    }
  }
  return loads;
}

}  // namespace stentor
