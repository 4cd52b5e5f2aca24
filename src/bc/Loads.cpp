#include "bc/Loads.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "bc/Axisymmetry.hpp"
#include "mesh/MeshPart.hpp"

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

// The unit normal of the plane (3D) or line (2D) through the group's nodes, pointing away
// from the cells that touch it; InputError (naming `where` and the group) when the nodes do
// not span a plane or do not lie on one. Deterministic: ranks holding the whole group (Model
// reads these groups whole) compute the same normal.
std::array<double, 3> plane_normal(const Mesh& mesh, const std::vector<GId>& nodes, const std::string& where, const std::string& group) {
  const int dim = mesh.dim;
  double x0[3] = {0, 0, 0};
  std::size_t count = 0;
  for (GId g : nodes) {
    if (mesh.stored_index(g) < 0) continue;
    for (int c = 0; c < 3; ++c) x0[c] += mesh.coord(g)[c];
    ++count;
  }
  std::array<double, 3> n{};
  if (count == 0) return n;  // nothing of the group on this rank: nothing to constrain here
  for (double& v : x0) v /= static_cast<double>(count);
  double C[3][3] = {}, extent = 0.0;
  for (GId g : nodes) {
    if (mesh.stored_index(g) < 0) continue;
    double d[3];
    for (int c = 0; c < 3; ++c) d[c] = mesh.coord(g)[c] - x0[c];
    extent = std::max(extent, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b) C[a][b] += d[a] * d[b];
  }
  // The rows of the scatter matrix lie in the plane (a line in 2D): the normal is the largest
  // cross product of two rows (2D: the largest row turned by 90 degrees).
  double best = 0.0;
  if (dim == 2) {
    for (int a = 0; a < 2; ++a) {
      const double len = std::hypot(C[a][0], C[a][1]);
      if (len > best) best = len, n = {-C[a][1] / len, C[a][0] / len, 0.0};
    }
  } else {
    for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b) {
        const double v[3] = {C[a][1] * C[b][2] - C[a][2] * C[b][1], C[a][2] * C[b][0] - C[a][0] * C[b][2],
                             C[a][0] * C[b][1] - C[a][1] * C[b][0]};
        const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (len > best) best = len, n = {v[0] / len, v[1] / len, v[2] / len};
      }
  }
  const double scale = std::pow(static_cast<double>(count) * extent * extent, dim == 2 ? 1.0 : 2.0);
  if (!(extent > 0.0) || !(best > 1e-12 * scale))
    throw InputError(where + ": components 'normal' needs group '" + group + "' to span a " + (dim == 2 ? "line" : "plane") +
                     "; its " + std::to_string(count) + " nodes do not");
  for (GId g : nodes) {
    if (mesh.stored_index(g) < 0) continue;
    double off = 0.0;
    for (int c = 0; c < dim; ++c) off += n[static_cast<std::size_t>(c)] * (mesh.coord(g)[c] - x0[c]);
    if (std::abs(off) > 1e-6 * extent) {
      std::ostringstream os;
      os << where << ": components 'normal' needs group '" << group << "' to be " << (dim == 2 ? "straight" : "planar") << "; node " << g
         << " lies " << std::abs(off) << " off the best-fitting " << (dim == 2 ? "line" : "plane") << " (tolerance 1e-6 x its extent "
         << extent << ")";
      throw InputError(os.str());
    }
  }
  // Outward: the cells touching the group lie on the other side.
  const std::set<GId> on(nodes.begin(), nodes.end());
  double side = 0.0;
  for (const auto& b : mesh.volumes)
    for (std::size_t e = 0; e < b.num_cells(); ++e) {
      const GId* cell = &b.conn[e * static_cast<std::size_t>(b.nodes_per_cell)];
      if (std::none_of(cell, cell + b.nodes_per_cell, [&](GId g) { return on.count(g) > 0; })) continue;
      for (int a = 0; a < b.nodes_per_cell; ++a)
        for (int c = 0; c < dim; ++c) side += n[static_cast<std::size_t>(c)] * (mesh.coord(cell[a])[c] - x0[c]);
    }
  if (side > 0.0)
    for (double& v : n) v = -v;
  return n;
}

}  // namespace

