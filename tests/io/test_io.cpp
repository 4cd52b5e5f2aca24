// Result output: XDMF/HDF5 writer, CSV time series, staged output directory, gnuplot PNGs.
#include <gtest/gtest.h>
#include <unistd.h>
#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "io/Csv.hpp"
#include "io/OutputDir.hpp"
#include "io/Plot.hpp"
#include "io/Units.hpp"
#include "io/XdmfWriter.hpp"
#include "mesh/Mesh.hpp"

namespace fs = std::filesystem;
using namespace stentor;

namespace {

// A fresh scratch directory per test.
fs::path scratch(const std::string& name) {
  fs::path p = fs::path(STENTOR_BINARY_DIR) / "test_io_tmp" / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream o;
  o << in.rdbuf();
  return o.str();
}

// ---------------------------------------------------------------------------------------
// Test mesh: two tri3 + one quad4 in the plane z = 0, and one tet10 above it (gmsh order).
// ---------------------------------------------------------------------------------------
constexpr int kTetEdgesGmsh[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
constexpr int kTetEdgesVtk[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

Mesh test_mesh() {
  Mesh m;
  m.dim = 3;
  m.source = "test";
  const double pts[10][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0},
                             {2, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0, 0, 2}};
  for (const auto& p : pts) m.x.insert(m.x.end(), p, p + 3);
  // tet10 edge nodes 10..15 in gmsh order: node 10 + e is the midpoint of gmsh edge e.
  const int tv[4] = {6, 7, 8, 9};
  for (const auto& e : kTetEdgesGmsh)
    for (int c = 0; c < 3; ++c) m.x.push_back(0.5 * (m.x[3 * tv[e[0]] + c] + m.x[3 * tv[e[1]] + c]));

  CellBlock tris;
  tris.name = "tris";
  tris.physical_tag = 1;
  tris.type = CellType::Tri3;
  tris.nodes_per_cell = 3;
  tris.conn = {0, 1, 2, 0, 2, 3};
  tris.cell_id = {0, 1};
  CellBlock quad;
  quad.name = "quad";
  quad.physical_tag = 2;
  quad.type = CellType::Quad4;
  quad.nodes_per_cell = 4;
  quad.conn = {1, 4, 5, 2};
  quad.cell_id = {2};
  CellBlock tet;
  tet.name = "tet";
  tet.physical_tag = 3;
  tet.type = CellType::Tet10;
  tet.nodes_per_cell = 10;
  tet.conn = {6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  tet.cell_id = {3};
  m.volumes = {tris, quad, tet};
  CellBlock edge;  // boundaries are not written
  edge.name = "bottom";
  edge.type = CellType::Line2;
  edge.nodes_per_cell = 2;
  edge.conn = {0, 1};
  m.boundaries = {edge};
  return m;
}

// ---------------------------------------------------------------------------------------
// HDF5 reading
// ---------------------------------------------------------------------------------------
struct H5File {
  hid_t id;
  explicit H5File(const std::string& p) : id(H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {
    if (id < 0) throw std::runtime_error("cannot open " + p);
  }
  ~H5File() { H5Fclose(id); }
};

std::vector<hsize_t> dims_of(hid_t file, const std::string& path) {
  hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (d < 0) throw std::runtime_error("no dataset " + path);
  hid_t s = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(s);
  std::vector<hsize_t> dims(rank > 0 ? rank : 0);
  if (rank > 0) H5Sget_simple_extent_dims(s, dims.data(), nullptr);
  H5Sclose(s);
  H5Dclose(d);
  return dims;
}

template <class T>
std::vector<T> read_all(hid_t file, const std::string& path, hid_t memtype) {
  std::size_t n = 1;
  for (hsize_t d : dims_of(file, path)) n *= d;
  std::vector<T> v(n);
  hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (n && H5Dread(d, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    throw std::runtime_error("cannot read " + path);
  H5Dclose(d);
  return v;
}

std::vector<double> read_doubles(hid_t f, const std::string& p) {
  return read_all<double>(f, p, H5T_NATIVE_DOUBLE);
}
std::vector<long long> read_ints(hid_t f, const std::string& p) {
  return read_all<long long>(f, p, H5T_NATIVE_LLONG);
}

// Type class and size of a dataset's file type.
std::pair<H5T_class_t, std::size_t> type_of(hid_t file, const std::string& path) {
  hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  hid_t t = H5Dget_type(d);
  auto r = std::make_pair(H5Tget_class(t), H5Tget_size(t));
  H5Tclose(t);
  H5Dclose(d);
  return r;
}

// Every link along `path` exists and the object it names exists.
bool h5_path_exists(hid_t file, const std::string& path) {
  if (path.empty() || path[0] != '/') return false;
  std::size_t pos = 1;
  while (true) {
    const std::size_t next = path.find('/', pos);
    const std::string prefix = path.substr(0, next);
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (next == std::string::npos) break;
    pos = next + 1;
  }
  return H5Oexists_by_name(file, path.c_str(), H5P_DEFAULT) > 0;
}

// ---------------------------------------------------------------------------------------
// A minimal XML parser (elements, attributes, text; prolog, comments, DOCTYPE skipped).
// Throws std::runtime_error on anything malformed.
// ---------------------------------------------------------------------------------------
struct XmlNode {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::string text;
  std::vector<XmlNode> kids;
  std::string attr(const std::string& k) const {
    auto it = attrs.find(k);
    return it == attrs.end() ? std::string() : it->second;
  }
  std::vector<const XmlNode*> children(const std::string& n) const {
    std::vector<const XmlNode*> r;
    for (const auto& k : kids)
      if (k.name == n) r.push_back(&k);
    return r;
  }
};

class XmlParser {
 public:
  explicit XmlParser(const std::string& s) : s_(s) {}
  XmlNode document() {
    skip_misc();
    XmlNode root = element();
    skip_misc();
    if (i_ != s_.size()) bad("content after the root element");
    return root;
  }

 private:
  const std::string& s_;
  std::size_t i_ = 0;
  [[noreturn]] void bad(const std::string& w) {
    throw std::runtime_error("XML: " + w + " at offset " + std::to_string(i_));
  }
  bool at(const char* p) const { return s_.compare(i_, std::strlen(p), p) == 0; }
  void skip_ws() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  void skip_to(const char* end) {
    const std::size_t j = s_.find(end, i_);
    if (j == std::string::npos) bad(std::string("missing ") + end);
    i_ = j + std::strlen(end);
  }
  void skip_misc() {
    while (true) {
      skip_ws();
      if (at("<?")) skip_to("?>");
      else if (at("<!--")) skip_to("-->");
      else if (at("<!")) skip_to(">");
      else return;
    }
  }
  std::string name() {
    const std::size_t b = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) ||
                              s_[i_] == '_' || s_[i_] == ':' || s_[i_] == '-' || s_[i_] == '.'))
      ++i_;
    if (i_ == b) bad("expected a name");
    return s_.substr(b, i_ - b);
  }
  std::string decode(const std::string& raw) {
    std::string r;
    for (std::size_t k = 0; k < raw.size(); ++k) {
      if (raw[k] == '<') bad("'<' in text or attribute");
      if (raw[k] != '&') {
        r += raw[k];
        continue;
      }
      const std::size_t e = raw.find(';', k);
      if (e == std::string::npos) bad("unterminated entity");
      const std::string ent = raw.substr(k + 1, e - k - 1);
      if (ent == "amp") r += '&';
      else if (ent == "lt") r += '<';
      else if (ent == "gt") r += '>';
      else if (ent == "quot") r += '"';
      else if (ent == "apos") r += '\'';
      else bad("unknown entity &" + ent + ";");
      k = e;
    }
    return r;
  }
  XmlNode element() {
    if (!at("<")) bad("expected '<'");
    ++i_;
    XmlNode n;
    n.name = name();
    while (true) {
      skip_ws();
      if (at("/>")) {
        i_ += 2;
        return n;
      }
      if (at(">")) {
        ++i_;
        break;
      }
      const std::string k = name();
      skip_ws();
      if (!at("=")) bad("expected '='");
      ++i_;
      skip_ws();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) bad("expected a quote");
      const char q = s_[i_++];
      const std::size_t e = s_.find(q, i_);
      if (e == std::string::npos) bad("unterminated attribute");
      if (n.attrs.count(k)) bad("duplicate attribute " + k);
      n.attrs[k] = decode(s_.substr(i_, e - i_));
      i_ = e + 1;
    }
    while (true) {
      const std::size_t lt = s_.find('<', i_);
      if (lt == std::string::npos) bad("unclosed element " + n.name);
      n.text += decode(s_.substr(i_, lt - i_));
      i_ = lt;
      if (at("</")) {
        i_ += 2;
        if (name() != n.name) bad("mismatched end tag for " + n.name);
        skip_ws();
        if (!at(">")) bad("expected '>'");
        ++i_;
        return n;
      }
      if (at("<!--")) {
        skip_to("-->");
        continue;
      }
      n.kids.push_back(element());
    }
  }
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::vector<hsize_t> parse_dims(const std::string& s) {
  std::istringstream in(s);
  std::vector<hsize_t> d;
  hsize_t v;
  while (in >> v) d.push_back(v);
  return d;
}

// Checks every HDF DataItem under `n` (file relative to `dir`): the file and the dataset
// exist and the declared Dimensions equal the dataset's. Counts them in `count`.
void check_data_items(const XmlNode& n, const fs::path& dir, int& count) {
  if (n.name == "DataItem" && n.attr("Format") == "HDF") {
    const std::string ref = trim(n.text);
    const auto colon = ref.find(':');
    ASSERT_NE(colon, std::string::npos) << ref;
    const fs::path file = dir / ref.substr(0, colon);
    const std::string path = ref.substr(colon + 1);
    ASSERT_TRUE(fs::exists(file)) << file;
    H5File f(file.string());
    ASSERT_TRUE(h5_path_exists(f.id, path)) << ref;
    EXPECT_EQ(parse_dims(n.attr("Dimensions")), dims_of(f.id, path)) << ref;
    EXPECT_EQ(n.attr("Precision"), "8") << ref;
    ++count;
  }
  for (const auto& k : n.kids) check_data_items(k, dir, count);
}

// Field values used by the tests: value of component c at entity i in step s.
double node_val(int s, int i, int c) { return 100.0 * s + i + 0.1 * c + 1.0 / 3.0; }
double cell_val(int s, int i, int c) { return -1000.0 * s + 10.0 * i + c + 0.125; }

void write_step(XdmfWriter& w, int s, double t, std::size_t nn, std::size_t nc) {
  w.begin_step(t);
  std::vector<double> u(nn * 3), temp(nn), sym(nc * 6), id(nc);
  for (std::size_t i = 0; i < nn; ++i) {
    for (int c = 0; c < 3; ++c) u[3 * i + c] = node_val(s, static_cast<int>(i), c);
    temp[i] = node_val(s, static_cast<int>(i), 7);
  }
  for (std::size_t i = 0; i < nc; ++i) {
    for (int c = 0; c < 6; ++c) sym[6 * i + c] = cell_val(s, static_cast<int>(i), c);
    id[i] = static_cast<double>(i);
  }
  w.node_field("displacement", 3, u);
  w.node_field("temperature", 1, temp);
  w.cell_field("stress", 6, sym);
  w.cell_field("cell id", 1, id);
  w.end_step();
}

}  // namespace

// ---------------------------------------------------------------------------------------
// XDMF / HDF5
// ---------------------------------------------------------------------------------------
TEST(XdmfWriter, TopologyNamesAndPermutation) {
  EXPECT_STREQ(xdmf_topology_name(CellType::Tri3), "Triangle");
  EXPECT_STREQ(xdmf_topology_name(CellType::Tri6), "Triangle_6");
  EXPECT_STREQ(xdmf_topology_name(CellType::Quad4), "Quadrilateral");
  EXPECT_STREQ(xdmf_topology_name(CellType::Quad8), "Quadrilateral_8");
  EXPECT_STREQ(xdmf_topology_name(CellType::Tet4), "Tetrahedron");
  EXPECT_STREQ(xdmf_topology_name(CellType::Tet10), "Tetrahedron_10");
  EXPECT_STREQ(xdmf_topology_name(CellType::Hex8), "Hexahedron");
  EXPECT_STREQ(xdmf_topology_name(CellType::Line2), "Polyline");
  EXPECT_EQ(xdmf_topology_name(CellType::Line3), nullptr);
  int perm[kMaxCellNodes];
  ASSERT_EQ(xdmf_node_permutation(CellType::Tri6, perm), 6);
  for (int j = 0; j < 6; ++j) EXPECT_EQ(perm[j], j);
  ASSERT_EQ(xdmf_node_permutation(CellType::Tet10, perm), 10);
  // XDMF edge node 4+e must be gmsh's node on the same (unordered) edge.
  for (int e = 0; e < 6; ++e) {
    const int g = perm[4 + e] - 4;
    ASSERT_GE(g, 0);
    const auto& a = kTetEdgesVtk[e];
    const auto& b = kTetEdgesGmsh[g];
    EXPECT_TRUE((a[0] == b[0] && a[1] == b[1]) || (a[0] == b[1] && a[1] == b[0])) << "edge " << e;
  }
}

TEST(XdmfWriter, WritesMeshFieldsAndConsistentXdmf) {
  const fs::path dir = scratch("xdmf");
  const Mesh mesh = test_mesh();
  const std::size_t nn = mesh.num_nodes(), nc = mesh.num_volume_cells();
  ASSERT_EQ(nn, 16u);
  ASSERT_EQ(nc, 4u);
  {
    XdmfWriter w(dir.string(), "result", mesh);
    EXPECT_EQ(w.h5_path(), (dir / "result.h5").string());
    write_step(w, 0, 0.0, nn, nc);
    // After each end_step the pair is consistent: the .xdmf has step 0 only.
    ASSERT_TRUE(fs::exists(dir / "result.xdmf"));
    const XmlNode x1 = XmlParser(slurp(dir / "result.xdmf")).document();
    EXPECT_EQ(x1.children("Domain")[0]->children("Grid")[0]->children("Grid").size(), 1u);
    int count = 0;
    check_data_items(x1, dir, count);
    EXPECT_GT(count, 0);
    write_step(w, 1, 0.5, nn, nc);
    EXPECT_EQ(w.num_steps(), 2);
  }
  EXPECT_FALSE(fs::exists(dir / "result.xdmf.tmp"));

  H5File f((dir / "result.h5").string());
  // Coordinates.
  EXPECT_EQ(dims_of(f.id, "/mesh/coordinates"), (std::vector<hsize_t>{16, 3}));
  EXPECT_EQ(read_doubles(f.id, "/mesh/coordinates"), mesh.x);
  auto [cls, size] = type_of(f.id, "/mesh/coordinates");
  EXPECT_EQ(cls, H5T_FLOAT);
  EXPECT_EQ(size, 8u);
  // Connectivity: 64-bit ints, tri3/quad4 unchanged.
  EXPECT_EQ(dims_of(f.id, "/mesh/block_0/connectivity"), (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(read_ints(f.id, "/mesh/block_0/connectivity"), (std::vector<long long>{0, 1, 2, 0, 2, 3}));
  std::tie(cls, size) = type_of(f.id, "/mesh/block_0/connectivity");
  EXPECT_EQ(cls, H5T_INTEGER);
  EXPECT_EQ(size, 8u);
  EXPECT_EQ(read_ints(f.id, "/mesh/block_1/connectivity"), (std::vector<long long>{1, 4, 5, 2}));
  // tet10: gmsh nodes 8 and 9 swapped ...
  const auto tet = read_ints(f.id, "/mesh/block_2/connectivity");
  EXPECT_EQ(tet, (std::vector<long long>{6, 7, 8, 9, 10, 11, 12, 13, 15, 14}));
  // ... so that every XDMF/VTK edge node sits at the midpoint of its VTK edge.
  ASSERT_EQ(tet.size(), 10u);
  for (int e = 0; e < 6; ++e)
    for (int c = 0; c < 3; ++c) {
      const double mid = 0.5 * (mesh.x[3 * tet[kTetEdgesVtk[e][0]] + c] +
                                mesh.x[3 * tet[kTetEdgesVtk[e][1]] + c]);
      EXPECT_DOUBLE_EQ(mesh.x[3 * tet[4 + e] + c], mid) << "edge " << e;
    }
  EXPECT_FALSE(h5_path_exists(f.id, "/mesh/block_3"));  // boundaries are not written

  // Fields of both steps.
  for (int s = 0; s < 2; ++s) {
    const std::string g = "/step_" + std::to_string(s);
    double t = -1;
    hid_t gid = H5Gopen2(f.id, g.c_str(), H5P_DEFAULT);
    ASSERT_GE(gid, 0);
    hid_t a = H5Aopen(gid, "time", H5P_DEFAULT);
    ASSERT_GE(a, 0);
    H5Aread(a, H5T_NATIVE_DOUBLE, &t);
    H5Aclose(a);
    H5Gclose(gid);
    EXPECT_EQ(t, s * 0.5);

    EXPECT_EQ(dims_of(f.id, g + "/displacement"), (std::vector<hsize_t>{16, 3}));
    const auto u = read_doubles(f.id, g + "/displacement");
    for (std::size_t i = 0; i < nn; ++i)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(u[3 * i + c], node_val(s, static_cast<int>(i), c));
    EXPECT_EQ(dims_of(f.id, g + "/temperature"), (std::vector<hsize_t>{16}));
    const auto temp = read_doubles(f.id, g + "/temperature");
    for (std::size_t i = 0; i < nn; ++i) EXPECT_EQ(temp[i], node_val(s, static_cast<int>(i), 7));
    // Symmetric tensors (xx,yy,zz,xy,yz,xz) are stored as full row-major 3x3.
    EXPECT_EQ(dims_of(f.id, g + "/stress"), (std::vector<hsize_t>{4, 9}));
    const auto sig = read_doubles(f.id, g + "/stress");
    const int v2f[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
    for (std::size_t i = 0; i < nc; ++i)
      for (int k = 0; k < 9; ++k)
        EXPECT_EQ(sig[9 * i + k], cell_val(s, static_cast<int>(i), v2f[k]));
    // Dataset names: characters outside [A-Za-z0-9_.+-] become '_'.
    EXPECT_EQ(read_doubles(f.id, g + "/cell_id"), (std::vector<double>{0, 1, 2, 3}));
  }

  // The whole mesh: the three blocks' cells in block order as one XDMF "Mixed" list
  // (type number, nodes), and each cell's block.
  EXPECT_EQ(read_ints(f.id, "/mesh/topology"),
            (std::vector<long long>{0x4, 0, 1, 2, 0x4, 0, 2, 3, 0x5, 1, 4, 5, 2, 0x26, 6, 7, 8, 9,
                                    10, 11, 12, 13, 15, 14}));
  EXPECT_EQ(read_ints(f.id, "/mesh/cell_block"), (std::vector<long long>{0, 0, 1, 2}));

  // XDMF: well-formed, two time steps, each one Uniform grid with the whole mesh (what
  // meshio's TimeSeriesReader and ParaView's readers both read), every DataItem resolves.
  const XmlNode x = XmlParser(slurp(dir / "result.xdmf")).document();
  EXPECT_EQ(x.name, "Xdmf");
  EXPECT_EQ(x.attr("Version"), "3.0");
  ASSERT_EQ(x.children("Domain").size(), 1u);
  const XmlNode& dom = *x.children("Domain")[0];
  ASSERT_EQ(dom.children("Grid").size(), 1u);
  ASSERT_EQ(dom.children("Information").size(), 1u);
  EXPECT_EQ(dom.children("Information")[0]->attr("Value"), "0: tris; 1: quad; 2: tet");
  const XmlNode& series = *dom.children("Grid")[0];
  EXPECT_EQ(series.attr("GridType"), "Collection");
  EXPECT_EQ(series.attr("CollectionType"), "Temporal");
  const auto steps = series.children("Grid");
  ASSERT_EQ(steps.size(), 2u);
  for (int s = 0; s < 2; ++s) {
    const XmlNode& g = *steps[s];
    EXPECT_EQ(g.attr("GridType"), "Uniform");
    EXPECT_TRUE(g.children("Grid").empty());
    ASSERT_EQ(g.children("Time").size(), 1u);
    EXPECT_EQ(std::stod(g.children("Time")[0]->attr("Value")), s * 0.5);
    ASSERT_EQ(g.children("Topology").size(), 1u);
    const XmlNode& topo = *g.children("Topology")[0];
    EXPECT_EQ(topo.attr("TopologyType"), "Mixed");
    EXPECT_EQ(topo.attr("NumberOfElements"), "4");
    EXPECT_EQ(parse_dims(topo.children("DataItem")[0]->attr("Dimensions")), (std::vector<hsize_t>{24}));
    ASSERT_EQ(g.children("Geometry").size(), 1u);
    EXPECT_EQ(g.children("Geometry")[0]->attr("GeometryType"), "XYZ");
    std::map<std::string, const XmlNode*> attrs;
    for (const XmlNode* a : g.children("Attribute")) attrs[a->attr("Name")] = a;
    ASSERT_EQ(attrs.size(), 5u);
    EXPECT_EQ(attrs["displacement"]->attr("AttributeType"), "Vector");
    EXPECT_EQ(attrs["displacement"]->attr("Center"), "Node");
    EXPECT_EQ(attrs["temperature"]->attr("AttributeType"), "Scalar");
    EXPECT_EQ(attrs["stress"]->attr("AttributeType"), "Tensor");
    EXPECT_EQ(attrs["stress"]->attr("Center"), "Cell");
    EXPECT_EQ(attrs["cell_block"]->attr("Center"), "Cell");
    ASSERT_NE(attrs["cell id"], nullptr);
    // Cell fields reference their whole dataset (the grid has every cell).
    const XmlNode& di = *attrs["stress"]->children("DataItem")[0];
    EXPECT_EQ(di.attr("Format"), "HDF");
    EXPECT_EQ(parse_dims(di.attr("Dimensions")), (std::vector<hsize_t>{4, 9}));
    EXPECT_EQ(trim(di.text), "result.h5:/step_" + std::to_string(s) + "/stress");
  }
  int count = 0;
  check_data_items(x, dir, count);
  // Per step: topology, geometry, cell_block, 4 fields.
  EXPECT_EQ(count, 2 * 7);
}

TEST(XdmfWriter, OneCellTypeIsOneTopology) {
  const fs::path dir = scratch("xdmf_single");
  Mesh mesh = test_mesh();
  mesh.volumes.erase(mesh.volumes.begin(), mesh.volumes.begin() + 2);  // tet10 only
  mesh.volumes.push_back(mesh.volumes[0]);                             // a second tet10 block
  mesh.volumes[1].name = "tet";                                        // same name: made unique
  {
    XdmfWriter w(dir.string(), "one", mesh);
    w.begin_step(1.0);
    w.cell_field("p", 1, {42.0, 43.0});
    EXPECT_THROW(w.cell_field("cell_block", 1, {0.0, 0.0}), std::runtime_error);  // reserved
    w.end_step();
  }
  const XmlNode x = XmlParser(slurp(dir / "one.xdmf")).document();
  EXPECT_EQ(x.children("Domain")[0]->children("Information")[0]->attr("Value"), "0: tet; 1: tet_1");
  const XmlNode& g = *x.children("Domain")[0]->children("Grid")[0]->children("Grid")[0];
  const XmlNode& topo = *g.children("Topology")[0];
  EXPECT_EQ(topo.attr("TopologyType"), "Tetrahedron_10");
  EXPECT_EQ(topo.attr("NumberOfElements"), "2");
  EXPECT_EQ(parse_dims(topo.children("DataItem")[0]->attr("Dimensions")), (std::vector<hsize_t>{2, 10}));
  H5File f((dir / "one.h5").string());
  const std::vector<long long> tet = {6, 7, 8, 9, 10, 11, 12, 13, 15, 14};
  std::vector<long long> both = tet;
  both.insert(both.end(), tet.begin(), tet.end());
  EXPECT_EQ(read_ints(f.id, "/mesh/topology"), both);
  EXPECT_EQ(read_ints(f.id, "/mesh/cell_block"), (std::vector<long long>{0, 1}));
  const XmlNode& di = *g.children("Attribute")[1]->children("DataItem")[0];
  EXPECT_EQ(di.attr("Format"), "HDF");
  EXPECT_EQ(trim(di.text), "one.h5:/step_0/p");
  int count = 0;
  check_data_items(x, dir, count);
  EXPECT_EQ(count, 4);
}

TEST(XdmfWriter, Errors) {
  const fs::path dir = scratch("xdmf_err");
  const Mesh mesh = test_mesh();
  // Unwritable location: the message names the file (HDF5's own error print silenced).
  H5E_auto2_t old_func;
  void* old_data;
  H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  try {
    XdmfWriter w((dir / "missing" / "sub").string(), "r", mesh);
    ADD_FAILURE() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("r.h5"), std::string::npos) << e.what();
  }
  H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
  // Volume cells without an XDMF topology (line3), line cells (Polyline) mixed with others.
  Mesh bad = mesh;
  bad.volumes.push_back(mesh.boundaries[0]);
  EXPECT_THROW(XdmfWriter(dir.string(), "bad", bad), std::runtime_error);
  bad.volumes.back().type = CellType::Line3;
  bad.volumes.back().nodes_per_cell = 3;
  bad.volumes.back().conn = {0, 1, 2};
  EXPECT_THROW(XdmfWriter(dir.string(), "bad", bad), std::runtime_error);
  // Node out of range.
  bad = mesh;
  bad.volumes[0].conn[0] = 99;
  EXPECT_THROW(XdmfWriter(dir.string(), "bad", bad), std::runtime_error);

  XdmfWriter w(dir.string(), "r", mesh);
  EXPECT_THROW(w.node_field("u", 3, std::vector<double>(48)), std::runtime_error);  // no step
  EXPECT_THROW(w.end_step(), std::runtime_error);
  w.begin_step(0.0);
  EXPECT_THROW(w.begin_step(1.0), std::runtime_error);
  EXPECT_THROW(w.node_field("u", 3, std::vector<double>(47)), std::runtime_error);
  EXPECT_THROW(w.cell_field("c", 3, std::vector<double>(16 * 3)), std::runtime_error);
  EXPECT_THROW(w.node_field("u", 2, std::vector<double>(32)), std::runtime_error);
  EXPECT_THROW(w.node_field("", 1, std::vector<double>(16)), std::runtime_error);
  w.node_field("a/b", 1, std::vector<double>(16));  // stored as a_b
  EXPECT_THROW(w.node_field("a b", 1, std::vector<double>(16)), std::runtime_error);
  w.node_field("u", 3, std::vector<double>(48, 1.0));
  EXPECT_THROW(w.cell_field("u", 1, std::vector<double>(4)), std::runtime_error);  // same name
  w.end_step();
  EXPECT_EQ(w.num_steps(), 1);
}

// A moving mesh of line segments (the rigid obstacles' outlines, io/Obstacles.hpp): XDMF
// "Polyline" with NodesPerElement 2, each step's Geometry on its own /step_<k>/coordinates.
TEST(XdmfWriter, MovingPolylineMesh) {
  const fs::path dir = scratch("xdmf_moving");
  Mesh m;
  m.dim = 2;
  m.x = {0, 0, 0, 1, 0, 0, 1, 1, 0};
  CellBlock b;
  b.name = "balloon";
  b.type = CellType::Line2;
  b.nodes_per_cell = 2;
  b.conn = {0, 1, 1, 2};
  b.cell_id = {0, 1};
  m.volumes = {b};
  {
    XdmfWriter w(dir.string(), "ob", m);
    EXPECT_THROW(w.geometry(m.x), std::runtime_error);  // no step
    for (int k = 0; k < 2; ++k) {
      w.begin_step(k);
      std::vector<double> x = m.x;
      for (std::size_t i = 1; i < x.size(); i += 3) x[i] += 0.5 * k;
      EXPECT_THROW(w.geometry(std::vector<double>(8)), std::runtime_error);
      w.geometry(x);
      EXPECT_THROW(w.geometry(x), std::runtime_error);                                 // twice
      EXPECT_THROW(w.node_field("coordinates", 3, x), std::runtime_error);             // its dataset
      w.node_field("displacement", 3, std::vector<double>(9, 0.5 * k));
      w.end_step();
    }
  }
  const XmlNode x = XmlParser(slurp(dir / "ob.xdmf")).document();
  const auto steps = x.children("Domain")[0]->children("Grid")[0]->children("Grid");
  ASSERT_EQ(steps.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const XmlNode& topo = *steps[static_cast<std::size_t>(k)]->children("Topology")[0];
    EXPECT_EQ(topo.attr("TopologyType"), "Polyline");
    EXPECT_EQ(topo.attr("NodesPerElement"), "2");
    const XmlNode& geo = *steps[static_cast<std::size_t>(k)]->children("Geometry")[0]->children("DataItem")[0];
    EXPECT_EQ(trim(geo.text), "ob.h5:/step_" + std::to_string(k) + "/coordinates");
  }
  H5File f((dir / "ob.h5").string());
  EXPECT_EQ(read_ints(f.id, "/mesh/topology"), (std::vector<long long>{0, 1, 1, 2}));
  int count = 0;
  check_data_items(x, dir, count);
  EXPECT_EQ(count, 2 * 4);
}

// ---------------------------------------------------------------------------------------
// CSV
// ---------------------------------------------------------------------------------------
// Shortest exact form (issue 13: times were written as 0.10000000000000001).
TEST(Csv, FormatDoubleIsShortestExact) {
  EXPECT_EQ(format_double(0.1), "0.1");
  EXPECT_EQ(format_double(0.15), "0.15");
  EXPECT_EQ(format_double(0.1 + 0.2), "0.30000000000000004");  // not the double nearest 0.3
  EXPECT_EQ(format_double(3 * 0.05), "0.15000000000000002");
  EXPECT_EQ(format_double(1.0), "1");
  EXPECT_EQ(format_double(-2.5e10), "-25000000000");
  EXPECT_EQ(format_double(1e-300), "1e-300");
  EXPECT_EQ(format_double(-0.0), "-0");
  EXPECT_EQ(format_double(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_double(std::numeric_limits<double>::quiet_NaN()), "nan");
  // Every double reads back exactly, in at most 17 significant digits (24 characters).
  std::mt19937_64 gen(13);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> ex(-300, 300);
  for (int i = 0; i < 20000; ++i) {
    const double v = std::ldexp(mant(gen), ex(gen));
    const std::string s = format_double(v);
    ASSERT_EQ(std::strtod(s.c_str(), nullptr), v) << s;
    ASSERT_LE(s.size(), 24u) << s;
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.15g", v);
    if (std::strtod(buf, nullptr) == v) ASSERT_EQ(s, buf);  // no longer than needed
  }
}

TEST(Csv, RoundTripsAtFullPrecision) {
  const fs::path dir = scratch("csv");
  const std::string path = (dir / "energy.csv").string();
  const std::vector<std::vector<double>> rows = {
      {0.0, 0.1, 1.0 / 3.0, -2.5e10},
      {1e-300, std::nextafter(1.0, 2.0), -0.0, 123456789.123456789},
  };
  {
    CsvWriter w(path, {"time", "E_kin", "E,total", "W \"ext\""});
    w.row(rows[0]);
    // Flushed per row: readable before the writer is gone.
    const std::string partial = slurp(path);
    EXPECT_EQ(std::count(partial.begin(), partial.end(), '\n'), 2);
    w.row(rows[1]);
    EXPECT_THROW(w.row({1.0, 2.0}), std::runtime_error);
    EXPECT_THROW(w.row({1.0, 2.0, 3.0, 4.0, 5.0}), std::runtime_error);
  }
  std::istringstream in(slurp(path));
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "time,E_kin,\"E,total\",\"W \"\"ext\"\"\"");
  for (const auto& r : rows) {
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream ls(line);
    std::string cell;
    std::size_t k = 0;
    while (std::getline(ls, cell, ',')) {
      ASSERT_LT(k, r.size());
      const double v = std::strtod(cell.c_str(), nullptr);
      EXPECT_EQ(v, r[k]) << cell;
      EXPECT_EQ(std::signbit(v), std::signbit(r[k])) << cell;
      ++k;
    }
    EXPECT_EQ(k, r.size());
  }
  EXPECT_FALSE(std::getline(in, line));
  EXPECT_THROW(CsvWriter((dir / "no" / "x.csv").string(), {"a"}), std::runtime_error);
}

// ---------------------------------------------------------------------------------------
// Staged output directory
// ---------------------------------------------------------------------------------------
TEST(OutputDir, CommitReplacesAndFailureKeepsEarlierResults) {
  const fs::path base = scratch("outdir");
  const std::string fin = (base / "results").string();
  auto put = [](const std::string& dir, const std::string& name, const std::string& text) {
    std::ofstream(fs::path(dir) / name) << text;
  };
  {
    OutputDir d(fin);
    EXPECT_EQ(d.path(), fin + ".partial");
    EXPECT_TRUE(fs::is_directory(d.path()));
    EXPECT_FALSE(fs::exists(fin));  // nothing visible before commit
    put(d.path(), "a.txt", "first");
    d.commit();
    EXPECT_TRUE(d.committed());
    EXPECT_THROW(d.commit(), std::runtime_error);
  }
  EXPECT_EQ(slurp(fs::path(fin) / "a.txt"), "first");
  EXPECT_FALSE(fs::exists(fin + ".partial"));
  EXPECT_FALSE(fs::exists(fin + ".old"));

  // A second successful run replaces the results entirely.
  {
    OutputDir d(fin + "/");  // trailing slash is the same directory
    EXPECT_EQ(d.path(), fin + ".partial");
    put(d.path(), "b.txt", "second");
    d.commit();
  }
  EXPECT_EQ(slurp(fs::path(fin) / "b.txt"), "second");
  EXPECT_FALSE(fs::exists(fs::path(fin) / "a.txt"));
  EXPECT_FALSE(fs::exists(fin + ".old"));

  // A failed run (no commit): earlier results untouched, the partial ones kept aside.
  {
    OutputDir d(fin);
    put(d.path(), "c.txt", "broken");
  }
  EXPECT_EQ(slurp(fs::path(fin) / "b.txt"), "second");
  EXPECT_FALSE(fs::exists(fs::path(fin) / "c.txt"));
  EXPECT_EQ(slurp(fs::path(fin + ".partial") / "c.txt"), "broken");

  // The next run starts from a clean staging directory (but for its lock) and says
  // that it took over the failed run's folder.
  {
    OutputDir d(fin);
    EXPECT_FALSE(fs::exists(fs::path(d.path()) / "c.txt"));
    EXPECT_EQ(std::distance(fs::directory_iterator(d.path()), fs::directory_iterator()), 1);
    EXPECT_NE(d.notice().find("took over " + fin + ".partial from an earlier run"), std::string::npos) << d.notice();
  }
  // Nested final directories are created.
  {
    OutputDir d((base / "x" / "y" / "z").string());
    put(d.path(), "f", "1");
    d.commit();
  }
  EXPECT_TRUE(fs::exists(base / "x" / "y" / "z" / "f"));
}

// The user's files: a foreign non-empty folder is refused (unless overwrite), the
// inputs never lie in the output folder, only the files the manifest lists are replaced.
TEST(OutputDir, NeverTouchesFilesItDidNotWrite) {
  const fs::path base = scratch("outdir_safe");
  const std::string fin = (base / "r").string();
  fs::create_directories(fin);
  std::ofstream(fs::path(fin) / "user.txt") << "mine";
  EXPECT_THROW(OutputDir d(fin), std::runtime_error);
  EXPECT_FALSE(fs::exists(fin + ".partial"));
  OutputDir::Options o;
  o.inputs = {fin + "/deck.xml"};
  o.overwrite = true;
  EXPECT_THROW(OutputDir d(fin, o), std::runtime_error);  // the deck's folder, even with overwrite
  o.inputs.clear();
  {
    OutputDir d(fin, o);
    std::ofstream(fs::path(d.path()) / "a.csv") << "new";
    d.copy_in((fs::path(fin) / "user.txt").string(), "copy.txt");
    d.commit();
  }
  EXPECT_EQ(slurp(fs::path(fin) / "user.txt"), "mine");
  EXPECT_EQ(slurp(fs::path(fin) / "copy.txt"), "mine");
  // Now a Stentor folder: no overwrite needed; a result name the manifest does not list is
  // refused at once when it starts with the run's prefix.
  std::ofstream(fs::path(fin) / "stentor_x.csv") << "the user's";
  OutputDir::Options p;
  p.prefix = "stentor";
  EXPECT_THROW(OutputDir d(fin, p), std::runtime_error);
  {
    OutputDir d(fin);
    std::ofstream(fs::path(d.path()) / "b.csv") << "b";
    d.commit();
  }
  EXPECT_FALSE(fs::exists(fs::path(fin) / "a.csv"));  // listed by the earlier run: replaced
  EXPECT_FALSE(fs::exists(fs::path(fin) / "copy.txt"));
  EXPECT_EQ(slurp(fs::path(fin) / "b.csv"), "b");
  EXPECT_EQ(slurp(fs::path(fin) / "user.txt"), "mine");
  EXPECT_EQ(slurp(fs::path(fin) / "stentor_x.csv"), "the user's");
}

// A second OutputDir on the same folder while the first holds it is refused, naming it.
TEST(OutputDir, LockRefusesASecondRun) {
  const fs::path base = scratch("outdir_lock");
  const std::string fin = (base / "r").string();
  OutputDir::Options o;
  o.deck = "first.xml";
  auto first = std::make_unique<OutputDir>(fin, o);
  try {
    OutputDir second(fin);
    ADD_FAILURE() << "second OutputDir not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("another run is writing into '" + fin + "': pid " + std::to_string(::getpid())),
              std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("deck first.xml"), std::string::npos) << e.what();
  }
  first.reset();  // released: the next one takes it over
  OutputDir third(fin);
  EXPECT_NE(third.notice().find("took over"), std::string::npos);
  // A staging folder that is not Stentor's is never emptied.
  third.discard();
  fs::create_directories(fin + ".partial");
  std::ofstream(fs::path(fin + ".partial") / "keep") << "k";
  EXPECT_THROW(OutputDir d(fin), std::runtime_error);
  EXPECT_EQ(slurp(fs::path(fin + ".partial") / "keep"), "k");
}

// ---------------------------------------------------------------------------------------
// Unit labels (Problem->units)
// ---------------------------------------------------------------------------------------
TEST(Units, LabelsPerSystemAndPerThicknessIn2D) {
  const UnitLabels si3 = unit_labels("SI", 3), si2 = unit_labels("SI", 2);
  EXPECT_EQ(si3.length, "m");
  EXPECT_EQ(si3.force, "N");
  EXPECT_EQ(si3.energy, "J");
  EXPECT_EQ(si3.stress, "Pa");
  EXPECT_EQ(si2.force, "N/m");  // plane strain: per unit thickness
  EXPECT_EQ(si2.energy, "J/m");
  EXPECT_EQ(si2.stress, "Pa");
  const UnitLabels mm = unit_labels("mm-N-s", 2);
  EXPECT_EQ(mm.force, "N/mm");
  EXPECT_EQ(mm.energy, "mJ/mm");
  EXPECT_EQ(mm.stress, "MPa");
  EXPECT_EQ(mm.mass, "t");
  const UnitLabels ms = unit_labels("mm-g-ms", 3);
  EXPECT_EQ(ms.time, "ms");
  EXPECT_EQ(ms.mass, "g");
  EXPECT_EQ(ms.energy, "mJ");
  const UnitLabels none = unit_labels("none", 2);
  EXPECT_EQ(none.force, "");
  EXPECT_EQ(with_unit("force", none.force), "force");
  EXPECT_EQ(with_unit("force", si2.force), "force [N/m]");
  // Axisymmetric: the full revolution, forces and energies as in 3D.
  const UnitLabels axi = unit_labels("SI", 2, true);
  EXPECT_EQ(axi.force, "N");
  EXPECT_EQ(axi.energy, "J");
  for (const std::string& s : unit_systems()) EXPECT_NO_THROW(unit_labels(s, 3)) << s;
  EXPECT_THROW(unit_labels("cgs", 3), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// gnuplot
// ---------------------------------------------------------------------------------------
TEST(Plot, WritesPng) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  const fs::path dir = scratch("plot");
  const std::string csv = (dir / "energy.csv").string();
  {
    CsvWriter w(csv, {"time", "E_total", "E_n+1 - E_n"});
    for (int i = 0; i <= 50; ++i) {
      const double t = 0.02 * i;
      w.row({t, std::exp(-t), -0.02 * std::exp(-t)});
    }
  }
  const std::string png = (dir / "energy.png").string();
  ASSERT_TRUE(plot_csv_png(csv, png, "time", {"E_total", "E_n+1 - E_n"}, "Energy \"test\"",
                           "energy [J]"));
  const std::string bytes = slurp(png);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // The script names its files relative to its directory: it still works after a move.
  const std::string script = slurp(dir / "energy.gp");
  EXPECT_EQ(script.find(dir.string()), std::string::npos) << script;
  const fs::path moved = dir.parent_path() / "plot_moved";
  fs::remove_all(moved);
  fs::rename(dir, moved);
  fs::remove(moved / "energy.png");
  const std::string cmd = "cd '" + moved.string() + "' && gnuplot energy.gp 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(moved / "energy.png").substr(0, 4), "\x89PNG");
  fs::rename(moved, dir);
  // Missing column: no plot, no exception.
  EXPECT_FALSE(plot_csv_png(csv, (dir / "bad.png").string(), "time", {"nope"}, "t", "y"));
  EXPECT_FALSE(fs::exists(dir / "bad.png"));
  EXPECT_FALSE(plot_csv_png((dir / "missing.csv").string(), (dir / "m.png").string(), "time",
                            {"E_total"}, "t", "y"));
}

// plot_png from an in-memory table: the script holds the plotted columns inline (x first,
// each column once), NaN for non-finite values (a gap), the legends and axis labels given,
// and a time axis from 0; a missing column or an empty table draws nothing.
TEST(Plot, TableScriptHasDataLabelsAndLegends) {
  const fs::path dir = scratch("plot_table");
  PlotTable t;
  t.add("time", {0.0, 0.5, 1.0});
  t.add("u", {0.0, 0.1, 0.2});
  t.add("R", {std::nan(""), 2.0, 4.0});
  PlotSpec s{"Reaction", "time [s]", "reaction force [N/m]", "time", {{"R", "pull: reaction x", ""}, {"R", "R vs u", "u"}}, true};
  const bool drawn = plot_png(t, (dir / "r.png").string(), s);
  EXPECT_EQ(drawn, gnuplot_available());
  const std::string script = slurp(dir / "r.gp");
  EXPECT_NE(script.find("$data << EOD\n0 NaN 0\n0.5 2 0.1\n1 4 0.2\nEOD\n"), std::string::npos) << script;
  EXPECT_NE(script.find("$data using 1:2 "), std::string::npos) << script;
  EXPECT_NE(script.find("$data using 3:2 "), std::string::npos) << script;
  EXPECT_NE(script.find("title 'pull: reaction x'"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'R vs u'"), std::string::npos) << script;
  EXPECT_NE(script.find("set xlabel 'time [s]'"), std::string::npos) << script;
  EXPECT_NE(script.find("set ylabel 'reaction force [N/m]'"), std::string::npos) << script;
  EXPECT_NE(script.find("set xrange [0:*]"), std::string::npos) << script;
  if (drawn) EXPECT_EQ(slurp(dir / "r.png").substr(0, 4), "\x89PNG");
  s.curves.push_back({"nope", "missing", ""});
  EXPECT_FALSE(plot_png(t, (dir / "bad.png").string(), s));
  EXPECT_FALSE(fs::exists(dir / "bad.png"));
  EXPECT_FALSE(plot_png(PlotTable{}, (dir / "empty.png").string(), s));
  // read_csv_table: a CsvWriter file back, quoted names included.
  const std::string csv = (dir / "h.csv").string();
  {
    CsvWriter w(csv, {"time", "a,b"});
    w.row({0.0, 1.5});
    w.row({1.0, -2.5});
  }
  PlotTable back;
  ASSERT_TRUE(read_csv_table(csv, back));
  ASSERT_EQ(back.names, (std::vector<std::string>{"time", "a,b"}));
  EXPECT_EQ(back.columns[1], (std::vector<double>{1.5, -2.5}));
  EXPECT_FALSE(read_csv_table((dir / "none.csv").string(), back));
}

// Deck text reaches plot labels (load and probe names in column headers, the basename in
// file names); gnuplot runs `backquoted` text inside double quotes, so nothing may be
// interpreted: labels are single-quoted gnuplot strings.
TEST(Plot, LabelsAreNeverInterpreted) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  const fs::path dir = scratch("plot_inject");
  const std::string evil = "pull`touch PWNED`_x";
  const std::string csv = (dir / "h.csv").string();
  {
    CsvWriter w(csv, {"time", evil, "it's \\\"q\\\""});
    for (int i = 0; i <= 5; ++i) w.row({0.2 * i, 1.0 * i, 2.0 * i});
  }
  const std::string png = (dir / "p`touch PWNED2`.png").string();
  ASSERT_TRUE(plot_csv_png(csv, png, "time", {evil, "it's \\\"q\\\""}, "`touch PWNED3` @x", "y'`touch PWNED4`"));
  EXPECT_EQ(slurp(png).substr(0, 4), "\x89PNG");
  for (const char* f : {"PWNED", "PWNED2", "PWNED3", "PWNED4"}) {
    EXPECT_FALSE(fs::exists(dir / f)) << f;
    EXPECT_FALSE(fs::exists(fs::path(f))) << f;
  }
  const std::string script = slurp(dir / "p`touch PWNED2`.gp");
  EXPECT_NE(script.find("'pull`touch PWNED`_x'"), std::string::npos) << script;
  EXPECT_NE(script.find("'it''s \\\"q\\\"'"), std::string::npos) << script;
}

// A gnuplot that fails or hangs never fails or stalls a run (issue 16): a fake gnuplot
// first on PATH. One that exits 1 after writing half a PNG, or 0 after a PNG cut short
// (a full disk): no plot, no PNG left, the script kept. One that hangs (and started a child of its own): stopped with its child
// after the limit (1 s here; 60 s in a run), no PNG; the next plot is not tried at all.
namespace {
bool process_alive(long pid) {
  std::ifstream st("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(st, line)) return false;
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}
long read_pid(const fs::path& f) {
  std::ifstream in(f);
  long pid = 0;
  in >> pid;
  return pid;
}
}  // namespace

TEST(Plot, FailingOrHangingGnuplotEndsWithoutPlot) {
  const fs::path dir = scratch("plot_fake_gnuplot");
  const fs::path bin = dir / "bin";
  fs::create_directories(bin);
  const std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", (bin.string() + ":" + old_path).c_str(), 1);
  struct Restore {
    std::string path;
    ~Restore() {
      ::setenv("PATH", path.c_str(), 1);
      set_plot_time_limit(std::chrono::seconds(60));
    }
  } restore{old_path};
  PlotTable t;
  t.add("time", {0.0, 1.0});
  t.add("u", {0.0, 2.0});
  const PlotSpec spec{"u", "time [s]", "u [m]", "time", {{"u", "u", ""}}, true};
  auto fake = [&](const std::string& body) {
    {
      std::ofstream f(bin / "gnuplot");
      f << "#!/bin/sh\n" << body << "\n";
    }
    fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  };

  fake("printf '\\211PNG half' > \"$(basename \"$1\" .gp).png\"\necho 'broken' >&2\nexit 1");
  ASSERT_TRUE(gnuplot_available());
  EXPECT_FALSE(plot_png(t, (dir / "failed.png").string(), spec));
  EXPECT_FALSE(fs::exists(dir / "failed.png"));
  EXPECT_TRUE(fs::exists(dir / "failed.gp"));
  EXPECT_EQ(slurp(dir / "failed.gp.log"), "broken\n");

  // Exit 0 with a PNG cut short (its write failed, a full disk): no PNG either.
  fake("printf '\\211PNG\\r\\n\\032\\n0123456789' > \"$(basename \"$1\" .gp).png\"\nexit 0");
  EXPECT_FALSE(plot_png(t, (dir / "cut.png").string(), spec));
  EXPECT_FALSE(fs::exists(dir / "cut.png"));
  set_plot_time_limit(std::chrono::seconds(1));
  fake("echo $$ > '" + (dir / "gnuplot.pid").string() + "'\nsleep 300 &\necho $! > '" +
       (dir / "child.pid").string() + "'\nprintf '\\211PNG' > \"$(basename \"$1\" .gp).png\"\nwait");
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(plot_png(t, (dir / "hung.png").string(), spec));
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(waited, 0.9);
  EXPECT_LT(waited, 10.0);
  EXPECT_FALSE(fs::exists(dir / "hung.png"));
  EXPECT_TRUE(fs::exists(dir / "hung.gp"));
  const long gp = read_pid(dir / "gnuplot.pid"), child = read_pid(dir / "child.pid");
  ASSERT_GT(gp, 0);
  ASSERT_GT(child, 0);
  for (int i = 0; i < 100 && (process_alive(gp) || process_alive(child)); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(process_alive(gp)) << "gnuplot " << gp;
  EXPECT_FALSE(process_alive(child)) << "its child " << child;
  // gnuplot hung once: the next plot is not tried (no wait), its script still written.
  const auto t1 = std::chrono::steady_clock::now();
  EXPECT_FALSE(plot_png(t, (dir / "next.png").string(), spec));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), 0.5);
  EXPECT_TRUE(fs::exists(dir / "next.gp"));
}

// The manifest lists odd names unambiguously, and a run removes only the listed files that
// still are as the earlier run wrote them.
TEST(OutputDir, ManifestIsVerifiedNotObeyed) {
  const fs::path base = scratch("outdir_manifest");
  const std::string fin = (base / "r").string();
  const std::string odd = "a b\nc%.csv";
  {
    OutputDir d(fin);
    std::ofstream(fs::path(d.path()) / odd) << "odd";
    std::ofstream(fs::path(d.path()) / "kept.csv") << "run 1";
    d.commit();
  }
  const std::string manifest = slurp(fs::path(fin) / OutputDir::kManifest);
  EXPECT_NE(manifest.find(" a%20b%0Ac%25.csv\n"), std::string::npos) << manifest;
  std::ofstream(fs::path(fin) / "kept.csv", std::ios::app) << ", changed by the user";
  {
    OutputDir d(fin);
    EXPECT_NE(d.notice().find("1 files that " + fin + "/" + OutputDir::kManifest + " lists are not as the run"), std::string::npos)
        << d.notice();
    std::ofstream(fs::path(d.path()) / "new.csv") << "run 2";
    d.commit();
  }
  EXPECT_FALSE(fs::exists(fs::path(fin) / odd));  // as written: removed
  EXPECT_EQ(slurp(fs::path(fin) / "kept.csv"), "run 1, changed by the user");  // changed: kept
  EXPECT_EQ(slurp(fs::path(fin) / "new.csv"), "run 2");
  // A manifest with a line added by hand is not Stentor's: none of its lines counts.
  std::ofstream(fs::path(fin) / OutputDir::kManifest, std::ios::app) << "0 cbf29ce484222325 new.csv\n";
  {
    OutputDir d(fin);
    d.commit();
  }
  EXPECT_EQ(slurp(fs::path(fin) / "new.csv"), "run 2");
}

// running_in() names a run that holds the lock, and nothing once it has ended.
TEST(OutputDir, RunningInNamesTheHolder) {
  const fs::path base = scratch("outdir_running");
  const std::string fin = (base / "r").string();
  EXPECT_EQ(OutputDir::running_in(fin), "");
  OutputDir::Options o;
  o.deck = "live.xml";
  {
    OutputDir d(fin, o);
    // flock() locks are per open file: this process's second look sees the first's lock.
    EXPECT_NE(OutputDir::running_in(fin).find("deck live.xml (lock file " + fin + ".partial/.stentor.lock)"), std::string::npos)
        << OutputDir::running_in(fin);
  }
  EXPECT_EQ(OutputDir::running_in(fin), "");
}
