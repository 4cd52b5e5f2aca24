#include "io/Checkpoint.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#include "io/RankVote.hpp"
#include "io/SafeFile.hpp"

namespace stentor {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "stentor checkpoint";
constexpr long long kVersion = 2;  // 2: the payload checksum (attribute "checksum")
// The most columns a table may have, and the seconds a rank waits for the others to
// agree on a failed parallel write before the job is ended (io/RankVote.hpp).
constexpr hsize_t kMaxColumns = 1 << 16;
constexpr double kWriteVoteTimeout = 120.0;

// The payload checksum: FNV-1a of the scalars (names and values, in name order) plus the
// sum, modulo 2^64, of one FNV-1a per table row (table name, id, values). A sum, so that
// ranks holding different rows add their parts (MPI_SUM) and the order of rows does not
// matter; any changed byte of a value, id, name or scalar changes it.
std::uint64_t scalar_sum(const CheckpointData& d) {
  Fnv1a f;
  for (const auto& [k, v] : d.reals) f.add(k), f.add(&v, sizeof v);
  for (const auto& [k, v] : d.ints) f.add(k), f.add(&v, sizeof v);
  for (const auto& [k, v] : d.strings) f.add(k), f.add(v);
  return f.h;
}
std::uint64_t row_sum(const CheckpointData& d) {
  std::uint64_t sum = 0;
  for (const auto& [name, t] : d.tables) {
    const auto k = static_cast<std::size_t>(t.ncols);
    for (std::size_t i = 0; i < t.ids.size(); ++i) {
      Fnv1a f;
      f.add(name);
      f.add(&t.ids[i], sizeof(long long));
      f.add(t.values.data() + i * k, k * sizeof(double));
      sum += f.h;
    }
  }
  return sum;
}
std::string checksum_text(std::uint64_t sum) {
  Fnv1a f;
  f.h = sum;
  return f.hex();
}

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
// from `span.first` (the dataset's creation is collective in parallel, the write not).
void write_dataset(hid_t loc, const char* name, hid_t type, hsize_t cols, RowSpan span, std::size_t n, const void* data, hid_t dxpl,
                   const std::string& file) {
  const int rank = cols > 1 ? 2 : 1;
  const hsize_t dims[2] = {span.total, cols}, start[2] = {span.first, 0}, count[2] = {n, cols};
  H5 space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "H5Screate_simple", file);
  H5 dset(H5Dcreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
          std::string("dataset ") + name, file);
  if (span.total == 0) return;
  if (n == 0) return;  // independent transfers (see write_file): a rank without rows writes nothing
  H5 mem(H5Screate_simple(rank, count, nullptr), H5Sclose, "H5Screate_simple", file);
  check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting rows", file);
  check(H5Dwrite(dset.get(), type, mem.get(), space.get(), dxpl, data), std::string("writing ") + name, file);
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

// STENTOR_TEST_FAIL_CHECKPOINT_RANK=R: rank R's checkpoint writes fail after its rows, as a
// full disk on that rank's node would (the other ranks' writes succeed).
void test_fail_rank_hook(MPI_Comm comm, const std::string& tmp) {
  const char* v = std::getenv("STENTOR_TEST_FAIL_CHECKPOINT_RANK");
  if (!v || !*v) return;
  int rank = 0;
  if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &rank);
  if (std::atoi(v) == rank) throw std::runtime_error(tmp + ": writing the rows failed: " + std::strerror(ENOSPC) + " (test hook)");
}

// STENTOR_TEST_KILL_CHECKPOINT=N: SIGKILL while writing the N-th checkpoint of this process.
void test_kill_hook() {
  static int count = 0;
  ++count;
  const char* v = std::getenv("STENTOR_TEST_KILL_CHECKPOINT");
  if (v && *v && std::atoi(v) == count) std::raise(SIGKILL);
}

