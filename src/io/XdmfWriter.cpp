#include "io/XdmfWriter.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/Csv.hpp"
#include "io/SafeFile.hpp"
#include "io/WriteError.hpp"

namespace stentor {

const char* xdmf_topology_name(CellType t) {
  switch (t) {
    case CellType::Line2: return "Polyline";  // with NodesPerElement="2": line segments
    case CellType::Tri3: return "Triangle";
    case CellType::Tri6: return "Triangle_6";
    case CellType::Quad4: return "Quadrilateral";
    case CellType::Quad8: return "Quadrilateral_8";
    case CellType::Tet4: return "Tetrahedron";
    case CellType::Tet10: return "Tetrahedron_10";
    case CellType::Hex8: return "Hexahedron";
    default: return nullptr;
  }
}

int xdmf_node_permutation(CellType t, int perm[kMaxCellNodes]) {
  if (!xdmf_topology_name(t)) return 0;
  const int n = cell_num_nodes(t);
  for (int j = 0; j < n; ++j) perm[j] = j;
  // gmsh tet10 edge nodes: 4(0,1) 5(1,2) 6(2,0) 7(3,0) 8(3,2) 9(3,1);
  // XDMF/VTK:              4(0,1) 5(1,2) 6(2,0) 7(0,3) 8(1,3) 9(2,3).
  // Vertices, tri6, quad8 (edges (0,1),(1,2),(2,3),(3,0)) and hex8 agree.
  if (t == CellType::Tet10) {
    perm[8] = 9;
    perm[9] = 8;
  }
  return n;
}

int xdmf_mixed_type_id(CellType t) {
  // XDMF's cell type numbers in a "Mixed" topology (XdmfTopologyType.cpp, Xdmf 2 and 3).
  switch (t) {
    case CellType::Tri3: return 0x4;
    case CellType::Quad4: return 0x5;
    case CellType::Tet4: return 0x6;
    case CellType::Hex8: return 0x9;
    case CellType::Tri6: return 0x24;
    case CellType::Quad8: return 0x25;
    case CellType::Tet10: return 0x26;
    default: return -1;
  }
}

namespace {

namespace fs = std::filesystem;

// Owns one HDF5 identifier.
class H5Id {
 public:
  using Closer = herr_t (*)(hid_t);
  H5Id() = default;
  H5Id(hid_t id, Closer c) : id_(id), close_(c) {}
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  H5Id(H5Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  H5Id& operator=(H5Id&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      close_ = o.close_;
      o.id_ = -1;
    }
    return *this;
  }
  ~H5Id() { reset(); }
  // Closes now, reporting failure (the destructor cannot).
  herr_t close() {
    herr_t s = 0;
    if (id_ >= 0 && close_) s = close_(id_);
    id_ = -1;
    return s;
  }
  void reset() { (void)close(); }
  // Forgets the identifier without closing it.
  void release() { id_ = -1; }
  hid_t get() const { return id_; }

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

std::string xml_escape(const std::string& s) {
  std::string r;
  r.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default:
        // Control characters are not allowed in XML 1.0 (except tab/newline/CR).
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
          r += '?';
        else
          r += c;
    }
  }
  return r;
}

// HDF5 dataset name for a field: characters other than [A-Za-z0-9_.+-] become '_' (XDMF
// readers split "file.h5:/path" references and some trim or tokenize them).
std::string dataset_name(const std::string& field) {
  std::string r = field;
  for (char& c : r)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' ||
          c == '-'))
      c = '_';
  return r;
}

std::string fmt_double(double v) { return format_double(v); }  // exact, shortest

// The innermost message of HDF5's error stack: for a failed write the system's reason
// ("No space left on device", "File too large"), else HDF5's own description.
std::string h5_reason() {
  std::string desc;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD,
           [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
             if (e->desc) *static_cast<std::string*>(out) = e->desc;
             return 0;
           },
           &desc);
  const std::string key = "error message = '";
  const std::size_t at = desc.find(key);
  if (at != std::string::npos) {
    const std::size_t end = desc.find('\'', at + key.size());
    return desc.substr(at + key.size(), end == std::string::npos ? std::string::npos : end - at - key.size());
  }
  return desc.empty() ? "HDF5 error" : desc;
}

