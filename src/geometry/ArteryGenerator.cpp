#include "geometry/ArteryGenerator.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "deck/Config.hpp"
#include "geometry/TubeGrid.hpp"
#include "stentor/format.hpp"

namespace stentor {
namespace {

// (cos, sin) of theta = 2 pi i / N, exact on the axes.
void unit_circle(int i, int N, double& c, double& s) {
  const int q = 4 * i;
  if (q == 0 || q == 4 * N) { c = 1.0; s = 0.0; return; }
  if (q == N) { c = 0.0; s = 1.0; return; }
  if (q == 2 * N) { c = -1.0; s = 0.0; return; }
  if (q == 3 * N) { c = 0.0; s = -1.0; return; }
  const double t = 2.0 * kPi * i / N;
  c = std::cos(t);
  s = std::sin(t);
}

// The node radii through the wall of a column whose lumen is narrowed by the plaque
// thickness h: the innermost layer from Ri - h (cells_inner_layer() cells), the others
// between their interfaces.
std::vector<double> radii(const ArteryConfig& a, double h) {
  std::vector<double> r{a.inner_radius() - h};
  double r0 = r[0];
  for (int l = 0; l < 3; ++l) {
    const double r1 = a.layer_outer_radius(l);
    const int n = l == 0 ? a.cells_inner_layer() : a.elements_layer[l];
    for (int k = 1; k <= n; ++k) r.push_back(k == n ? r1 : r0 + (r1 - r0) * k / n);
    r0 = r1;
  }
  return r;
}

double z_of(const ArteryConfig& a, const TubeGrid& g, int j) {
  return j == g.cells_z ? a.modelled_length() : a.modelled_length() * j / g.cells_z;
}

std::vector<double> nodes(const ArteryConfig& a, const TubeGrid& g) {
  std::vector<double> x(3 * static_cast<std::size_t>(g.nt()) * (g.cells_z + 1) * (g.cells_r + 1));
  for (int j = 0; j <= g.cells_z; ++j)
    for (int i = 0; i < g.nt(); ++i) {
      double c, s;
      unit_circle(i, a.elements_around, c, s);
      const double z = z_of(a, g, j);
      const std::vector<double> r = radii(a, a.plaque_thickness(2.0 * kPi * i / a.elements_around, z));
      for (int k = 0; k <= g.cells_r; ++k) {
        const GId n = g.node(i, j, k);
        x[3 * n] = r[k] * c;
        x[3 * n + 1] = r[k] * s;
        x[3 * n + 2] = z;
      }
    }
  return x;
}

CellBlock hex_block(const std::string& name, int tag) {
  CellBlock b;
  b.name = name;
  b.physical_tag = tag;
  b.type = CellType::Hex8;
  b.nodes_per_cell = 8;
  return b;
}

// Mean distance of a hex's 8 nodes from the z axis.
double centroid_radius(const std::vector<double>& x, const GId* h) {
  double r = 0.0;
  for (int n = 0; n < 8; ++n) r += std::hypot(x[3 * h[n]], x[3 * h[n] + 1]) / 8.0;
  return r;
}

CellBlock quads(const std::string& name, std::vector<GId> conn) {
  CellBlock b;
  b.name = name;
  b.type = CellType::Quad4;
  b.nodes_per_cell = 4;
  b.conn = std::move(conn);
  return b;
}

void boundaries(const ArteryConfig& a, const TubeGrid& g, Mesh& m) {
  std::map<std::string, std::vector<GId>> f;
  auto add = [&](const char* name, int i, int j, int k, int face) { g.face(i, j, k, face, f[name]); };
  for (int j = 0; j < g.cells_z; ++j)
    for (int i = 0; i < g.cells_t; ++i) {
      add("lumen", i, j, 0, 0);
      add("outer", i, j, g.cells_r - 1, 1);
    }
  for (int i = 0; i < g.cells_t; ++i)
    for (int k = 0; k < g.cells_r; ++k) {
      add("end_proximal", i, 0, k, 2);
      add(a.half_length ? "symmetry_z" : "end_distal", i, g.cells_z - 1, k, 3);
    }
  if (!g.periodic)
    for (int j = 0; j < g.cells_z; ++j)
      for (int k = 0; k < g.cells_r; ++k) {
        add("symmetry_y", 0, j, k, 4);  // theta = 0
        add(a.sector == "quarter" ? "symmetry_x" : "symmetry_y", g.cells_t - 1, j, k, 5);  // theta = pi/2 or pi
      }
  int tag = 4;
  GId next_id = 0;
  for (const char* name : {"lumen", "outer", "end_proximal", "end_distal", "symmetry_x", "symmetry_y", "symmetry_z"}) {
    auto it = f.find(name);
    if (it == f.end()) continue;
    CellBlock b = quads(name, std::move(it->second));
    b.physical_tag = tag++;
    for (std::size_t c = 0; c < b.num_cells(); ++c) b.cell_id.push_back(next_id++);
    m.boundaries.push_back(std::move(b));
  }
}

}  // namespace

Mesh generate_artery(const ArteryConfig& a, double max_cells, const std::string& source) {
  const std::string why = artery_config_error(a);
  if (!why.empty()) throw InputError(source + ": " + why);
  if (a.cells() > max_cells)
    throw InputError(source + ": the artery would have " + format_number(a.cells()) +
                     " cells, more than 'Mesh->max cells' = " + format_number(max_cells) +
                     "; use fewer 'Mesh->Artery->elements around', 'elements along' or elements "
                     "through the layers, or raise 'Mesh->max cells' to mesh this fine on purpose");
  const bool periodic = a.sector == "full";
  const int ct = a.cells_around(), cz = a.cells_along(), cr = a.cells_through();
  const TubeGrid g{ct, cz, cr, periodic};
  Mesh m;
  m.dim = 3;
  m.source = source;
  m.x = nodes(a, g);
  GId next_cell = 0;
  int k0 = 0;
  CellBlock plaque = hex_block("plaque", 4);
  for (int l = 0; l < 3; ++l) {
    CellBlock b = hex_block(kArteryLayer[l], l + 1);
    const int n = l == 0 ? a.cells_inner_layer() : a.elements_layer[l];
    for (int j = 0; j < cz; ++j)
      for (int i = 0; i < ct; ++i)
        for (int k = k0; k < k0 + n; ++k) {
          GId h[8];
          g.hex(i, j, k, h);
          // Cells of the innermost layer inside the healthy lumen (centroid r < Ri) are plaque.
          CellBlock& into = l == 0 && a.has_plaque() && centroid_radius(m.x, h) < a.inner_radius() ? plaque : b;
          into.conn.insert(into.conn.end(), h, h + 8);
          into.cell_id.push_back(next_cell++);
        }
    k0 += n;
    m.volumes.push_back(std::move(b));
  }
  if (a.has_plaque()) {
    if (plaque.conn.empty())
      throw InputError(source + ": the plaque ('Mesh->Artery->plaque stenosis' = " + format_number(a.plaque_stenosis) +
                       ") is thinner than the cells that would hold it: raise 'Mesh->Artery->elements through plaque' or "
                       "'elements along'");
    m.volumes.push_back(std::move(plaque));
  }
  boundaries(a, g, m);
  return m;
}

}  // namespace stentor
