#include "mesh/Mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace stentor {
namespace {
std::vector<std::string> unique_names(const std::vector<CellBlock>& blocks) {
  std::vector<std::string> names;  // first-appearance (block) order
  for (const auto& b : blocks)
    if (std::find(names.begin(), names.end(), b.name) == names.end()) names.push_back(b.name);
  return names;
}

// Minimal byte (de)serialiser (broadcast, gmsh process).
struct Writer {
  std::vector<char> buf;
  template <class T>
  void pod(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    buf.insert(buf.end(), p, p + sizeof(T));
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    pod<std::uint64_t>(v.size());
    const char* p = reinterpret_cast<const char*>(v.data());
    buf.insert(buf.end(), p, p + v.size() * sizeof(T));
  }
  void str(const std::string& s) {
    pod<std::uint64_t>(s.size());
    buf.insert(buf.end(), s.begin(), s.end());
  }
};

struct Reader {
  const std::vector<char>& buf;
  std::size_t pos = 0;
  void need(std::uint64_t n) const {
    if (n > buf.size() - pos) throw std::runtime_error("serialized mesh: truncated data");
  }
  template <class T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, buf.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> vec() {
    const auto n = pod<std::uint64_t>();
    if (n > (buf.size() - pos) / sizeof(T)) throw std::runtime_error("serialized mesh: truncated data");
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), buf.data() + pos, n * sizeof(T));
    pos += n * sizeof(T);
    return v;
  }
  std::string str() {
    const auto n = pod<std::uint64_t>();
    need(n);
    std::string s(buf.data() + pos, n);
    pos += n;
    return s;
  }
};

void write_blocks(Writer& w, const std::vector<CellBlock>& blocks) {
  w.pod<std::uint64_t>(blocks.size());
  for (const auto& b : blocks) {
    w.str(b.name);
    w.pod<int>(b.physical_tag);
    w.pod<int>(static_cast<int>(b.type));
    w.pod<int>(b.nodes_per_cell);
    w.vec(b.conn);
    w.vec(b.cell_id);
    w.vec(b.part);
    w.vec(b.side);
    w.vec(b.adjacent);
    w.pod<std::uint64_t>(b.whole_cells);
  }
}

std::vector<CellBlock> read_blocks(Reader& r) {
  const auto n = r.pod<std::uint64_t>();
  r.need(n);  // every block takes more than one byte
  std::vector<CellBlock> blocks(n);
  for (auto& b : blocks) {
    b.name = r.str();
    b.physical_tag = r.pod<int>();
    b.type = static_cast<CellType>(r.pod<int>());
    b.nodes_per_cell = r.pod<int>();
    b.conn = r.vec<GId>();
    b.cell_id = r.vec<GId>();
    b.part = r.vec<int>();
    b.side = r.vec<signed char>();
    b.adjacent = r.vec<GId>();
    b.whole_cells = r.pod<std::uint64_t>();
  }
  return blocks;
}

}  // namespace

std::vector<char> serialize_mesh(const Mesh& m) {
  Writer w;
  w.pod<int>(m.dim);
  w.str(m.source);
  w.vec(m.x);
  write_blocks(w, m.volumes);
  write_blocks(w, m.boundaries);
  w.pod<char>(m.partial ? 1 : 0);
  w.vec(m.node_ids);
  w.pod<std::uint64_t>(m.whole_nodes);
  w.pod(m.whole_box);
  return std::move(w.buf);
}

Mesh deserialize_mesh(const std::vector<char>& buf) {
  Reader r{buf};
  Mesh out;
  out.dim = r.pod<int>();
  out.source = r.str();
  out.x = r.vec<double>();
  out.volumes = read_blocks(r);
  out.boundaries = read_blocks(r);
  out.partial = r.pod<char>() != 0;
  out.node_ids = r.vec<GId>();
  out.whole_nodes = r.pod<std::uint64_t>();
  out.whole_box = r.pod<Mesh::Box>();
  if (r.pos != buf.size()) throw std::runtime_error("serialized mesh: trailing data");
  return out;
}

std::pair<std::size_t, std::size_t> locate_cell(const Mesh& m, GId id) {
  for (std::size_t b = 0; b < m.volumes.size(); ++b) {
    const CellBlock& blk = m.volumes[b];
    if (blk.num_cells() == 0 || id < blk.cell_id.front() || id > blk.cell_id.back()) continue;
    if (m.partial) {
      const auto it = std::lower_bound(blk.cell_id.begin(), blk.cell_id.end(), id);
      if (it != blk.cell_id.end() && *it == id) return {b, static_cast<std::size_t>(it - blk.cell_id.begin())};
      continue;
    }
    const auto i = static_cast<std::size_t>(id - blk.cell_id.front());
    if (blk.cell_id[i] != id) throw std::logic_error("locate_cell: the cell ids of block '" + blk.name + "' are not consecutive");
    return {b, i};
  }
  throw std::logic_error("locate_cell: no volume cell " + std::to_string(id));
}

std::vector<std::string> Mesh::volume_group_names() const { return unique_names(volumes); }
std::vector<std::string> Mesh::boundary_group_names() const { return unique_names(boundaries); }

long long Mesh::stored_index(GId g) const {
  if (!partial) return g >= 0 && static_cast<std::size_t>(g) < num_stored_nodes() ? g : -1;
  const auto it = std::lower_bound(node_ids.begin(), node_ids.end(), g);
  return it != node_ids.end() && *it == g ? static_cast<long long>(it - node_ids.begin()) : -1;
}

const double* Mesh::coord(GId g) const {
  const long long i = stored_index(g);
  if (i < 0) throw std::logic_error("Mesh::coord: node " + std::to_string(g) + " is not stored on this rank");
  return &x[3 * static_cast<std::size_t>(i)];
}

std::size_t Mesh::bytes() const {
  std::size_t n = x.size() * sizeof(double) + node_ids.size() * sizeof(GId);
  for (const auto* blocks : {&volumes, &boundaries})
    for (const CellBlock& b : *blocks)
      n += (b.conn.size() + b.cell_id.size() + b.adjacent.size()) * sizeof(GId) + b.part.size() * sizeof(int) + b.side.size();
  return n;
}

Mesh::Box Mesh::bounding_box() const {
  if (partial) return whole_box;
  Box b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (std::size_t n = 0; n < num_stored_nodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      b.lo[c] = std::min(b.lo[c], x[3 * n + c]);
      b.hi[c] = std::max(b.hi[c], x[3 * n + c]);
    }
  return b;
}

double Mesh::Box::diagonal() const {
  double d = 0.0;
  for (int c = 0; c < 3; ++c) d += (hi[c] - lo[c]) * (hi[c] - lo[c]);
  return std::sqrt(d);
}

}  // namespace stentor