// Runs `step`; in parallel the ranks then vote (io/RankVote.hpp), and every rank throws the
// lowest failing rank's message: no rank leaves the write (for H5Fclose, a collective)
// while another is still in it. A rank stuck in a collective ends the job (exit 3).
template <class F>
void agreed_step(MPI_Comm comm, F step) {
  std::string err;
  try {
    step();
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (comm != MPI_COMM_NULL) {
    const RankVote v = vote_on_failure(comm, err, kWriteVoteTimeout);
    if (v.failed_rank >= 0) err = v.failure + (v.failed_rank > 0 ? " (on rank " + std::to_string(v.failed_rank) + ")" : "");
  }
  if (!err.empty()) throw std::runtime_error(err);  // every rank: the file is closed together
}

// The scalars and tables into the open file `f` (every rank the same scalars, its rows).
void write_payload(hid_t f, const CheckpointData& d, MPI_Comm comm, hid_t dxpl, const std::string& checksum, const std::string& tmp) {
  write_string_attr(f, "format", kFormat, tmp);
  write_attr(f, "version", H5T_NATIVE_LLONG, &kVersion, tmp);
  write_string_attr(f, "checksum", checksum, tmp);
  {
    H5 g(H5Gcreate2(f, "reals", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group reals", tmp);
    for (const auto& [k, v] : d.reals) write_attr(g.get(), k, H5T_NATIVE_DOUBLE, &v, tmp);
  }
  {
    H5 g(H5Gcreate2(f, "ints", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group ints", tmp);
    for (const auto& [k, v] : d.ints) write_attr(g.get(), k, H5T_NATIVE_LLONG, &v, tmp);
  }
  {
    H5 g(H5Gcreate2(f, "strings", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "group strings", tmp);
    for (const auto& [k, v] : d.strings) write_string_attr(g.get(), k, v, tmp);
  }
  write_tables(f, d, comm, dxpl, tmp);
  test_fail_rank_hook(comm, tmp);
}

// comm: MPI_COMM_NULL (serial) or the communicator of the ranks writing their rows. In
// parallel the rows are written independently (no collective inside a row write that a
// failing rank could leave), and the ranks vote on a failure before the file is closed:
// a rank whose write failed never leaves for H5Fclose while another still writes.
void write_file(const std::string& tmp, const CheckpointData& d, MPI_Comm comm) {
  std::uint64_t sum = row_sum(d), total = sum;
  if (comm != MPI_COMM_NULL) MPI_Allreduce(&sum, &total, 1, MPI_UINT64_T, MPI_SUM, comm);
  const std::string checksum = checksum_text(scalar_sum(d) + total);
  H5 fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate", tmp);
  H5 dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate", tmp);
  if (comm != MPI_COMM_NULL) {
    check(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL), "H5Pset_fapl_mpio", tmp);
    check(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_INDEPENDENT), "H5Pset_dxpl_mpio", tmp);
  }
  if (is_link(tmp)) throw std::runtime_error(tmp + ": " + open_error(ELOOP));
  H5 f(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose, "creating the file", tmp);
  // Each part that may fail on one rank is followed by a vote; H5Fflush (collective) only
  // once every rank's rows are written.
  agreed_step(comm, [&] { write_payload(f.get(), d, comm, dxpl.get(), checksum, tmp); });
  test_kill_hook();
  agreed_step(comm, [&] { check(H5Fflush(f.get(), H5F_SCOPE_GLOBAL), "H5Fflush", tmp); });
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

// An attribute of one value (a scalar or one-element dataspace) of type class `cls`:
// anything else in a hand-edited file would overrun the value it is read into.
void check_attr(hid_t attr, H5T_class_t cls, const std::string& name, const std::string& file) {
  H5 space(H5Aget_space(attr), H5Sclose, "space of " + name, file);
  H5 type(H5Aget_type(attr), H5Tclose, "type of " + name, file);
  const char* expected = cls == H5T_STRING ? "a string" : cls == H5T_FLOAT ? "a floating-point number" : "an integer";
  if (H5Sget_simple_extent_npoints(space.get()) != 1 || H5Tget_class(type.get()) != cls ||
      (cls == H5T_STRING && (H5Tis_variable_str(type.get()) != 0 || H5Tget_size(type.get()) > (1u << 20))))
    throw std::runtime_error(file + ": attribute " + name + " is not " + expected + " (one value" +
                             (cls == H5T_STRING ? ", fixed length, at most 1 MiB)" : ")"));
}

std::string read_string_attr(hid_t loc, const std::string& name, const std::string& file) {
  H5 attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, "attribute " + name, file);
  check_attr(attr.get(), H5T_STRING, name, file);
  H5 type(H5Aget_type(attr.get()), H5Tclose, "type of " + name, file);
  const std::size_t n = H5Tget_size(type.get());
  std::string v(n, '\0');
  check(H5Aread(attr.get(), type.get(), v.data()), "reading " + name, file);
  v.resize(std::strlen(v.c_str()));
  return v;
}

template <class T>
T read_attr(hid_t loc, const std::string& name, hid_t type, const std::string& file) {
  H5 attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, "attribute " + name, file);
  check_attr(attr.get(), std::is_floating_point<T>::value ? H5T_FLOAT : H5T_INTEGER, name, file);
  T v{};
  check(H5Aread(attr.get(), type, &v), "reading " + name, file);
  if constexpr (std::is_floating_point<T>::value)
    if (!std::isfinite(v)) throw std::runtime_error(file + ": attribute " + name + " is not a finite number");
  return v;
}

herr_t collect_link_name(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

// The dimensions of dataset `dset` (named `what`) of type class `cls`: rank 1 or 2, the
// element count within what the file's `file_bytes` can hold.
std::vector<hsize_t> dataset_dims(hid_t dset, H5T_class_t cls, const std::string& what, std::uintmax_t file_bytes,
                                  const std::string& file) {
  H5 space(H5Dget_space(dset), H5Sclose, what + " space", file);
  H5 type(H5Dget_type(dset), H5Tclose, what + " type", file);
  if (H5Tget_class(type.get()) != cls)
    throw std::runtime_error(file + ": " + what + " is not of " + (cls == H5T_FLOAT ? "floating-point" : "integer") + " type");
  const int nd = H5Sget_simple_extent_ndims(space.get());
  if (nd < 1 || nd > 2) throw std::runtime_error(file + ": " + what + " has " + std::to_string(nd) + " dimensions, expected 1 or 2");
  std::vector<hsize_t> dims(static_cast<std::size_t>(nd));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  const hsize_t cols = nd == 2 ? dims[1] : 1;
  if (cols > kMaxColumns || (dims[0] > 0 && cols == 0) || dims[0] > file_bytes / 8 || dims[0] * cols > file_bytes / 8)
    throw std::runtime_error(file + ": " + what + " claims " + std::to_string(dims[0]) + " x " + std::to_string(cols) +
                             " values, more than the file holds");
  return dims;
}

// Table `name`: ids (integers, none negative, none twice) and values (finite), one row each.
CheckpointTable read_table(hid_t tables, const std::string& name, std::uintmax_t file_bytes, const std::string& file) {
  const std::string where = "table /tables/" + name;
  H5 g(H5Gopen2(tables, name.c_str(), H5P_DEFAULT), H5Gclose, where, file);
  H5 ids(H5Dopen2(g.get(), "ids", H5P_DEFAULT), H5Dclose, where + "/ids", file);
  H5 vals(H5Dopen2(g.get(), "values", H5P_DEFAULT), H5Dclose, where + "/values", file);
  const auto id_dims = dataset_dims(ids.get(), H5T_INTEGER, where + "/ids", file_bytes, file);
  const auto v_dims = dataset_dims(vals.get(), H5T_FLOAT, where + "/values", file_bytes, file);
  if (id_dims.size() != 1) throw std::runtime_error(file + ": " + where + "/ids is not a vector");
  const hsize_t n = id_dims[0], cols = v_dims.size() == 2 ? v_dims[1] : 1;
  if (v_dims[0] != n) throw std::runtime_error(file + ": " + where + ": ids and values differ in length");
  CheckpointTable t;
  t.ncols = static_cast<int>(cols);
  t.ids.resize(n);
  t.values.resize(n * cols);
  if (n > 0) {
    check(H5Dread(ids.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.ids.data()), "reading " + where + "/ids", file);
    check(H5Dread(vals.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.values.data()), "reading " + where + "/values", file);
  }
  for (std::size_t i = 0; i < t.values.size(); ++i)
    if (!std::isfinite(t.values[i]))
      throw std::runtime_error(file + ": " + where + "/values holds a non-finite number (row " + std::to_string(i / cols) + ", id " +
                               std::to_string(t.ids[i / cols]) + ")");
  if (!std::is_sorted(t.ids.begin(), t.ids.end())) t.sort_rows();
  for (std::size_t i = 0; i < t.ids.size(); ++i)
    if (t.ids[i] < 0 || (i > 0 && t.ids[i] == t.ids[i - 1]))
      throw std::runtime_error(file + ": " + where + "/ids: id " + std::to_string(t.ids[i]) + (t.ids[i] < 0 ? " is negative" : " appears twice"));
  return t;
}

// The named scalars of group `group` (reals, ints or strings).
void read_scalars(hid_t f, CheckpointData& d, const std::string& path) {
  {
    H5 g(H5Gopen2(f, "reals", H5P_DEFAULT), H5Gclose, "group reals", path);
    for (const auto& k : attr_names(g.get())) d.reals[k] = read_attr<double>(g.get(), k, H5T_NATIVE_DOUBLE, path + ": /reals");
  }
  {
    H5 g(H5Gopen2(f, "ints", H5P_DEFAULT), H5Gclose, "group ints", path);
    for (const auto& k : attr_names(g.get())) d.ints[k] = read_attr<long long>(g.get(), k, H5T_NATIVE_LLONG, path + ": /ints");
  }
  {
    H5 g(H5Gopen2(f, "strings", H5P_DEFAULT), H5Gclose, "group strings", path);
    for (const auto& k : attr_names(g.get())) d.strings[k] = read_string_attr(g.get(), k, path + ": /strings");
  }
}

CheckpointData read_file(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(path, ec);
  H5 f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "not an HDF5 file, or unreadable:", path);
  if (H5Aexists(f.get(), "format") <= 0 || read_string_attr(f.get(), "format", path) != kFormat)
    throw std::runtime_error(path + ": not a Stentor checkpoint (no 'format' attribute \"" + kFormat + "\")");
  const long long version = read_attr<long long>(f.get(), "version", H5T_NATIVE_LLONG, path);
  if (version != kVersion)
    throw std::runtime_error(path + ": checkpoint format version " + std::to_string(version) + ", this build reads version " +
                             std::to_string(kVersion));
  if (H5Aexists(f.get(), "checksum") <= 0) throw std::runtime_error(path + ": no 'checksum' attribute");
  const std::string checksum = read_string_attr(f.get(), "checksum", path);
  CheckpointData d;
  read_scalars(f.get(), d, path);
  H5 tables(H5Gopen2(f.get(), "tables", H5P_DEFAULT), H5Gclose, "group tables", path);
  std::vector<std::string> names;
  hsize_t idx = 0;
  check(H5Literate(tables.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect_link_name, &names), "listing tables", path);
  for (const auto& n : names) d.tables[n] = read_table(tables.get(), n, ec ? ~std::uintmax_t(0) : bytes, path);
  if (checksum_text(scalar_sum(d) + row_sum(d)) != checksum)
    throw std::runtime_error(path + ": the checksum of its data does not match (the file was changed after Stentor wrote it, "
                             "or is damaged)");
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
