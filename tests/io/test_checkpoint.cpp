// Checkpoint files (io/Checkpoint.hpp): round trip, byte image, replacement that keeps the
// previous file, clear errors for files that are not checkpoints, and hand-edited files
// (changed values, non-finite numbers, malformed objects) refused with the object named.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <vector>

#include "io/Checkpoint.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path d = fs::path(STENTOR_BINARY_DIR) / "test_checkpoint.work" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

CheckpointData sample(double t) {
  CheckpointData d;
  d.reals = {{"time", t}, {"tiny", 1e-300}};
  d.ints = {{"step", 42}, {"big", 1LL << 40}};
  d.strings = {{"deck", "/some/deck.xml"}, {"empty", ""}};
  CheckpointTable u;
  u.ncols = 2;
  u.ids = {7, 3, 5};  // unsorted, as gathered from ranks
  u.values = {7.0, 7.5, 3.0, 3.5, 5.0, 0.1 + 0.2};
  u.sort_rows();
  d.tables["u"] = u;
  d.tables["empty"] = CheckpointTable{4, {}, {}};
  return d;
}

void expect_equal(const CheckpointData& a, const CheckpointData& b) {
  EXPECT_EQ(a.reals, b.reals);
  EXPECT_EQ(a.ints, b.ints);
  EXPECT_EQ(a.strings, b.strings);
  ASSERT_EQ(a.tables.size(), b.tables.size());
  for (const auto& [name, t] : a.tables) {
    const CheckpointTable& o = b.table(name);
    EXPECT_EQ(t.ncols, o.ncols) << name;
    EXPECT_EQ(t.ids, o.ids) << name;
    EXPECT_EQ(t.values, o.values) << name;  // bit for bit
  }
}

}  // namespace

TEST(Checkpoint, RowsSortedAndFoundById) {
  const CheckpointData d = sample(1.0);
  const CheckpointTable& u = d.table("u");
  EXPECT_EQ(u.ids, (std::vector<long long>{3, 5, 7}));
  ASSERT_NE(u.find(5), nullptr);
  EXPECT_EQ(u.find(5)[1], 0.1 + 0.2);
  EXPECT_EQ(u.find(4), nullptr);
  EXPECT_THROW(d.table("v"), std::runtime_error);
  EXPECT_THROW(d.real("nope"), std::runtime_error);
}

TEST(Checkpoint, FileRoundTripIsExact) {
  const fs::path f = scratch("roundtrip") / "run_checkpoint.h5";
  const CheckpointData d = sample(0.125);
  write_checkpoint_file(f.string(), d);
  expect_equal(d, read_checkpoint_file(f.string()));
  EXPECT_FALSE(fs::exists(f.string() + ".tmp"));
}

TEST(Checkpoint, ByteImageRoundTripIsExact) { expect_equal(sample(2.0), unpack_checkpoint(pack_checkpoint(sample(2.0)))); }

TEST(Checkpoint, ReplacingKeepsThePreviousOne) {
  const fs::path f = scratch("replace") / "run_checkpoint.h5";
  write_checkpoint_file(f.string(), sample(1.0));
  EXPECT_FALSE(fs::exists(previous_checkpoint_path(f.string())));
  write_checkpoint_file(f.string(), sample(2.0));
  write_checkpoint_file(f.string(), sample(3.0));
  EXPECT_EQ(previous_checkpoint_path(f.string()), (f.parent_path() / "run_checkpoint.prev.h5").string());
  EXPECT_EQ(read_checkpoint_file(f.string()).real("time"), 3.0);
  EXPECT_EQ(read_checkpoint_file(previous_checkpoint_path(f.string())).real("time"), 2.0);
}

