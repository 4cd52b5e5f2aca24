#include "geometry/ArteryGenerator.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "deck/Config.hpp"
#include "geometry/AppendGroups.hpp"
#include "geometry/TubeGrid.hpp"
#include "stentor/format.hpp"

namespace stentor {
namespace {

// Where the tube goes and what its groups are called: its proximal end at z = z0 (the
// artery's own z = 0: the plaque's profile is measured from there), the group of its cut
// plane at the kept sector's end (theta = 0 is always `symmetry_y`), and the prefix of its
// outer and end facet groups.
struct Frame {
  double z0 = 0.0;
  std::string sector_plane;  // symmetry_x, symmetry_y or symmetry_sector
  std::string prefix;        // "" or "artery_"
};

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

// The tube's nodes, numbered from 0 (g.base is not added).
std::vector<double> nodes(const ArteryConfig& a, TubeGrid g, double z0) {
  g.base = 0;
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
        x[3 * n + 2] = z0 + z;
      }
    }
  return x;
}

// A curved artery (ArteryConfig::centreline_radius): the nodes of the straight tube, from
// `first` on, mapped onto the bent one. The map takes the tube's cross-sections z = const to
// the planes through the bend's axis at the angle phi = (z - length / 2) / R, rigidly, so
// every cell keeps its orientation and the plaque its profile along the centreline.
void bend(const ArteryConfig& a, std::size_t first, std::vector<double>& x) {
  const double R = a.centreline_radius, zm = 0.5 * a.length;
  for (std::size_t n = 3 * first; n + 2 < x.size(); n += 3) {
    const double rho = R - x[n], phi = (x[n + 2] - zm) / R;
    x[n] = R - rho * std::cos(phi);
    x[n + 2] = zm + rho * std::sin(phi);
  }
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

void boundaries(const ArteryConfig& a, const TubeGrid& g, const Frame& fr, int first_tag, Mesh& m) {
  std::map<std::string, std::vector<GId>> f;
  auto add = [&](const std::string& name, int i, int j, int k, int face) { g.face(i, j, k, face, f[name]); };
  const std::string outer = fr.prefix + "outer", proximal = fr.prefix + "end_proximal", distal = fr.prefix + "end_distal";
  for (int j = 0; j < g.cells_z; ++j)
    for (int i = 0; i < g.cells_t; ++i) {
      add("lumen", i, j, 0, 0);
      add(outer, i, j, g.cells_r - 1, 1);
    }
  for (int i = 0; i < g.cells_t; ++i)
    for (int k = 0; k < g.cells_r; ++k) {
      add(proximal, i, 0, k, 2);
      add(a.half_length ? "symmetry_z" : distal, i, g.cells_z - 1, k, 3);
    }
  if (!g.periodic)
    for (int j = 0; j < g.cells_z; ++j)
      for (int k = 0; k < g.cells_r; ++k) {
        add("symmetry_y", 0, j, k, 4);                // theta = 0
        add(fr.sector_plane, g.cells_t - 1, j, k, 5);  // theta = the kept sector's end
      }
  std::vector<std::pair<std::string, std::vector<GId>>> ordered;
  for (const std::string& name : {std::string("lumen"), outer, proximal, distal, std::string("symmetry_x"),
                                  std::string("symmetry_y"), std::string("symmetry_sector"), std::string("symmetry_z")}) {
    auto it = f.find(name);
    if (it != f.end()) ordered.emplace_back(name, std::move(it->second));
  }
  append_quads(std::move(ordered), first_tag, m);
}

// Appends the tube g (its nodes numbered from g.base = the nodes already in m) to m: the
// layers' volume groups from the physical tag `tag` on (then `plaque`), their facet groups
// from facet_tag on (joining m's symmetry groups).
void add_tube(const ArteryConfig& a, const TubeGrid& g, const Frame& fr, int tag, int facet_tag,
              const std::string& source, Mesh& m) {
  const std::vector<double> x = nodes(a, g, fr.z0);
  const std::size_t first = m.x.size() / 3;
  m.x.insert(m.x.end(), x.begin(), x.end());
  // Cell ids consecutive within each block, in the order the blocks are appended (the
  // plaque's cells, picked out of the innermost layer, after the layers': output writers
  // take a block's cells as one range of ids).
  GId next_cell = next_cell_id(m);
  auto number = [&next_cell](CellBlock& b) {
    for (std::size_t c = 0; c < b.num_cells(); ++c) b.cell_id.push_back(next_cell++);
  };
  int k0 = 0;
  CellBlock plaque = hex_block("plaque", tag + 3);
  for (int l = 0; l < 3; ++l) {
    CellBlock b = hex_block(kArteryLayer[l], tag + l);
    const int n = l == 0 ? a.cells_inner_layer() : a.elements_layer[l];
    for (int j = 0; j < g.cells_z; ++j)
      for (int i = 0; i < g.cells_t; ++i)
        for (int k = k0; k < k0 + n; ++k) {
          GId h[8];
          g.hex(i, j, k, h);
          // Cells of the innermost layer inside the healthy lumen (centroid r < Ri) are plaque.
          CellBlock& into = l == 0 && a.has_plaque() && centroid_radius(m.x, h) < a.inner_radius() ? plaque : b;
          into.conn.insert(into.conn.end(), h, h + 8);
        }
    k0 += n;
    number(b);
    m.volumes.push_back(std::move(b));
  }
  if (a.has_plaque()) {
    if (plaque.conn.empty())
      throw InputError(source + ": the plaque ('Mesh->Artery->plaque stenosis' = " + format_number(a.plaque_stenosis) +
                       ") is thinner than the cells that would hold it: raise 'Mesh->Artery->elements through plaque' or "
                       "'elements along'");
    number(plaque);
    m.volumes.push_back(std::move(plaque));
  }
  if (a.curved()) bend(a, first, m.x);
  boundaries(a, g, fr, facet_tag, m);
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
  const TubeGrid g{a.cells_around(), a.cells_along(), a.cells_through(), a.sector == "full"};
  Mesh m;
  m.dim = 3;
  m.source = source;
  add_tube(a, g, Frame{0.0, a.sector == "quarter" ? "symmetry_x" : "symmetry_y", ""}, 1, 4, source, m);
  return m;
}

void add_artery(const ArteryConfig& artery, const StentConfig& s, double max_cells, const std::string& source, Mesh& m) {
  const std::string why = artery_around_stent_error(artery, s);
  if (!why.empty()) throw InputError(source + ": " + why);
  const ArteryConfig a = with_stent_reductions(artery, s);
  const TubeGrid g{cells_around_stent(a, s), a.cells_along(), a.cells_through(), s.sector == "full",
                   static_cast<GId>(m.x.size() / 3)};
  const double cells = static_cast<double>(g.cells_t) * g.cells_z * g.cells_r + static_cast<double>(m.num_volume_cells());
  if (cells > max_cells)
    throw InputError(source + ": the stent and the artery would have " + format_number(cells) +
                     " cells, more than 'Mesh->max cells' = " + format_number(max_cells) +
                     "; use fewer 'Mesh->Artery->elements around', 'elements along' or elements "
                     "through the layers, or raise 'Mesh->max cells' to mesh this fine on purpose");
  const Frame fr{z_begin_around_stent(a, s), s.sector == "quarter" ? "symmetry_x" : "symmetry_sector", "artery_"};
  const int tag = next_tag(m);
  add_tube(a, g, fr, tag, tag + (a.has_plaque() ? 4 : 3), source, m);
}

}  // namespace stentor