// While a writer exists HDF5 prints no error stack of its own: the writer reports the
// reason in its exception (h5_reason) instead.
struct QuietH5Errors {
  H5E_auto2_t func = nullptr;
  void* data = nullptr;
  QuietH5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietH5Errors() { H5Eset_auto2(H5E_DEFAULT, func, data); }
};

}  // namespace

RowRange block_rows(std::size_t n, int rank, int nranks) {
  const auto p = static_cast<std::size_t>(nranks), r = static_cast<std::size_t>(rank);
  const std::size_t q = n / p, extra = n % p;
  RowRange rows;
  rows.begin = r * q + std::min(r, extra);
  rows.end = rows.begin + q + (r < extra ? 1 : 0);
  return rows;
}

XdmfRows xdmf_rows(const XdmfMesh& mesh, int rank, int nranks) {
  std::size_t num_cells = 0;
  for (const auto& b : mesh.blocks) num_cells += b.num_cells;
  XdmfRows r;
  r.nodes = block_rows(mesh.num_nodes, rank, nranks);
  r.cells = block_rows(num_cells, rank, nranks);
  std::size_t offset = 0;  // the block's first cell
  for (const auto& b : mesh.blocks) {
    const auto clamp = [&](std::size_t c) { return std::min(std::max(c, offset), offset + b.num_cells) - offset; };
    r.blocks.push_back(RowRange{clamp(r.cells.begin), clamp(r.cells.end)});
    offset += b.num_cells;
  }
  return r;
}

XdmfMesh xdmf_mesh(const Mesh& whole, int rank, int nranks) {
  const auto fail = [&](const std::string& what) { throw std::runtime_error("XdmfWriter: " + what + " (mesh " + whole.source + ")"); };
  if (whole.partial) fail("a rank's part of a mesh is not a whole mesh");
  if (whole.x.size() % 3 != 0) fail("mesh coordinates are not 3 per node");
  XdmfMesh m;
  m.num_nodes = whole.num_nodes();
  std::vector<char> used(m.num_nodes, 0);  // the nodes of volume cells
  for (const CellBlock& cb : whole.volumes) {
    const int npc = cell_num_nodes(cb.type);
    if (npc <= 0 || cb.nodes_per_cell != npc || cb.conn.size() % static_cast<std::size_t>(npc) != 0)
      fail("volume block '" + cb.name + "': connectivity size does not match its cell type");
    for (GId n : cb.conn) {
      if (n < 0 || static_cast<std::size_t>(n) >= m.num_nodes)
        fail("volume block '" + cb.name + "': node " + std::to_string(n) + " out of range");
      used[static_cast<std::size_t>(n)] = 1;
    }
    m.blocks.push_back(XdmfMesh::Block{cb.name, cb.type, cb.num_cells(), {}});
  }
  const XdmfRows rows = xdmf_rows(m, rank, nranks);
  m.x.assign(3 * rows.nodes.size(), 0.0);
  for (std::size_t n = rows.nodes.begin; n < rows.nodes.end; ++n)
    if (used[n]) std::copy_n(&whole.x[3 * n], 3, &m.x[3 * (n - rows.nodes.begin)]);
  for (std::size_t i = 0; i < m.blocks.size(); ++i) {
    const auto npc = static_cast<std::size_t>(whole.volumes[i].nodes_per_cell);
    const auto first = whole.volumes[i].conn.begin();
    m.blocks[i].conn.assign(first + static_cast<std::ptrdiff_t>(rows.blocks[i].begin * npc),
                            first + static_cast<std::ptrdiff_t>(rows.blocks[i].end * npc));
  }
  return m;
}