TEST(Checkpoint, FilesThatAreNotCheckpointsAreNamedInTheError) {
  const fs::path d = scratch("bad");
  auto message = [](const std::string& path) {
    try {
      read_checkpoint_file(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string missing = (d / "missing.h5").string();
  EXPECT_EQ(message(missing), missing + ": no such checkpoint file");
  const std::string text = (d / "text.h5").string();
  std::ofstream(text) << "not HDF5\n";
  EXPECT_NE(message(text).find(text + ": not an HDF5 file"), std::string::npos) << message(text);
  // Half a file, as a crash in the middle of writing leaves it.
  const std::string good = (d / "good.h5").string(), cut = (d / "cut.h5").string();
  write_checkpoint_file(good, sample(1.0));
  fs::copy_file(good, cut);
  fs::resize_file(cut, fs::file_size(good) / 2);
  EXPECT_EQ(message(cut).rfind(cut + ":", 0), 0u) << message(cut);
}

namespace {

std::string read_error(const std::string& path) {
  try {
    read_checkpoint_file(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

// Opens `path` read-write and runs `edit` on it (a hand edit with any HDF5 tool).
template <class F>
void edit_file(const std::string& path, F edit) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  edit(f);
  H5Fclose(f);
}

}  // namespace

// Any changed value is detected by the payload checksum, though the file is valid HDF5.
TEST(Checkpoint, ChangedValueFailsTheChecksum) {
  const std::string p = (scratch("checksum") / "c.h5").string();
  write_checkpoint_file(p, sample(1.0));
  edit_file(p, [](hid_t f) {
    const hid_t d = H5Dopen2(f, "/tables/u/values", H5P_DEFAULT);
    std::vector<double> v(6);
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    v[1] = std::nextafter(v[1], 1e300);  // one ulp
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(d);
  });
  EXPECT_NE(read_error(p).find("the checksum of its data does not match"), std::string::npos) << read_error(p);
}

// Non-finite values are refused on reading (naming the table), whatever the checksum says.
TEST(Checkpoint, NonFiniteValuesAreRefused) {
  const std::string p = (scratch("nonfinite") / "c.h5").string();
  CheckpointData d = sample(1.0);
  d.tables["u"].values[3] = std::nan("");
  write_checkpoint_file(p, d);
  EXPECT_NE(read_error(p).find("/tables/u/values holds a non-finite number (row 1, id 5)"), std::string::npos) << read_error(p);
  d = sample(std::numeric_limits<double>::infinity());
  write_checkpoint_file(p, d);
  EXPECT_NE(read_error(p).find("attribute time is not a finite number"), std::string::npos) << read_error(p);
}

// A scalar stored as an array (which would overrun the one value it is read into), a
// string where a number belongs, and an id twice: each named, none read.
TEST(Checkpoint, MalformedObjectsAreNamed) {
  const std::string p = (scratch("malformed") / "c.h5").string();
  write_checkpoint_file(p, sample(1.0));
  edit_file(p, [](hid_t f) {
    const hid_t g = H5Gopen2(f, "reals", H5P_DEFAULT);
    H5Adelete(g, "time");
    const hsize_t n = 1000;
    const hid_t s = H5Screate_simple(1, &n, nullptr);
    const hid_t a = H5Acreate2(g, "time", H5T_NATIVE_DOUBLE, s, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<double> zeros(n, 0.0);
    H5Awrite(a, H5T_NATIVE_DOUBLE, zeros.data());
    H5Aclose(a), H5Sclose(s), H5Gclose(g);
  });
  EXPECT_NE(read_error(p).find("attribute time is not a floating-point number (one value)"), std::string::npos) << read_error(p);
  write_checkpoint_file(p, sample(1.0));
  edit_file(p, [](hid_t f) {
    const hid_t d = H5Dopen2(f, "/tables/u/ids", H5P_DEFAULT);
    const long long ids[3] = {3, 3, 7};
    H5Dwrite(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, ids);
    H5Dclose(d);
  });
  EXPECT_NE(read_error(p).find("/tables/u/ids: id 3 appears twice"), std::string::npos) << read_error(p);
}
