#include "mesh/GmshReader.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <new>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "mesh/GeoScreen.hpp"
#include "mesh/Progress.hpp"
#include "mesh/MshScreen.hpp"

namespace stentor {
namespace {

// gmsh is a process-wide singleton: initialize on construction, always finalize.
class GmshSession {
 public:
  explicit GmshSession(bool verbose) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
    // No exceptions from gmsh: in 4.8 an exception thrown out of its .geo parser
    // can leave the parser broken for every later file of the process. Errors are
    // read back from the logger instead.
    gmsh::option::setNumber("General.AbortOnError", 0);
    // ONELAB parameters (a .geo's DefineNumber[..., Name "Parameters/h"]) outlive
    // gmsh::finalize(): without this, a second .geo read by the same process would
    // take the first file's `h` and may mesh at a wildly wrong size.
    gmsh::onelab::clear();
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
    } catch (...) {
    }
    try {
      gmsh::finalize();
    } catch (...) {
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // Error lines gmsh logged since the last call.
  std::vector<std::string> errors() {
    std::vector<std::string> log, out;
    try {
      gmsh::logger::get(log);
    } catch (...) {
    }
    for (std::size_t i = seen_; i < log.size(); ++i)
      if (log[i].rfind("Error", 0) == 0) out.push_back(log[i]);
    seen_ = std::max(seen_, log.size());
    return out;
  }

 private:
  std::size_t seen_ = 0;
};

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

// Runs a gmsh call; turns gmsh's exceptions (std::string in 4.8, std::exception
// in later versions) and logged errors into an InputError.
template <class F>
void gmsh_call(GmshSession& s, const std::string& file, const char* what, F&& f) {
  std::string msg;
  bool failed = false;
  try {
    f();
  } catch (const std::bad_alloc&) {
    s.errors();
    throw InputError(file + ": gmsh ran out of memory trying to " + what +
                     "; the mesh is too fine for this machine (use a larger 'Mesh->size')");
  } catch (const std::string& e) {
    failed = true;
    msg = e;
  } catch (const std::exception& e) {
    failed = true;
    msg = e.what();
  } catch (...) {
    failed = true;
    msg = "unknown error";
  }
  std::vector<std::string> errs = s.errors();
  if (!failed && errs.empty()) return;
  if (!errs.empty()) {
    // Prefer the logged lines (they may hold more than the exception text).
    for (auto& e : errs)
      if (e.rfind("Error: ", 0) == 0) e = e.substr(7);
    msg = join(errs, "; ");
  }
  throw InputError(file + ": gmsh could not " + what + ": " + msg);
}

std::string lower_extension(const std::string& path) {
  auto slash = path.find_last_of("/\\");
  auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot);
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

CellType cell_type_from_gmsh(int t) {
  switch (t) {
    case 15: return CellType::Point1;
    case 1: return CellType::Line2;
    case 8: return CellType::Line3;
    case 2: return CellType::Tri3;
    case 9: return CellType::Tri6;
    case 3: return CellType::Quad4;
    case 16: return CellType::Quad8;
    case 4: return CellType::Tet4;
    case 11: return CellType::Tet10;
    case 5: return CellType::Hex8;
    default: return CellType::Invalid;
  }
}

bool supported_volume_type(int dim, CellType t) {
  if (dim == 2) return t == CellType::Tri3 || t == CellType::Tri6 || t == CellType::Quad4;
  return t == CellType::Tet4 || t == CellType::Tet10 || t == CellType::Hex8;
}

std::string gmsh_type_name(int t) {
  try {
    std::string name;
    int d, o, nn, np;
    std::vector<double> xi;
    gmsh::model::mesh::getElementProperties(t, name, d, o, nn, xi, np);
    return name;
  } catch (...) {
    return "type " + std::to_string(t);
  }
}

void set_size_max(double size) {
  gmsh::option::setNumber("Mesh.MeshSizeMax", size);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
}

// Mean length of the 1D elements of the current mesh (0 when there are none).
double mean_edge_length() {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> etags, ntags;
  gmsh::model::mesh::getElements(types, etags, ntags, 1, -1);
  std::vector<std::size_t> tags;
  std::vector<double> xyz, param;
  gmsh::model::mesh::getNodes(tags, xyz, param, -1, -1, true, false);
  std::unordered_map<std::size_t, std::size_t> at;
  for (std::size_t i = 0; i < tags.size(); ++i) at.emplace(tags[i], i);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < types.size(); ++k) {
    const std::size_t per = etags[k].empty() ? 0 : ntags[k].size() / etags[k].size();
    for (std::size_t e = 0; per >= 2 && e < etags[k].size(); ++e) {
      const auto a = at.find(ntags[k][per * e]), b = at.find(ntags[k][per * e + 1]);
      if (a == at.end() || b == at.end()) continue;
      double d2 = 0.0;
      for (int c = 0; c < 3; ++c) d2 += std::pow(xyz[3 * a->second + c] - xyz[3 * b->second + c], 2);
      sum += std::sqrt(d2);
      ++n;
    }
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

// Refuses to mesh when the number of cells of size h filling the bounding box of the
// geometry (simplices per h^dim: 2.3 in 2D, 8.5 in 3D, x4 for subdivided hexes) is
// above cfg.max_cells. Cheap and coarse (it over-estimates thin shapes): it stops
// a tiny size from meshing for hours or exhausting memory.
// Returns the estimate.
double check_cell_estimate(const MeshConfig& cfg, const std::string& file, int dim, double h, const char* source) {
  double lo[3], hi[3];
  gmsh::model::getBoundingBox(-1, -1, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  std::vector<double> ext;
  for (int c = 0; c < 3; ++c) ext.push_back(std::max(hi[c] - lo[c], 0.0));
  std::sort(ext.rbegin(), ext.rend());
  double est = dim == 3 ? 8.5 : 2.3;
  if (dim == 3 && cfg.recombine) est *= 4.0;
  for (int c = 0; c < dim; ++c) est *= std::max(ext[static_cast<std::size_t>(c)], h) / h;
  if (est <= cfg.max_cells) return est;
  std::ostringstream os;
  os << file << ": meshing with element size " << h << " (" << source << ") would make about " << std::setprecision(3)
     << est << " cells, more than 'Mesh->max cells' = " << cfg.max_cells
     << "; use a larger 'Mesh->size', or raise 'Mesh->max cells' in the deck to mesh this fine on purpose";
  throw InputError(os.str());
}

// Meshes the .geo model already opened: bounded by check_cell_estimate, with the
// deck's size (or the .geo's own, estimated from the curve mesh), order and recombination.
// Meshing longer than 10 s prints a progress line every 10 s.
void mesh_geo(GmshSession& session, const MeshConfig& cfg, const std::string& file, int dim) {
  double estimate = 0.0;
  if (cfg.size > 0) {
    estimate = check_cell_estimate(cfg, file, dim, cfg.size, "'Mesh->size'");
    gmsh_call(session, file, "mesh the geometry", [&] { set_size_max(cfg.size); });
  } else {
    gmsh_call(session, file, "mesh the curves", [&] { gmsh::model::mesh::generate(1); });
    const double h = mean_edge_length();
    if (h > 0) estimate = check_cell_estimate(cfg, file, dim, h, "mean curve element length of the .geo's own sizes");
  }
  std::ostringstream detail;
  if (estimate > 0) detail << " (at most about " << std::setprecision(2) << estimate << " cells expected)";
  const Progress progress(std::cout, "meshing  " + file, detail.str(), 10.0);
  gmsh_call(session, file, "mesh the geometry", [&] {
    gmsh::option::setNumber("Mesh.ElementOrder", cfg.order);
    gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);
    if (cfg.recombine) {
      if (dim == 2) {
        // Blossom recombination of the default (Frontal-Delaunay) triangulation.
        // (Mesh.Algorithm = 8, "Frontal-Delaunay for quads", crashes gmsh 4.8.4.)
        gmsh::option::setNumber("Mesh.RecombineAll", 1);
      } else {
        gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 2);  // tets -> hexes
      }
    }
    gmsh::model::mesh::generate(dim);
  });
}

struct RawBlock {
  std::string name;
  int tag = -1;
  int gdim = 0;
  int gmsh_type = 0;
  std::vector<std::size_t> nodes;  // gmsh node tags
};

}  // namespace

Mesh read_mesh(const MeshConfig& cfg, bool verbose) {
  const std::string& file = cfg.file;
  {
    std::ifstream f(file, std::ios::binary);
    if (!f) throw InputError(file + ": cannot open mesh file (missing or unreadable)");
  }
  if (cfg.dimension != 0 && cfg.dimension != 2 && cfg.dimension != 3)
    throw InputError(file + ": mesh dimension must be 2 or 3 (or 0 for automatic), got " +
                     std::to_string(cfg.dimension));
  const bool is_msh = lower_extension(file) == ".msh";
  if (!is_msh) {
    if (cfg.order != 1 && cfg.order != 2)
      throw InputError(file + ": mesh order must be 1 or 2, got " + std::to_string(cfg.order));
    if (cfg.recombine && cfg.order == 2)
      throw InputError(file + ": recombine (quads/hexes) needs order 1: quad8/hex20 bodies are not supported");
    if (cfg.size < 0) throw InputError(file + ": mesh size must be >= 0");
  }

  if (!is_msh) screen_geo_file(file);  // before gmsh runs any of it
  if (is_msh) screen_msh_file(file);   // counts gmsh would trust (a crash, a hang)
  GmshSession session(verbose);
  gmsh_call(session, file, "read the file", [&] { gmsh::open(file); });

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  int dim = cfg.dimension;
  if (dim == 0) {
    for (auto& g : groups) dim = std::max(dim, g.first);
    if (dim < 2) dim = std::max(2, std::min(3, gmsh::model::getDimension()));
  }
  bool has_body = false;
  for (auto& g : groups) has_body = has_body || g.first == dim;
  if (!has_body)
    throw InputError(file + ": mesh has no physical group of dimension " + std::to_string(dim) +
                     ": bodies must be physical " + (dim == 2 ? "surfaces" : "volumes"));

  if (!is_msh) mesh_geo(session, cfg, file, dim);

  // Gather the cells of every physical group of dimension <= dim.
  std::vector<RawBlock> vol_raw, bnd_raw;
  std::map<int, std::string> volume_entity_owner;  // entity tag -> group name
  for (auto& g : groups) {
    const int gd = g.first, gt = g.second;
    if (gd > dim) continue;
    std::string name;
    gmsh::model::getPhysicalName(gd, gt, name);
    if (name.empty()) name = "tag" + std::to_string(gt);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(gd, gt, entities);
    std::map<int, std::vector<std::size_t>> by_type;  // gmsh type -> node tags
    for (int e : entities) {
      if (gd == dim) {
        auto it = volume_entity_owner.find(e);
        if (it != volume_entity_owner.end())
          throw InputError(file + ": physical groups '" + it->second + "' and '" + name +
                           "' share " + (dim == 2 ? "surface " : "volume ") + std::to_string(e) +
                           ": bodies must not overlap");
        volume_entity_owner[e] = name;
      }
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> etags, ntags;
      gmsh::model::mesh::getElements(types, etags, ntags, gd, e);
      for (std::size_t k = 0; k < types.size(); ++k) {
        auto& dst = by_type[types[k]];
        dst.insert(dst.end(), ntags[k].begin(), ntags[k].end());
      }
    }
    for (auto& [type, nodes] : by_type) {
      if (nodes.empty()) continue;
      const CellType ct = cell_type_from_gmsh(type);
      if (ct == CellType::Invalid)
        throw InputError(file + ": physical group '" + name + "' contains elements of gmsh type '" +
                         gmsh_type_name(type) + "' (" + std::to_string(type) +
                         "), which Stentor does not support (supported: point, line2, line3, tri3, "
                         "tri6, quad4, quad8 (boundaries only), tet4, tet10, hex8)");
      if (gd == dim && !supported_volume_type(dim, ct))
        throw InputError(file + ": physical group '" + name + "' contains " + cell_name(ct) +
                         " elements (gmsh '" + gmsh_type_name(type) + "'), not supported as " +
                         std::to_string(dim) + "D bodies (supported: " +
                         (dim == 2 ? "tri3, tri6, quad4" : "tet4, tet10, hex8") + ")");
      RawBlock rb;
      rb.name = name;
      rb.tag = gt;
      rb.gdim = gd;
      rb.gmsh_type = type;
      rb.nodes = std::move(nodes);
      (gd == dim ? vol_raw : bnd_raw).push_back(std::move(rb));
    }
  }
  if (vol_raw.empty())
    throw InputError(file + ": the physical " + (dim == 2 ? "surfaces" : "volumes") +
                     " of the mesh have no elements");

  // All nodes, then the compact numbering of the used ones (increasing gmsh tag).
  std::vector<std::size_t> all_tags;
  std::vector<double> all_xyz, param;
  gmsh::model::mesh::getNodes(all_tags, all_xyz, param, -1, -1, false, false);
  std::vector<std::size_t> used;
  for (auto* list : {&vol_raw, &bnd_raw})
    for (auto& rb : *list) used.insert(used.end(), rb.nodes.begin(), rb.nodes.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());

  std::unordered_map<std::size_t, std::size_t> pos_of_tag;  // gmsh tag -> index in all_tags
  pos_of_tag.reserve(all_tags.size());
  for (std::size_t i = 0; i < all_tags.size(); ++i) pos_of_tag.emplace(all_tags[i], i);
  std::unordered_map<std::size_t, GId> compact;
  compact.reserve(used.size());

  Mesh m;
  m.dim = dim;
  m.source = file;
  m.x.resize(3 * used.size());
  for (std::size_t i = 0; i < used.size(); ++i) {
    auto it = pos_of_tag.find(used[i]);
    if (it == pos_of_tag.end())
      throw InputError(file + ": element refers to node " + std::to_string(used[i]) +
                       ", which the mesh does not define");
    for (int c = 0; c < 3; ++c) m.x[3 * i + c] = all_xyz[3 * it->second + c];
    compact.emplace(used[i], static_cast<GId>(i));
  }

  if (dim == 2) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t i = 0; i < used.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], m.x[3 * i + c]);
        hi[c] = std::max(hi[c], m.x[3 * i + c]);
      }
    const double L = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
    for (std::size_t i = 0; i < used.size(); ++i) {
      double& z = m.x[3 * i + 2];
      if (std::abs(z) > 1e-10 * L) {
        std::ostringstream os;
        os << file << ": a 2D mesh must lie in the z = 0 plane, but node " << i << " is at ("
           << m.x[3 * i] << ", " << m.x[3 * i + 1] << ", " << z << ")";
        throw InputError(os.str());
      }
      z = 0.0;
    }
  }

  auto make_blocks = [&](std::vector<RawBlock>& raw, std::vector<CellBlock>& out) {
    GId next_id = 0;
    for (auto& rb : raw) {
      CellBlock b;
      b.name = rb.name;
      b.physical_tag = rb.tag;
      b.type = cell_type_from_gmsh(rb.gmsh_type);
      b.nodes_per_cell = cell_num_nodes(b.type);
      b.conn.resize(rb.nodes.size());
      for (std::size_t k = 0; k < rb.nodes.size(); ++k) b.conn[k] = compact.at(rb.nodes[k]);
      const std::size_t nc = b.num_cells();
      b.cell_id.resize(nc);
      for (std::size_t c = 0; c < nc; ++c) b.cell_id[c] = next_id++;
      out.push_back(std::move(b));
    }
  };
  make_blocks(vol_raw, m.volumes);
  make_blocks(bnd_raw, m.boundaries);
  return m;
}

}  // namespace stentor