struct XdmfWriter::Impl {
  QuietH5Errors quiet;  // first: restored after the handles below are closed
  struct Block {
    std::string name;          // physical group (the "name" attribute)
    std::string grid_name;     // unique within a step
    CellType type = CellType::Invalid;
    const char* topology = nullptr;
    int npc = 0;
    std::size_t ncells = 0;
    std::string conn_path;     // HDF5 path
  };
  struct Field {
    std::string name;
    bool on_nodes = true;
    int ncomp = 1;             // as stored (6 expanded to 9)
    std::string path;
  };
  struct Step {
    double time = 0.0;
    std::string group;
    std::vector<Field> fields;
    std::string geometry = "/mesh/coordinates";  // the node positions (geometry(): the step's own)
  };

  std::string h5_path, h5_name, xdmf_path;
  std::size_t num_nodes = 0, num_cells = 0;
  MPI_Comm comm = MPI_COMM_NULL;  // parallel only
  int rank = 0;
  bool parallel = false;
  RowRange nodes, cells;  // this rank's rows
  std::vector<RowRange> block_part;  // this rank's cells of each block, within it (xdmf_rows)
  std::vector<Block> blocks;
  // The whole mesh as one topology: /mesh/topology is num_cells x npc when every cell has
  // one type, else the 1-D XDMF "Mixed" list (type id, nodes; topology_size entries).
  std::string topology;
  bool mixed = false;
  int npc = 0;
  std::size_t topology_size = 0;
  std::string block_legend;  // "0: name; 1: name; ..." (the cell_block values)
  std::vector<Step> steps;  // completed
  bool in_step = false;
  Step current;
  H5Id file;
  H5Id step_group;

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XdmfWriter: " + what + " (file " + h5_path + ")");
  }
  // A failed HDF5 call is a failed write of the results (disk full, quota, ...).
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) throw WriteError("XdmfWriter: " + what + " in " + h5_path + " failed: " + h5_reason());
    return id;
  }
  void check_status(herr_t s, const std::string& what) const { check(s, what); }

  // Creates dataset `name` (nd dimensions `dims`) under `loc` and writes `data`: the rows
  // `rows` of dims[0] (all of them serially), row-major (may be empty).
  void write_dataset(hid_t loc, const std::string& name, hid_t type, int nd, const hsize_t* dims,
                     const void* data, const std::string& label, RowRange rows) {
    H5Id space(check(H5Screate_simple(nd, dims, nullptr), "H5Screate_simple for " + label),
               H5Sclose);
    H5Id dset(check(H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                               H5P_DEFAULT),
                    "creating dataset " + label),
              H5Dclose);
    hsize_t count = 1;
    for (int i = 0; i < nd; ++i) count *= dims[i];
    if (count > 0 && !parallel)
      check_status(H5Dwrite(dset.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
                   "writing dataset " + label);
    if (count > 0 && parallel) write_rows(dset.get(), space.get(), type, nd, dims, data, rows, label);
    check_status(dset.close(), "closing dataset " + label);
  }

  // Parallel: this rank's rows of a dataset, collectively (a rank without rows selects none).
  void write_rows(hid_t dset, hid_t file_space, hid_t type, int nd, const hsize_t* dims, const void* data,
                  RowRange rows, const std::string& label) {
    const hsize_t start[2] = {static_cast<hsize_t>(rows.begin), 0};
    const hsize_t block[2] = {static_cast<hsize_t>(rows.size()), nd > 1 ? dims[1] : 1};
    const hsize_t one[1] = {1};
    H5Id mem(check(rows.size() ? H5Screate_simple(nd, block, nullptr) : H5Screate_simple(1, one, nullptr),
                   "H5Screate_simple for " + label),
             H5Sclose);
    if (rows.size()) {
      check_status(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, block, nullptr),
                   "selecting rows of " + label);
    } else {
      check_status(H5Sselect_none(file_space), "selecting no rows of " + label);
      check_status(H5Sselect_none(mem.get()), "selecting no rows of " + label);
    }
    H5Id xfer(check(H5Pcreate(H5P_DATASET_XFER), "H5Pcreate"), H5Pclose);
    check_status(H5Pset_dxpl_mpio(xfer.get(), H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");
    static const double dummy = 0.0;  // a buffer for an empty selection
    check_status(H5Dwrite(dset, type, mem.get(), file_space, xfer.get(), data ? data : &dummy),
                 "writing dataset " + label);
  }

  void write_string_attr(hid_t loc, const char* attr, const std::string& value,
                         const std::string& label) {
    H5Id type(check(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
    check_status(H5Tset_size(type.get(), value.empty() ? 1 : value.size()), "H5Tset_size");
    H5Id space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
    H5Id a(check(H5Acreate2(loc, attr, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 "creating attribute " + label + "@" + attr),
           H5Aclose);
    const std::string v = value.empty() ? std::string(1, '\0') : value;
    check_status(H5Awrite(a.get(), type.get(), v.data()), "writing attribute " + label + "@" + attr);
  }

  void write_double_attr(hid_t loc, const char* attr, double value, const std::string& label) {
    H5Id space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
    H5Id a(check(H5Acreate2(loc, attr, H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 "creating attribute " + label + "@" + attr),
           H5Aclose);
    check_status(H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value),
                 "writing attribute " + label + "@" + attr);
  }

  void add_field(const std::string& name, bool on_nodes, int ncomp,
                 const std::vector<double>& data) {
    const char* kind = on_nodes ? "node_field" : "cell_field";
    if (!in_step) fail(std::string(kind) + "('" + name + "') called outside begin_step/end_step");
    if (name.empty()) fail(std::string(kind) + ": empty field name");
    const std::string dset = dataset_name(name);
    if (name == "cell_block") fail(std::string(kind) + ": the field name 'cell_block' is reserved");
    if (dset == "." || dset == "..") fail(std::string(kind) + ": invalid field name '" + name + "'");
    if (current.geometry == current.group + "/" + dset) fail(std::string(kind) + ": '" + name + "' is the step's geometry dataset");
    for (const auto& f : current.fields)
      if (f.name == name || dataset_name(f.name) == dset)
        fail(std::string(kind) + ": field '" + name + "' written twice in one step" +
             (f.name == name ? "" : " (same dataset name as '" + f.name + "')"));
    if (ncomp != 1 && ncomp != 3 && ncomp != 6 && ncomp != 9)
      fail(std::string(kind) + "('" + name + "'): ncomp must be 1, 3, 6 or 9, got " +
           std::to_string(ncomp));
    const std::size_t n = (on_nodes ? nodes : cells).size();
    if (data.size() != n * static_cast<std::size_t>(ncomp))
      fail(std::string(kind) + "('" + name + "'): expected " + std::to_string(n) + " x " +
           std::to_string(ncomp) + " values, got " + std::to_string(data.size()));

    Field f;
    f.name = name;
    f.on_nodes = on_nodes;
    f.ncomp = ncomp == 6 ? 9 : ncomp;
    f.path = current.group + "/" + dset;
    const double* src = data.data();
    std::vector<double> full;
    if (ncomp == 6) {  // xx,yy,zz,xy,yz,xz -> row-major 3x3
      full.resize(n * 9);
      for (std::size_t i = 0; i < n; ++i) {
        const double* s = &data[6 * i];
        double* t = &full[9 * i];
        t[0] = s[0]; t[1] = s[3]; t[2] = s[5];
        t[3] = s[3]; t[4] = s[1]; t[5] = s[4];
        t[6] = s[5]; t[7] = s[4]; t[8] = s[2];
      }
      src = full.data();
    }
    hsize_t dims[2] = {static_cast<hsize_t>(on_nodes ? num_nodes : num_cells), static_cast<hsize_t>(f.ncomp)};
    write_dataset(step_group.get(), dset, H5T_NATIVE_DOUBLE, f.ncomp == 1 ? 1 : 2, dims, src,
                  f.path, on_nodes ? nodes : cells);
    current.fields.push_back(std::move(f));
  }

  std::string data_item(const std::string& path, std::size_t rows, int ncomp, bool is_int,
                        const std::string& indent) const {
    std::ostringstream o;
    o << indent << "<DataItem Dimensions=\"" << rows;
    if (ncomp != 1) o << ' ' << ncomp;
    o << "\" NumberType=\"" << (is_int ? "Int" : "Float") << "\" Precision=\"8\" Format=\"HDF\">"
      << xml_escape(h5_name) << ':' << xml_escape(path) << "</DataItem>\n";
    return o.str();
  }

  // /mesh/topology (every block's cells in block order, one cell type or XDMF "Mixed"),
  // /mesh/cell_block (the block index of each cell) and the block legend. `conn`: this
  // rank's rows of each block (block_part), XDMF node order.
  void write_whole_mesh(const std::vector<std::vector<long long>>& conn) {
    std::set<CellType> types;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      if (blocks[i].ncells > 0) types.insert(blocks[i].type);
      block_legend += (i ? "; " : "") + std::to_string(i) + ": " + blocks[i].grid_name;
    }
    mixed = types.size() != 1;
    if (mixed && types.count(CellType::Line2)) fail("line cells (Polyline) cannot be mixed with other cell types");
    std::vector<long long> topo, cell_block;
    cell_block.reserve(cells.size());
    std::size_t mixed_begin = 0;  // this rank's first entry of a Mixed list
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const Block& b = blocks[i];
      const RowRange part = block_part[i];
      mixed_begin += part.begin * static_cast<std::size_t>(1 + b.npc);
      cell_block.insert(cell_block.end(), part.size(), static_cast<long long>(i));
      for (std::size_t c = 0; c < part.size(); ++c) {
        if (mixed) topo.push_back(xdmf_mixed_type_id(b.type));
        topo.insert(topo.end(), conn[i].begin() + static_cast<std::ptrdiff_t>(c * b.npc),
                    conn[i].begin() + static_cast<std::ptrdiff_t>((c + 1) * b.npc));
      }
    }
    if (mixed) {
      topology = "Mixed";
      for (const Block& b : blocks) topology_size += b.ncells * static_cast<std::size_t>(1 + b.npc);
      const hsize_t d[1] = {static_cast<hsize_t>(topology_size)};
      write_dataset(file.get(), "/mesh/topology", H5T_NATIVE_LLONG, 1, d, topo.data(), "/mesh/topology",
                    RowRange{mixed_begin, mixed_begin + topo.size()});
    } else {
      topology = xdmf_topology_name(*types.begin());
      npc = cell_num_nodes(*types.begin());
      const hsize_t d[2] = {static_cast<hsize_t>(num_cells), static_cast<hsize_t>(npc)};
      write_dataset(file.get(), "/mesh/topology", H5T_NATIVE_LLONG, 2, d, topo.data(), "/mesh/topology", cells);
    }
    H5Id ds(check(H5Dopen2(file.get(), "/mesh/topology", H5P_DEFAULT), "opening /mesh/topology"), H5Dclose);
    write_string_attr(ds.get(), "topology", topology, "/mesh/topology");
    const hsize_t d[1] = {static_cast<hsize_t>(num_cells)};
    write_dataset(file.get(), "/mesh/cell_block", H5T_NATIVE_LLONG, 1, d, cell_block.data(), "/mesh/cell_block", cells);
  }

  // One Uniform grid per step (see the header for why): Time, the whole mesh's Topology
  // and Geometry, the block index per cell, then the step's fields.
  std::string xdmf_text() const {
    std::ostringstream o;
    o << "<?xml version=\"1.0\" ?>\n"
      << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"3.0\">\n"
      << "  <Domain>\n"
      << "    <Information Name=\"cell_block\" Value=\"" << xml_escape(block_legend) << "\"/>\n"
      << "    <Grid Name=\"TimeSeries\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    const std::string in = "          ";
    for (const auto& s : steps) {
      o << "      <Grid Name=\"" << s.group.substr(1) << "\" GridType=\"Uniform\">\n"
        << "        <Time Value=\"" << fmt_double(s.time) << "\"/>\n"
        << "        <Topology TopologyType=\"" << topology << "\" NumberOfElements=\"" << num_cells << "\""
        << (topology == "Polyline" ? " NodesPerElement=\"2\"" : "") << ">\n";
      if (mixed)
        o << data_item("/mesh/topology", topology_size, 1, true, in);
      else
        o << data_item("/mesh/topology", num_cells, npc, true, in);
      o << "        </Topology>\n"
        << "        <Geometry GeometryType=\"XYZ\">\n"
        << data_item(s.geometry, num_nodes, 3, false, in) << "        </Geometry>\n"
        << "        <Attribute Name=\"cell_block\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
        << data_item("/mesh/cell_block", num_cells, 1, true, in) << "        </Attribute>\n";
      for (const auto& f : s.fields) {
        const char* at = f.ncomp == 1 ? "Scalar" : f.ncomp == 3 ? "Vector" : "Tensor";
        o << "        <Attribute Name=\"" << xml_escape(f.name) << "\" AttributeType=\"" << at
          << "\" Center=\"" << (f.on_nodes ? "Node" : "Cell") << "\">\n"
          << data_item(f.path, f.on_nodes ? num_nodes : num_cells, f.ncomp, false, in)
          << "        </Attribute>\n";
      }
      o << "      </Grid>\n";
    }
    o << "    </Grid>\n"
      << "  </Domain>\n"
      << "</Xdmf>\n";
    return o.str();
  }

  // The blocks, counts and this rank's rows of the outline of `mesh` (rank of nranks).
  void set_outline(const XdmfMesh& mesh, int nranks) {
    num_nodes = mesh.num_nodes;
    std::set<std::string> used;
    for (std::size_t i = 0; i < mesh.blocks.size(); ++i) {
      const XdmfMesh::Block& xb = mesh.blocks[i];
      Block b;
      b.name = xb.name;
      b.type = xb.type;
      b.topology = xdmf_topology_name(xb.type);
      if (!b.topology) fail("volume block '" + xb.name + "' has a cell type without XDMF topology");
      b.npc = cell_num_nodes(xb.type);
      b.ncells = xb.num_cells;
      num_cells += b.ncells;
      b.grid_name = xb.name.empty() ? "block_" + std::to_string(i) : xb.name;
      if (!used.insert(b.grid_name).second) {
        b.grid_name += "_" + std::to_string(i);
        used.insert(b.grid_name);
      }
      b.conn_path = "/mesh/block_" + std::to_string(i) + "/connectivity";
      blocks.push_back(std::move(b));
    }
    const XdmfRows rows = xdmf_rows(mesh, rank, nranks);
    nodes = rows.nodes;
    cells = rows.cells;
    block_part = rows.blocks;
  }

  // This rank's rows of `mesh` match its outline (set_outline).
  void check_rows(const XdmfMesh& mesh) const {
    if (mesh.x.size() != 3 * nodes.size())
      fail("expected " + std::to_string(nodes.size()) + " x 3 coordinates, got " + std::to_string(mesh.x.size()));
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const XdmfMesh::Block& xb = mesh.blocks[i];
      if (xb.conn.size() != block_part[i].size() * static_cast<std::size_t>(blocks[i].npc))
        fail("volume block '" + xb.name + "': connectivity size does not match its cell type and rows");
      for (long long n : xb.conn)
        if (n < 0 || static_cast<std::size_t>(n) >= num_nodes)
          fail("volume block '" + xb.name + "': node " + std::to_string(n) + " out of range");
    }
  }

  // The .h5 (MPI-IO in parallel).
  void create_file() {
    H5Id fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
    if (parallel) check_status(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL), "H5Pset_fapl_mpio");
    if (is_link(h5_path)) throw std::runtime_error(h5_path + ": " + open_error(ELOOP));
    file = H5Id(check(H5Fcreate(h5_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), "creating the HDF5 file"),
                H5Fclose);
  }

  // /mesh: this rank's rows of the coordinates, of every block's connectivity and of the
  // whole mesh's topology (`mesh`: this rank's rows, checked by check_rows).
  void write_mesh(const XdmfMesh& mesh) {
    H5Id g(check(H5Gcreate2(file.get(), "/mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "creating group /mesh"),
           H5Gclose);
    hsize_t dims[2] = {static_cast<hsize_t>(num_nodes), 3};
    write_dataset(g.get(), "coordinates", H5T_NATIVE_DOUBLE, 2, dims, mesh.x.data(), "/mesh/coordinates", nodes);
    std::vector<std::vector<long long>> block_conn;  // this rank's rows, XDMF node order
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const Block& b = blocks[i];
      const std::vector<long long>& gmsh = mesh.blocks[i].conn;
      const std::string gname = "/mesh/block_" + std::to_string(i);
      H5Id bg(check(H5Gcreate2(file.get(), gname.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    "creating group " + gname),
              H5Gclose);
      write_string_attr(bg.get(), "name", b.name, gname);
      write_string_attr(bg.get(), "topology", b.topology, gname);
      int perm[kMaxCellNodes];
      xdmf_node_permutation(b.type, perm);
      const RowRange part = block_part[i];
      std::vector<long long> conn(part.size() * static_cast<std::size_t>(b.npc));
      for (std::size_t c = 0; c < part.size(); ++c)
        for (int j = 0; j < b.npc; ++j) conn[c * b.npc + j] = gmsh[c * b.npc + perm[j]];
      hsize_t cd[2] = {static_cast<hsize_t>(b.ncells), static_cast<hsize_t>(b.npc)};
      write_dataset(bg.get(), "connectivity", H5T_NATIVE_LLONG, 2, cd, conn.data(), b.conn_path, part);
      block_conn.push_back(std::move(conn));
    }
    write_whole_mesh(block_conn);
    check_status(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "H5Fflush");
  }

  void write_xdmf() const {
    const std::string tmp = xdmf_path + ".tmp";
    check_write(write_text_file(tmp, xdmf_text()), "XdmfWriter: writing", tmp);
    std::error_code ec;
    fs::rename(tmp, xdmf_path, ec);
    errno = ec.value();
    check_write(!ec, "XdmfWriter: renaming " + tmp + " to", xdmf_path);
  }
};

XdmfWriter::XdmfWriter(const std::string& dir, const std::string& basename, const Mesh& mesh)
    : XdmfWriter(dir, basename, xdmf_mesh(mesh, 0, 1), MPI_COMM_NULL) {}

namespace {
int comm_rank(MPI_Comm comm) {
  int r = 0;
  if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &r);
  return r;
}
int comm_size(MPI_Comm comm) {
  int n = 1;
  if (comm != MPI_COMM_NULL) MPI_Comm_size(comm, &n);
  return n;
}
}  // namespace