// Each facet's outward side, from the whole mesh (mesh/MeshPart.hpp facet_sides), or
// as a rank's part of the mesh carries it (worked out on the whole mesh before it was cut).
std::vector<OrientedFacets> oriented_facets(const Mesh& mesh, const std::string& group, const std::string& where) {
  std::vector<OrientedFacets> out;
  for (const CellBlock* b : boundary_blocks_named(mesh, group, where)) {
    if (cell_dim(b->type) != mesh.dim - 1)
      throw InputError(where + ": group '" + group + "' has cells of dimension " + std::to_string(cell_dim(b->type)) +
                       "; facets of dimension " + std::to_string(mesh.dim - 1) + " are needed");
    OrientedFacets of;
    of.type = b->type;
    of.nodes_per_facet = b->nodes_per_cell;
    of.conn = b->conn;
    FacetSides sides;
    if (mesh.partial) sides = FacetSides{b->side, b->adjacent};
    else sides = facet_sides(mesh, *b);
    for (std::size_t f = 0; f < b->num_cells(); ++f) {
      if (sides.side[f] == 0) {  // named by its centre: the same on every rank's part of the mesh
        double xc[3] = {0, 0, 0};
        for (int a = 0; a < b->nodes_per_cell; ++a)
          for (int d = 0; d < 3; ++d) xc[d] += mesh.coord(b->conn[f * static_cast<std::size_t>(b->nodes_per_cell) + static_cast<std::size_t>(a)])[d] / b->nodes_per_cell;
        std::ostringstream os;
        os << where << ": the facet of group '" << group << "' centred at (" << xc[0] << ", " << xc[1] << ", " << xc[2]
           << ") bounds no volume cell of the mesh";
        throw InputError(os.str());
      }
      of.orientation.push_back(sides.side[f]);
      of.adjacent_cell.push_back(sides.adjacent[f]);
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

namespace {

// A fluid cavity's wall ends on planes normal to its axis (its ends) and planes through it
// (symmetry cuts), or the volume of assembly/FluidCavity.hpp is not the cavity's: every
// edge of the wall that only one of its facets has must lie at one axial coordinate or be
// coplanar with the axis, (x_a - x0) . ((x_b - x_a) x a) = 0. (An edge parallel to the axis
// passes either way: which plane through it closes the cavity is the deck's `axis point`.)
void check_cavity_rim(const FluidCavitySpec& c, const Mesh& mesh, const std::vector<OrientedFacets>& facets, const std::string& where) {
  std::map<std::pair<GId, GId>, int> edges;
  for (const OrientedFacets& of : facets) {
    const int corners = (of.type == CellType::Tri3 || of.type == CellType::Tri6) ? 3 : 4;
    for (std::size_t f = 0; f < of.num_facets(); ++f)
      for (int k = 0; k < corners; ++k) {
        GId a = of.conn[f * static_cast<std::size_t>(of.nodes_per_facet) + static_cast<std::size_t>(k)];
        GId b = of.conn[f * static_cast<std::size_t>(of.nodes_per_facet) + static_cast<std::size_t>((k + 1) % corners)];
        ++edges[{std::min(a, b), std::max(a, b)}];
      }
  }
  const double L = mesh.bounding_box().diagonal(), tol = 1e-8 * L;
  const double* ax = c.axis.data();
  for (const auto& [e, n] : edges) {
    if (n != 1) continue;
    const double *xa = mesh.coord(e.first), *xb = mesh.coord(e.second);
    double y[3], d[3];
    for (int k = 0; k < 3; ++k) y[k] = xa[k] - c.point[static_cast<std::size_t>(k)], d[k] = xb[k] - xa[k];
    const double dxa[3] = {d[1] * ax[2] - d[2] * ax[1], d[2] * ax[0] - d[0] * ax[2], d[0] * ax[1] - d[1] * ax[0]};
    const bool end_plane = std::abs(d[0] * ax[0] + d[1] * ax[1] + d[2] * ax[2]) <= tol;
    const bool cut_plane = std::abs(y[0] * dxa[0] + y[1] * dxa[1] + y[2] * dxa[2]) <= tol * L;
    if (!end_plane && !cut_plane)
      throw InputError(where + ": the cavity's wall '" + c.group + "' ends at the edge of nodes " + std::to_string(e.first) + " and " +
                       std::to_string(e.second) + ", which lies neither on a plane normal to the axis nor on a plane through it "
                       "('axis point', 'axis'); the cavity must be closed by such planes (its ends, symmetry cuts)");
  }
}

}  // namespace

Loads resolve_loads(const Config& cfg, const Mesh& mesh) {
  Loads loads;
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
        if (lc.normal) {
          d.normal = true;
          d.normal_value = lc.value;
          d.components = {true, true, mesh.dim == 3};
          d.n = plane_normal(mesh, d.nodes, where + "->boundary", lc.group);
        }
        if (mesh.dim == 2 && lc.all_components) d.components[2] = false;
        if (mesh.dim == 2 && d.components[2])
          throw InputError(where + "->components: 'z' is not a component of a 2D (plane strain) problem");
        loads.dirichlet.push_back(std::move(d));
        break;
      }
      case LoadConfig::Type::Traction:
      case LoadConfig::Type::Pressure:
      case LoadConfig::Type::FluidCavity: {
        int cavity = -1;
        if (lc.type == LoadConfig::Type::FluidCavity) {
          if (mesh.dim != 3) throw InputError(where + ": a fluid cavity needs a 3D mesh (the mesh is " + std::to_string(mesh.dim) + "D)");
          cavity = static_cast<int>(loads.cavities.size());
          loads.cavities.push_back({lc.name, lc.group, lc.volume_ratio, lc.bulk_modulus, lc.axis_point, lc.axis, lc.ramp});
          check_cavity_rim(loads.cavities.back(), mesh, oriented_facets(mesh, lc.group, where + "->boundary"), where);
        }
        for (OrientedFacets& of : oriented_facets(mesh, lc.group, where + "->boundary")) {
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
          fl.cavity = cavity;
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
  if (cfg.problem.axisymmetric()) {
    // u_r = 0 on the axis (prepare_axisymmetric_mesh put its nodes at x = 0 exactly); the
    // set is there (perhaps empty) in every axisymmetric run, on every rank alike.
    DirichletSet d;
    d.name = axis_set_name();
    d.group = "(nodes at r = 0)";
    for (std::size_t i = 0; i < mesh.num_stored_nodes(); ++i)
      if (mesh.x[3 * i] == 0.0) d.nodes.push_back(mesh.stored_node(i));
    std::sort(d.nodes.begin(), d.nodes.end());
    d.components = {true, false, false};
    d.ramp.kind = Ramp::Kind::Constant;
    loads.dirichlet.push_back(std::move(d));
  }
  return loads;
}

}  // namespace stentor
