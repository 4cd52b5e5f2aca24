// Checkpoint files (io/Checkpoint.hpp): round trip, byte image, replacement that keeps the
// previous file, and clear errors for files that are not checkpoints.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

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