XdmfWriter::XdmfWriter(const std::string& dir, const std::string& basename, const Mesh& mesh, MPI_Comm comm)
    : XdmfWriter(dir, basename, xdmf_mesh(mesh, comm_rank(comm), comm_size(comm)), comm) {}

XdmfWriter::XdmfWriter(const std::string& dir, const std::string& basename, const XdmfMesh& mesh, MPI_Comm comm)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (basename.empty() || basename.find_first_of("/: \t\r\n") != std::string::npos)
    throw std::runtime_error("XdmfWriter: invalid basename '" + basename + "' in " + dir);
  m.h5_name = basename + ".h5";
  m.h5_path = (fs::path(dir) / m.h5_name).string();
  m.xdmf_path = (fs::path(dir) / (basename + ".xdmf")).string();
  const int nranks = comm_size(comm);
  m.rank = comm_rank(comm);
  m.parallel = nranks > 1;
  if (m.parallel) m.comm = comm;
  // Check the rows before creating anything; every rank throws when any rank's are wrong.
  std::string error;
  try {
    m.set_outline(mesh, nranks);
    m.check_rows(mesh);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  int bad = error.empty() ? 0 : 1, any = bad;
  if (m.parallel) MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, comm);
  if (any) throw std::runtime_error(bad ? error : "XdmfWriter: another rank's mesh rows are invalid (file " + m.h5_path + ")");
  m.create_file();
  m.write_mesh(mesh);
}

