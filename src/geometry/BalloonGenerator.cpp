#include "geometry/BalloonGenerator.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "deck/Config.hpp"
#include "geometry/AppendGroups.hpp"
#include "geometry/TubeGrid.hpp"
#include "stentor/format.hpp"

namespace stentor {
namespace {

// (cos, sin) of theta, exact on the planes y = 0 and x = 0.
void direction(double theta, double& c, double& s) {
  if (theta == 0.0) { c = 1.0, s = 0.0; return; }
  if (std::abs(theta - 0.5 * kPi) < 1e-14) { c = 0.0, s = 1.0; return; }
  c = std::cos(theta), s = std::sin(theta);
}

void add_nodes(const BalloonConfig& b, const StentConfig& s, const TubeGrid& t, Mesh& m) {
  const double th = s.sector_angle(), z0 = b.z_begin(s), z1 = b.z_end(s);
  const double ri = b.inner_radius(), ro = b.outer_radius();
  for (int j = 0; j <= t.cells_z; ++j)
    for (int i = 0; i < t.nt(); ++i) {
      double c, sn;
      direction(i == t.cells_t ? th : th * i / t.cells_t, c, sn);
      const double z = j == t.cells_z ? z1 : z0 + (z1 - z0) * j / t.cells_z;
      for (int k = 0; k <= t.cells_r; ++k) {
        const double r = k == t.cells_r ? ro : ri + (ro - ri) * k / t.cells_r;
        m.x.insert(m.x.end(), {r * c, r * sn, z});
      }
    }
}

void add_facets(const StentConfig& s, const TubeGrid& t, Mesh& m) {
  std::map<std::string, std::vector<GId>> f;
  auto add = [&](const std::string& name, int i, int j, int k, int face) { t.face(i, j, k, face, f[name]); };
  for (int j = 0; j < t.cells_z; ++j)
    for (int i = 0; i < t.cells_t; ++i) add("balloon_inner", i, j, 0, 0), add("balloon_outer", i, j, t.cells_r - 1, 1);
  for (int i = 0; i < t.cells_t; ++i)
    for (int k = 0; k < t.cells_r; ++k) {
      add("balloon_ends", i, 0, k, 2);
      add(s.half_length ? "symmetry_z" : "balloon_ends", i, t.cells_z - 1, k, 3);
    }
  if (!t.periodic)
    for (int j = 0; j < t.cells_z; ++j)
      for (int k = 0; k < t.cells_r; ++k) {
        add("symmetry_y", 0, j, k, 4);
        add(s.sector == "quarter" ? "symmetry_x" : "symmetry_sector", t.cells_t - 1, j, k, 5);
      }
  append_quads({f.begin(), f.end()}, next_tag(m), m);
}

}  // namespace

void add_balloon(const BalloonConfig& b, const StentConfig& s, double max_cells, const std::string& source, Mesh& m) {
  const std::string why = balloon_config_error(b, s);
  if (!why.empty()) throw InputError(source + ": " + why);
  const double cells = b.cells(s) + static_cast<double>(m.num_volume_cells());
  if (cells > max_cells)
    throw InputError(source + ": the stent and the balloon would have " + format_number(cells) +
                     " cells, more than 'Mesh->max cells' = " + format_number(max_cells) +
                     "; use a larger 'Mesh->Balloon->element length' or fewer 'elements through thickness', or raise "
                     "'Mesh->max cells' to mesh this fine on purpose");
  const TubeGrid t{b.cells_around(s), b.cells_along(s), b.elements_thickness, s.sector == "full",
                   static_cast<GId>(m.x.size() / 3)};
  add_nodes(b, s, t, m);
  CellBlock v;
  v.name = "balloon";
  v.physical_tag = next_tag(m);
  v.type = CellType::Hex8;
  v.nodes_per_cell = 8;
  GId id = next_cell_id(m);
  for (int j = 0; j < t.cells_z; ++j)
    for (int i = 0; i < t.cells_t; ++i)
      for (int k = 0; k < t.cells_r; ++k) {
        GId h[8];
        t.hex(i, j, k, h);
        v.conn.insert(v.conn.end(), h, h + 8);
        v.cell_id.push_back(id++);
      }
  m.volumes.push_back(std::move(v));
  add_facets(s, t, m);
}

}  // namespace stentor
