#include "mesh/GmshReader.hpp"

#include <fcntl.h>
#include <gmsh.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>
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

#include "deck/InputLimits.hpp"
#include "mesh/Confine.hpp"
#include "mesh/GeoScreen.hpp"
#include "mesh/Progress.hpp"
#include "mesh/MshScreen.hpp"

extern char** environ;

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
void check_cell_estimate(const MeshConfig& cfg, const std::string& file, int dim, double h, const char* source) {
  double lo[3], hi[3];
  gmsh::model::getBoundingBox(-1, -1, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  std::vector<double> ext;
  for (int c = 0; c < 3; ++c) ext.push_back(std::max(hi[c] - lo[c], 0.0));
  std::sort(ext.rbegin(), ext.rend());
  double est = dim == 3 ? 8.5 : 2.3;
  if (dim == 3 && cfg.recombine) est *= 4.0;
  for (int c = 0; c < dim; ++c) est *= std::max(ext[static_cast<std::size_t>(c)], h) / h;
  if (est <= cfg.max_cells) return;
  std::ostringstream os;
  os << file << ": meshing with element size " << h << " (" << source << ") would make about " << std::setprecision(3)
     << est << " cells, more than 'Mesh->max cells' = " << cfg.max_cells
     << "; use a larger 'Mesh->size', or raise 'Mesh->max cells' in the deck to mesh this fine on purpose";
  throw InputError(os.str());
}

// Meshes the .geo model already opened: bounded by check_cell_estimate, with the
// deck's size (or the .geo's own, estimated from the curve mesh), order and recombination.
void mesh_geo(GmshSession& session, const MeshConfig& cfg, const std::string& file, int dim) {
  if (cfg.size > 0) {
    check_cell_estimate(cfg, file, dim, cfg.size, "'Mesh->size'");
    gmsh_call(session, file, "mesh the geometry", [&] { set_size_max(cfg.size); });
  } else {
    gmsh_call(session, file, "mesh the curves", [&] { gmsh::model::mesh::generate(1); });
    const double h = mean_edge_length();
    if (h > 0) check_cell_estimate(cfg, file, dim, h, "mean curve element length of the .geo's own sizes");
  }
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

// The screens (mesh/GeoScreen.hpp, mesh/MshScreen.hpp) on the mesh file and everything
// gmsh would read with it; returns those files (the mesh file first).
std::vector<std::string> screen_mesh_file(const std::string& file) {
  if (lower_extension(file) != ".msh") return screen_geo_file(file);
  check_input_size(file, true, ".msh file");
  std::vector<std::string> files = {file};
  if (geo_screen_disabled()) return files;
  screen_msh_file(file);  // counts gmsh would trust (a crash, a hang)
  screen_options_file(file, 0, &files);
  return files;
}

// Mesh->Parameters: each must have been read by a DefineNumber of the .geo (gmsh then lists
// itself among the ONELAB parameter's clients); else the deck's value changed nothing.
void check_parameters_read(const MeshConfig& cfg, const std::string& file) {
  if (cfg.parameters.empty()) return;
  const auto read_by_gmsh = [](const std::string& name) {
    std::string json;
    gmsh::onelab::get(json, name);
    return json.find("\"clients\"") != std::string::npos;
  };
  std::vector<std::string> names, defined;
  gmsh::onelab::getNames(names);
  for (const std::string& n : names)  // the .geo's own, not gmsh's (Gmsh/..., "}Gmsh/...")
    if (n.find("Gmsh/") == std::string::npos && read_by_gmsh(n)) defined.push_back(n);
  for (const auto& p : cfg.parameters) {
    if (read_by_gmsh(p.first)) continue;
    const std::string shown = p.first.rfind("Parameters/", 0) == 0 ? p.first.substr(11) : p.first;
    throw InputError("'Mesh->Parameters->" + shown + "': " + file + " has no DefineNumber parameter '" + p.first +
                     "', so the value would change nothing; " +
                     (defined.empty() ? std::string("it defines none") : "its parameters: " + join(defined, ", ")));
  }
}

// read_mesh() in this process.
Mesh read_mesh_here(const MeshConfig& cfg, bool verbose) {
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

  screen_mesh_file(file);  // before gmsh runs any of it
  GmshSession session(verbose);
  for (const auto& [name, value] : cfg.parameters) gmsh::onelab::setNumber(name, {value});
  gmsh_call(session, file, "read the file", [&] { gmsh::open(file); });
  check_parameters_read(cfg, file);

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

// ------------------------------------------------------------- gmsh's own process
//
// gmsh runs the .geo language (loops, macros, includes) and meshes with no bound of its
// own: a .geo can loop forever, recurse, crash gmsh (a bad format in Printf, a size field
// of 1e-9 that runs out of memory inside an OpenMP region, where std::bad_alloc cannot be
// caught), or end the process. So stentor reads every mesh in a child process
// (`<stentor> --gmsh-helper DIR ...`, the same executable): it writes the Mesh into DIR,
// or the input error into DIR/error.txt; a crash, an exit or a run past
// 'Mesh->time limit' is an input error naming the file, and stentor goes on to report
// it like any other. The child's HOME is DIR (gmsh/FLTK write preferences there) and its
// address space is limited to the machine's memory (running out is a clean failure, not
// the OOM killer).

std::string g_helper_exe;  // empty: gmsh runs in this process

constexpr const char* kMeshFile = "mesh.bin";
constexpr const char* kErrorFile = "error.txt";
constexpr const char* kConfinementFile = "confinement.txt";  // "landlock ABI N" or "unconfined: why"

// Says once per run, in the log, that gmsh's process ran without the kernel's
// confinement (mesh/Confine.hpp), and why; the .geo screen was then the only guard.
void report_confinement(const std::string& dir) {
  static bool said = false;
  std::ifstream in(dir + "/" + kConfinementFile);
  std::string line;
  if (said || !std::getline(in, line) || line.rfind("unconfined: ", 0) != 0) return;
  said = true;
  std::cout << "warning: gmsh's process runs without Landlock confinement (" << line.substr(12)
            << "): the .geo screen alone keeps mesh scripts from writing, deleting or running anything\n"
            << std::flush;
}

std::string num17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A temporary folder, removed with everything in it.
struct TempDir {
  std::string path;
  TempDir() {
    std::error_code ec;
    std::string tmpl = (std::filesystem::temp_directory_path(ec) / "stentor-gmsh-XXXXXX").string();
    if (ec) tmpl = "/tmp/stentor-gmsh-XXXXXX";
    if (!::mkdtemp(tmpl.data()))
      throw std::runtime_error("cannot create a temporary folder for gmsh (" + tmpl + "): " + std::strerror(errno));
    path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

std::string signal_text(int sig) {
  const char* d = ::strsignal(sig);
  return "signal " + std::to_string(sig) + (d ? std::string(", ") + d : std::string());
}

Mesh read_mesh_in_child(const MeshConfig& cfg, bool verbose) {
  const std::string& file = cfg.file;
  {
    std::ifstream f(file, std::ios::binary);
    if (!f) throw InputError(file + ": cannot open mesh file (missing or unreadable)");
  }
  // The screens first, here: nothing of a refused file ever reaches gmsh.
  screen_mesh_file(file);
  TempDir dir;
  std::vector<std::string> args = {g_helper_exe, "--gmsh-helper", dir.path, file, num17(cfg.size),
                                   std::to_string(cfg.order), cfg.recombine ? "1" : "0", std::to_string(cfg.dimension),
                                   num17(cfg.max_cells), verbose ? "1" : "0", std::to_string(::getpid()),
                                   std::to_string(input_limits().text), std::to_string(input_limits().mesh)};
  for (const auto& [name, value] : cfg.parameters) {  // Mesh->Parameters: name, value pairs after the fixed ones
    args.push_back(name);
    args.push_back(num17(value));
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_s;
  for (char** e = environ; e && *e; ++e)
    if (std::strncmp(*e, "HOME=", 5) != 0 && std::strncmp(*e, "TMPDIR=", 7) != 0) env_s.emplace_back(*e);
  env_s.push_back("HOME=" + dir.path);
  env_s.push_back("TMPDIR=" + dir.path);
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t fa;
  posix_spawnattr_t attr;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  const std::string log = dir.path + "/gmsh.log";
  if (!verbose) {  // what gmsh or the C++ runtime prints when it fails: quoted in the message
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  }
  posix_spawnattr_init(&attr);
  posix_spawnattr_setpgroup(&attr, 0);  // its own process group: stopped as a whole
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, g_helper_exe.c_str(), &fa, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  if (rc != 0)
    throw std::runtime_error("cannot start gmsh's process (" + g_helper_exe + "): " + std::strerror(rc));

  int status = 0;
  bool timed_out = false;
  // gmsh reports nothing while it meshes: a line every 10 s from here (its own output goes
  // to its log), with the time limit that will stop it.
  std::ostringstream limit;
  limit << " (stopped at 'Mesh->time limit' = " << cfg.time_limit << " s)";
  const Progress progress(std::cout, "meshing  " + file, limit.str(), 10.0);
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(std::min(cfg.time_limit, 1e9)));
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) throw std::runtime_error(std::string("waitpid on gmsh's process: ") + std::strerror(errno));
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(-pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(-pid, SIGKILL);  // anything it left running
  report_confinement(dir.path);

  if (timed_out) {
    std::ostringstream os;
    os << file << ": gmsh did not finish reading" << (lower_extension(file) == ".msh" ? "" : " and meshing")
       << " it within 'Mesh->time limit' = " << cfg.time_limit
       << " s and was stopped (a loop or recursion in the .geo, or a mesh far too fine?); raise 'Mesh->time limit' "
          "to wait longer";
    throw InputError(os.str());
  }
  std::string last;  // the last line gmsh's process printed
  {
    std::istringstream in(slurp(log));
    for (std::string line; std::getline(in, line);)
      if (line.find_first_not_of(" \t\r") != std::string::npos) last = line.substr(0, 300);
  }
  const std::string said = last.empty() ? "" : " (it said: " + last + ")";
  if (WIFSIGNALED(status))
    throw InputError(file + ": gmsh crashed reading or meshing it (" + signal_text(WTERMSIG(status)) + ")" + said +
                     ": the file is malformed, or asks gmsh for more than it can do (out of memory?)");
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  const std::string error = slurp(dir.path + "/" + kErrorFile);
  if (code == 2 && !error.empty()) throw InputError(error);
  if (code == 1 && !error.empty()) throw std::runtime_error(error);
  if (code != 0)
    throw InputError(file + ": gmsh ended its process with exit status " + std::to_string(code) +
                     " while reading or meshing it" + (error.empty() ? said : ": " + error));
  const std::string bytes = slurp(dir.path + "/" + kMeshFile);
  try {
    return deserialize_mesh(std::vector<char>(bytes.begin(), bytes.end()));
  } catch (const std::exception& e) {
    throw std::runtime_error(file + ": the mesh from gmsh's process cannot be read back: " + e.what());
  }
}

void write_file(const std::string& path, const std::string& data) {
  std::ofstream out(path, std::ios::binary);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

}  // namespace

void enable_gmsh_process(const std::string& exe) { g_helper_exe = exe; }

namespace {
MeshGenerator g_generator = nullptr;
}  // namespace

void set_mesh_generator(MeshGenerator g) { g_generator = g; }

Mesh read_mesh(const MeshConfig& cfg, bool verbose) {
  if (!cfg.generator.empty()) {
    if (!g_generator) throw std::logic_error("read_mesh: no mesh generator set for '" + cfg.generator + "'");
    return g_generator(cfg);
  }
  const std::string before = current_phase();
  current_phase() = "reading the mesh " + cfg.file;
  Mesh m = g_helper_exe.empty() ? read_mesh_here(cfg, verbose) : read_mesh_in_child(cfg, verbose);
  current_phase() = before;
  return m;
}

int gmsh_helper_main(int argc, char** argv) {
  if (argc < 13 || (argc - 13) % 2 != 0) {
    std::fprintf(stderr, "stentor --gmsh-helper: internal use only\n");
    return 1;
  }
  // Ends with stentor: killed (a batch job's limit, SIGKILL), stentor must not leave gmsh
  // looping in a process group of its own.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != static_cast<pid_t>(std::atol(argv[10]))) return 1;  // it ended already
  const std::string dir = argv[2];
  // Address space at most the machine's memory: a mesh far too fine fails in gmsh
  // (bad_alloc, or an abort where it cannot be caught) instead of swapping.
  // Not where the process already maps more than half of it (AddressSanitizer's shadow
  // memory: terabytes of address space, and every allocation would fail).
  struct rlimit rl;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  unsigned long long mapped_pages = 0;
  std::ifstream("/proc/self/statm") >> mapped_pages;
  if (pages > 0 && page > 0 && mapped_pages < static_cast<unsigned long long>(pages) / 2 &&
      ::getrlimit(RLIMIT_AS, &rl) == 0) {
    const rlim_t phys = static_cast<rlim_t>(pages) * static_cast<rlim_t>(page);
    if (rl.rlim_cur == RLIM_INFINITY || rl.rlim_cur > phys) {
      rl.rlim_cur = phys;
      ::setrlimit(RLIMIT_AS, &rl);
    }
  }
  MeshConfig cfg;
  cfg.file = argv[3];
  cfg.size = std::strtod(argv[4], nullptr);
  cfg.order = std::atoi(argv[5]);
  cfg.recombine = std::atoi(argv[6]) != 0;
  cfg.dimension = std::atoi(argv[7]);
  cfg.max_cells = std::strtod(argv[8], nullptr);
  const bool verbose = std::atoi(argv[9]) != 0;
  input_limits().text = std::strtoull(argv[11], nullptr, 10);
  input_limits().mesh = std::strtoull(argv[12], nullptr, 10);
  for (int i = 13; i + 1 < argc; i += 2) cfg.parameters.emplace_back(argv[i], std::strtod(argv[i + 1], nullptr));
  try {
    // Confined before gmsh reads anything: reads only the screened files, writes only in `dir`.
    const std::string why = confine_process(dir, screen_mesh_file(cfg.file));
    write_file(dir + "/" + kConfinementFile,
               why.empty() ? "landlock ABI " + std::to_string(landlock_abi()) : "unconfined: " + why);
    const Mesh m = read_mesh_here(cfg, verbose);
    const std::vector<char> bytes = serialize_mesh(m);
    write_file(dir + "/" + kMeshFile, std::string(bytes.begin(), bytes.end()));
    return 0;
  } catch (const InputError& e) {
    write_file(dir + "/" + kErrorFile, e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    write_file(dir + "/" + kErrorFile, cfg.file + ": gmsh ran out of memory reading or meshing it; the mesh is too "
                                       "fine for this machine (use a larger 'Mesh->size')");
    return 2;
  } catch (const std::exception& e) {
    write_file(dir + "/" + kErrorFile, e.what());
    return 1;
  } catch (...) {
    write_file(dir + "/" + kErrorFile, cfg.file + ": unknown error in gmsh's process");
    return 1;
  }
}

}  // namespace stentor