XdmfWriter::~XdmfWriter() {
  // Closing is collective in parallel: not while an exception unwinds (see the header).
  if (impl_ && impl_->parallel && std::uncaught_exceptions() > 0) {
    impl_->step_group.release();
    impl_->file.release();
  }
}  // Impl's handles close the step group, then the file

RowRange XdmfWriter::node_rows() const { return impl_->nodes; }
RowRange XdmfWriter::cell_rows() const { return impl_->cells; }

void XdmfWriter::begin_step(double time) {
  Impl& m = *impl_;
  if (m.in_step) m.fail("begin_step called twice without end_step");
  m.current = Impl::Step{};
  m.current.time = time;
  m.current.group = "/step_" + std::to_string(m.steps.size());
  m.step_group = H5Id(m.check(H5Gcreate2(m.file.get(), m.current.group.c_str(), H5P_DEFAULT,
                                         H5P_DEFAULT, H5P_DEFAULT),
                              "creating group " + m.current.group),
                      H5Gclose);
  m.write_double_attr(m.step_group.get(), "time", time, m.current.group);
  m.in_step = true;
}

void XdmfWriter::node_field(const std::string& name, int ncomp, const std::vector<double>& data) {
  impl_->add_field(name, true, ncomp, data);
}

void XdmfWriter::cell_field(const std::string& name, int ncomp, const std::vector<double>& data) {
  impl_->add_field(name, false, ncomp, data);
}

