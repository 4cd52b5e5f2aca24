#include "io/Checkpoint.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <stdexcept>

namespace stentor {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "stentor checkpoint";
constexpr long long kVersion = 1;

// An HDF5 handle closed by its own close function.
class H5 {
 public:
  H5(hid_t id, herr_t (*close)(hid_t), const std::string& what, const std::string& file) : id_(id), close_(close) {
    if (id < 0) throw std::runtime_error(file + ": " + what + " failed");
  }
  ~H5() {
    if (id_ >= 0) close_(id_);
  }
  H5(const H5&) = delete;
  H5& operator=(const H5&) = delete;
  hid_t get() const { return id_; }
  void close(const std::string& file) {
    const herr_t rc = close_(id_);
    id_ = -1;
    if (rc < 0) throw std::runtime_error(file + ": closing failed");
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t rc, const std::string& what, const std::string& file) {
  if (rc < 0) throw std::runtime_error(file + ": " + what + " failed");
}

void write_attr(hid_t loc, const std::string& name, hid_t type, const void* value, const std::string& file) {
  H5 space(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", file);
  H5 attr(H5Acreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "attribute " + name, file);
  check(H5Awrite(attr.get(), type, value), "writing attribute " + name, file);
}

void write_string_attr(hid_t loc, const std::string& name, const std::string& value, const std::string& file) {
  H5 type(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy", file);
  check(H5Tset_size(type.get(), std::max<std::size_t>(1, value.size())), "H5Tset_size", file);
  std::string v = value.empty() ? std::string(1, '\0') : value;
  write_attr(loc, name, type.get(), v.data(), file);
}

// Where this rank's rows go in a table written by several ranks: its first row and the
// table's row count (serial: 0 and its own count). Collective when comm is not null.
struct RowSpan {
  hsize_t first = 0, total = 0;
};
RowSpan row_span(std::size_t mine, MPI_Comm comm) {
  unsigned long long n = mine, first = 0, total = mine;
  if (comm != MPI_COMM_NULL) {
    MPI_Exscan(&n, &first, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) first = 0;  // MPI_Exscan leaves rank 0's result undefined
    MPI_Allreduce(&n, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
  }
  return {first, total};
}

// Dataset `name` of `span.total` rows of `cols` columns (1: a vector), this rank's `n` rows
// from `span.first`; collective when `dxpl` is a collective MPI-IO transfer list.
void write_dataset(hid_t loc, const char* name, hid_t type, hsize_t cols, RowSpan span, std::size_t n, const void* data, hid_t dxpl,
                   const std::string& file) {
  const int rank = cols > 1 ? 2 : 1;
  const hsize_t dims[2] = {span.total, cols}, start[2] = {span.first, 0}, count[2] = {n, cols};
  H5 space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "H5Screate_simple", file);
  H5 dset(H5Dcreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
          std::string("dataset ") + name, file);
  if (span.total == 0) return;
  H5 mem(H5Screate_simple(rank, count, nullptr), H5Sclose, "H5Screate_simple", file);
  if (n > 0) {
    check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting rows", file);
  } else {
    check(H5Sselect_none(space.get()), "H5Sselect_none", file);
    check(H5Sselect_none(mem.get()), "H5Sselect_none", file);
  }
  check(H5Dwrite(dset.get(), type, mem.get(), space.get(), dxpl, n > 0 ? data : nullptr), std::string("writing ") + name, file);
}

void write_tables(hid_t root, const CheckpointData& d, MPI_Comm comm, hid_t dxpl, const std::string& file) {
  H5 tables(H5Gcreate2(root, "tables", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group tables", file);
  for (const auto& [name, t] : d.tables) {
    H5 g(H5Gcreate2(tables.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group " + name, file);
    const RowSpan span = row_span(t.ids.size(), comm);
    write_dataset(g.get(), "ids", H5T_NATIVE_LLONG, 1, span, t.ids.size(), t.ids.data(), dxpl, file);
    write_dataset(g.get(), "values", H5T_NATIVE_DOUBLE, static_cast<hsize_t>(t.ncols), span, t.ids.size(), t.values.data(), dxpl, file);
  }
}

// STENTOR_TEST_KILL_CHECKPOINT=N: SIGKILL while writing the N-th checkpoint of this process.
void test_kill_hook() {
  static int count = 0;
  ++count;
  const char* v = std::getenv("STENTOR_TEST_KILL_CHECKPOINT");
  if (v && *v && std::atoi(v) == count) std::raise(SIGKILL);
}

// comm: MPI_COMM_NULL (serial) or the communicator of the ranks writing their rows.
void write_file(const std::string& tmp, const CheckpointData& d, MPI_Comm comm) {
  H5 fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate", tmp);
  H5 dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate", tmp);
  if (comm != MPI_COMM_NULL) {
    check(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL), "H5Pset_fapl_mpio", tmp);
    check(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio", tmp);
  }
  H5 f(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose, "creating the file", tmp);
  write_string_attr(f.get(), "format", kFormat, tmp);
  write_attr(f.get(), "version", H5T_NATIVE_LLONG, &kVersion, tmp);
  {
    H5 g(H5Gcreate2(f.get(), "reals", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group reals", tmp);
    for (const auto& [k, v] : d.reals) write_attr(g.get(), k, H5T_NATIVE_DOUBLE, &v, tmp);
  }
  {
    H5 g(H5Gcreate2(f.get(), "ints", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group ints", tmp);
    for (const auto& [k, v] : d.ints) write_attr(g.get(), k, H5T_NATIVE_LLONG, &v, tmp);
  }
  {
    H5 g(H5Gcreate2(f.get(), "strings", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group strings", tmp);
    for (const auto& [k, v] : d.strings) write_string_attr(g.get(), k, v, tmp);
  }
  write_tables(f.get(), d, comm, dxpl.get(), tmp);
  test_kill_hook();
  check(H5Fflush(f.get(), H5F_SCOPE_GLOBAL), "H5Fflush", tmp);
  f.close(tmp);
}

void fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// --- reading ---

herr_t collect_attr_name(hid_t, const char* name, const H5A_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

std::vector<std::string> attr_names(hid_t loc) {
  std::vector<std::string> names;
  hsize_t idx = 0;
  H5Aiterate2(loc, H5_INDEX_NAME, H5_ITER_INC, &idx, collect_attr_name, &names);
  return names;
}

std::string read_string_attr(hid_t loc, const std::string& name, const std::string& file) {
  H5 attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, "attribute " + name, file);
  H5 type(H5Aget_type(attr.get()), H5Tclose, "type of " + name, file);
  if (H5Tget_class(type.get()) != H5T_STRING) throw std::runtime_error(file + ": attribute " + name + " is not a string");
  const std::size_t n = H5Tget_size(type.get());
  std::string v(n, '\0');
  check(H5Aread(attr.get(), type.get(), v.data()), "reading " + name, file);
  v.resize(std::strlen(v.c_str()));
  return v;
}

template <class T>
T read_attr(hid_t loc, const std::string& name, hid_t type, const std::string& file) {
  H5 attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, "attribute " + name, file);
  T v{};
  check(H5Aread(attr.get(), type, &v), "reading " + name, file);
  return v;
}

herr_t collect_link_name(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

CheckpointTable read_table(hid_t tables, const std::string& name, const std::string& file) {
  H5 g(H5Gopen2(tables, name.c_str(), H5P_DEFAULT), H5Gclose, "table " + name, file);
  H5 ids(H5Dopen2(g.get(), "ids", H5P_DEFAULT), H5Dclose, "table " + name + " ids", file);
  H5 vals(H5Dopen2(g.get(), "values", H5P_DEFAULT), H5Dclose, "table " + name + " values", file);
  H5 is(H5Dget_space(ids.get()), H5Sclose, "ids space", file), vs(H5Dget_space(vals.get()), H5Sclose, "values space", file);
  hsize_t n = 0, dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(is.get()) != 1 || H5Sget_simple_extent_ndims(vs.get()) != 2)
    throw std::runtime_error(file + ": table " + name + " has the wrong shape");
  H5Sget_simple_extent_dims(is.get(), &n, nullptr);
  H5Sget_simple_extent_dims(vs.get(), dims, nullptr);
  if (dims[0] != n) throw std::runtime_error(file + ": table " + name + ": ids and values differ in length");
  CheckpointTable t;
  t.ncols = static_cast<int>(dims[1]);
  t.ids.resize(n);
  t.values.resize(n * dims[1]);
  if (n > 0) {
    check(H5Dread(ids.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.ids.data()), "reading " + name, file);
    if (dims[1] > 0) check(H5Dread(vals.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.values.data()), "reading " + name, file);
  }
  if (!std::is_sorted(t.ids.begin(), t.ids.end())) t.sort_rows();
  return t;
}

CheckpointData read_file(const std::string& path) {
  H5 f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "not an HDF5 file, or unreadable:", path);
  if (H5Aexists(f.get(), "format") <= 0 || read_string_attr(f.get(), "format", path) != kFormat)
    throw std::runtime_error(path + ": not a Stentor checkpoint (no 'format' attribute \"" + kFormat + "\")");
  const long long version = read_attr<long long>(f.get(), "version", H5T_NATIVE_LLONG, path);
  if (version != kVersion)
    throw std::runtime_error(path + ": checkpoint format version " + std::to_string(version) + ", this build reads version " +
                             std::to_string(kVersion));
  CheckpointData d;
  {
    H5 g(H5Gopen2(f.get(), "reals", H5P_DEFAULT), H5Gclose, "group reals", path);
    for (const auto& k : attr_names(g.get())) d.reals[k] = read_attr<double>(g.get(), k, H5T_NATIVE_DOUBLE, path);
  }
  {
    H5 g(H5Gopen2(f.get(), "ints", H5P_DEFAULT), H5Gclose, "group ints", path);
    for (const auto& k : attr_names(g.get())) d.ints[k] = read_attr<long long>(g.get(), k, H5T_NATIVE_LLONG, path);
  }
  {
    H5 g(H5Gopen2(f.get(), "strings", H5P_DEFAULT), H5Gclose, "group strings", path);
    for (const auto& k : attr_names(g.get())) d.strings[k] = read_string_attr(g.get(), k, path);
  }
  H5 tables(H5Gopen2(f.get(), "tables", H5P_DEFAULT), H5Gclose, "group tables", path);
  std::vector<std::string> names;
  hsize_t idx = 0;
  check(H5Literate(tables.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect_link_name, &names), "listing tables", path);
  for (const auto& n : names) d.tables[n] = read_table(tables.get(), n, path);
  return d;
}

// --- byte image ---

template <class T>
void put(std::vector<char>& b, const T& v) {
  const char* p = reinterpret_cast<const char*>(&v);
  b.insert(b.end(), p, p + sizeof(T));
}
void put_str(std::vector<char>& b, const std::string& s) {
  put(b, static_cast<std::size_t>(s.size()));
  b.insert(b.end(), s.begin(), s.end());
}
template <class T>
void put_vec(std::vector<char>& b, const std::vector<T>& v) {
  put(b, static_cast<std::size_t>(v.size()));
  const char* p = reinterpret_cast<const char*>(v.data());
  b.insert(b.end(), p, p + v.size() * sizeof(T));
}

struct Reader {
  const std::vector<char>& b;
  std::size_t pos = 0;
  template <class T>
  T get() {
    if (pos + sizeof(T) > b.size()) throw std::runtime_error("checkpoint image truncated");
    T v;
    std::memcpy(&v, b.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
  std::string str() {
    const auto n = get<std::size_t>();
    if (pos + n > b.size()) throw std::runtime_error("checkpoint image truncated");
    std::string s(b.data() + pos, n);
    pos += n;
    return s;
  }
  template <class T>
  std::vector<T> vec() {
    const auto n = get<std::size_t>();
    if (pos + n * sizeof(T) > b.size()) throw std::runtime_error("checkpoint image truncated");
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), b.data() + pos, n * sizeof(T));
    pos += n * sizeof(T);
    return v;
  }
};

}  // namespace

void CheckpointTable::sort_rows() {
  std::vector<std::size_t> order(ids.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  std::vector<long long> sid(ids.size());
  std::vector<double> sv(values.size());
  const auto k = static_cast<std::size_t>(ncols);
  for (std::size_t i = 0; i < order.size(); ++i) {
    sid[i] = ids[order[i]];
    std::copy(values.begin() + static_cast<std::ptrdiff_t>(order[i] * k), values.begin() + static_cast<std::ptrdiff_t>(order[i] * k + k),
              sv.begin() + static_cast<std::ptrdiff_t>(i * k));
  }
  ids.swap(sid);
  values.swap(sv);
}

const double* CheckpointTable::find(long long id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  if (it == ids.end() || *it != id) return nullptr;
  return values.data() + static_cast<std::size_t>(it - ids.begin()) * static_cast<std::size_t>(ncols);
}

double CheckpointData::real(const std::string& name) const {
  const auto it = reals.find(name);
  if (it == reals.end()) throw std::runtime_error("missing '" + name + "'");
  return it->second;
}
long long CheckpointData::integer(const std::string& name) const {
  const auto it = ints.find(name);
  if (it == ints.end()) throw std::runtime_error("missing '" + name + "'");
  return it->second;
}
const std::string& CheckpointData::string(const std::string& name) const {
  const auto it = strings.find(name);
  if (it == strings.end()) throw std::runtime_error("missing '" + name + "'");
  return it->second;
}
const CheckpointTable& CheckpointData::table(const std::string& name) const {
  const auto it = tables.find(name);
  if (it == tables.end()) throw std::runtime_error("missing table '" + name + "'");
  return it->second;
}

std::string previous_checkpoint_path(const std::string& path) {
  fs::path p(path);
  return (p.parent_path() / (p.stem().string() + ".prev" + p.extension().string())).string();
}

namespace {

// The written temporary file into place, keeping the checkpoint it replaces (see the header).
void replace_checkpoint(const std::string& tmp, const std::string& path) {
  fsync_path(tmp, false);
  std::error_code ec;
  if (fs::exists(path, ec)) {
    // Keep the checkpoint being replaced: a second name for it, renamed into place, so
    // that `path` itself never disappears.
    const std::string prev = previous_checkpoint_path(path), link = prev + ".tmp";
    fs::remove(link, ec);
    fs::create_hard_link(path, link, ec);
    if (!ec) fs::rename(link, prev, ec);
    if (ec) throw std::runtime_error(path + ": cannot keep the previous checkpoint as " + prev + ": " + ec.message());
  }
  fs::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot rename " + tmp + " to it: " + ec.message());
  fsync_path(fs::path(path).parent_path().empty() ? "." : fs::path(path).parent_path().string(), true);
}

// The lowest failing rank's message on every rank, thrown there. Collective.
void throw_if_any_failed(std::string err, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int mine = err.empty() ? INT_MAX : rank, who = INT_MAX;
  MPI_Allreduce(&mine, &who, 1, MPI_INT, MPI_MIN, comm);
  if (who == INT_MAX) return;
  unsigned long long n = err.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, who, comm);
  err.resize(n);
  MPI_Bcast(err.data(), static_cast<int>(n), MPI_CHAR, who, comm);
  throw std::runtime_error(err);
}

}  // namespace

void write_checkpoint_file(const std::string& path, const CheckpointData& data) {
  const std::string tmp = path + ".tmp";
  write_file(tmp, data, MPI_COMM_NULL);
  replace_checkpoint(tmp, path);
}

void write_checkpoint_file(const std::string& path, const CheckpointData& mine, MPI_Comm comm) {
  int nranks = 1, rank = 0;
  MPI_Comm_size(comm, &nranks);
  MPI_Comm_rank(comm, &rank);
  if (nranks == 1) return write_checkpoint_file(path, mine);
  const std::string tmp = path + ".tmp";
  std::string err;
  try {
    write_file(tmp, mine, comm);
  } catch (const std::exception& e) {
    err = e.what();
  }
  throw_if_any_failed(err, comm);
  if (rank == 0) try {
      replace_checkpoint(tmp, path);
    } catch (const std::exception& e) {
      err = e.what();
    }
  throw_if_any_failed(err, comm);
}

CheckpointData read_checkpoint_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw std::runtime_error(path + ": no such checkpoint file");
  // Our messages, not HDF5's error stack, for a file that is not what it should be.
  H5E_auto2_t func = nullptr;
  void* client = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &func, &client);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  try {
    CheckpointData d = read_file(path);
    H5Eset_auto2(H5E_DEFAULT, func, client);
    return d;
  } catch (...) {
    H5Eset_auto2(H5E_DEFAULT, func, client);
    throw;
  }
}

std::vector<char> pack_checkpoint(const CheckpointData& d) {
  std::vector<char> b;
  put(b, d.reals.size());
  for (const auto& [k, v] : d.reals) put_str(b, k), put(b, v);
  put(b, d.ints.size());
  for (const auto& [k, v] : d.ints) put_str(b, k), put(b, v);
  put(b, d.strings.size());
  for (const auto& [k, v] : d.strings) put_str(b, k), put_str(b, v);
  put(b, d.tables.size());
  for (const auto& [k, t] : d.tables) {
    put_str(b, k);
    put(b, t.ncols);
    put_vec(b, t.ids);
    put_vec(b, t.values);
  }
  return b;
}

CheckpointData unpack_checkpoint(const std::vector<char>& bytes) {
  Reader r{bytes};
  CheckpointData d;
  for (auto n = r.get<std::size_t>(); n > 0; --n) {
    std::string k = r.str();
    d.reals[k] = r.get<double>();
  }
  for (auto n = r.get<std::size_t>(); n > 0; --n) {
    std::string k = r.str();
    d.ints[k] = r.get<long long>();
  }
  for (auto n = r.get<std::size_t>(); n > 0; --n) {
    std::string k = r.str();
    d.strings[k] = r.str();
  }
  for (auto n = r.get<std::size_t>(); n > 0; --n) {
    std::string k = r.str();
    CheckpointTable t;
    t.ncols = r.get<int>();
    t.ids = r.vec<long long>();
    t.values = r.vec<double>();
    d.tables[k] = std::move(t);
  }
  return d;
}

}  // namespace stentor