void XdmfWriter::geometry(const std::vector<double>& x) {
  Impl& m = *impl_;
  if (!m.in_step) m.fail("geometry() called outside begin_step/end_step");
  const std::string path = m.current.group + "/coordinates";
  if (m.current.geometry == path) m.fail("geometry() called twice in one step");
  for (const auto& f : m.current.fields)
    if (f.path == path) m.fail("geometry(): a field named 'coordinates' holds its dataset name");
  if (x.size() != 3 * m.nodes.size())
    m.fail("geometry(): expected " + std::to_string(m.nodes.size()) + " x 3 values, got " + std::to_string(x.size()));
  const hsize_t dims[2] = {static_cast<hsize_t>(m.num_nodes), 3};
  m.write_dataset(m.step_group.get(), "coordinates", H5T_NATIVE_DOUBLE, 2, dims, x.data(), path, m.nodes);
  m.current.geometry = path;
}

void XdmfWriter::end_step() {
  Impl& m = *impl_;
  if (!m.in_step) m.fail("end_step called without begin_step");
  m.check_status(m.step_group.close(), "closing group " + m.current.group);
  m.in_step = false;
  m.check_status(H5Fflush(m.file.get(), H5F_SCOPE_GLOBAL), "H5Fflush");
  m.steps.push_back(std::move(m.current));
  m.current = Impl::Step{};
  if (m.rank != 0) return;
  check_write(true, "XdmfWriter: writing step " + std::to_string(m.steps.size() - 1) + " to", m.h5_path);  // test hook
  m.write_xdmf();
}

const std::string& XdmfWriter::h5_path() const { return impl_->h5_path; }
const std::string& XdmfWriter::xdmf_path() const { return impl_->xdmf_path; }
int XdmfWriter::num_steps() const { return static_cast<int>(impl_->steps.size()); }

}  // namespace stentor
