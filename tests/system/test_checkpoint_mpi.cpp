// The parallel checkpoint writer (io/Checkpoint.hpp): every rank writes its rows of each
// table with MPI-IO; the file reads back as the serial writer's. Runs on any number of
// ranks (mpi.checkpoint.np2 / np3 in tests/cli/CMakeLists.txt); a plain test on one.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <string>

#include "io/Checkpoint.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

int rank_of() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int size_of() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// A folder every rank sees (rank 0's name).
std::string shared_dir(const std::string& name) {
  std::string dir = rank_of() == 0 ? (fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))).string() : "";
  unsigned long long n = dir.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  dir.resize(n);
  MPI_Bcast(dir.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  if (rank_of() == 0) fs::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

// The whole data: scalars, a table of 3 columns over ids 0, 2, 4, ... (2n rows) and an
// empty one.
CheckpointData whole_data(int n) {
  CheckpointData d;
  d.reals["time"] = 0.25;
  d.ints["step"] = 7;
  d.strings["deck"] = "cube.xml";
  CheckpointTable& t = d.tables["u"];
  t.ncols = 3;
  for (int i = 0; i < 2 * n; ++i) {
    t.ids.push_back(2LL * i);
    for (int c = 0; c < 3; ++c) t.values.push_back(i + 0.1 * c);
  }
  d.tables["contact_none"].ncols = 4;
  return d;
}

// This rank's share: rows [r*m/p, (r+1)*m/p) of every table (uneven, and empty on some
// ranks when there are few rows).
CheckpointData share(const CheckpointData& d) {
  CheckpointData s = d;
  const auto r = static_cast<std::size_t>(rank_of()), p = static_cast<std::size_t>(size_of());
  for (auto& [name, t] : s.tables) {
    const CheckpointTable& w = d.tables.at(name);
    const std::size_t m = w.ids.size(), lo = r * m / p, hi = (r + 1) * m / p, k = static_cast<std::size_t>(w.ncols);
    t.ids.assign(w.ids.begin() + static_cast<std::ptrdiff_t>(lo), w.ids.begin() + static_cast<std::ptrdiff_t>(hi));
    t.values.assign(w.values.begin() + static_cast<std::ptrdiff_t>(lo * k), w.values.begin() + static_cast<std::ptrdiff_t>(hi * k));
  }
  return s;
}

}  // namespace

TEST(CheckpointMpi, EveryRanksRowsReadBackAsTheSerialFile) {
  const std::string dir = shared_dir("ckpt_mpi");
  const CheckpointData whole = whole_data(5);
  const std::string path = dir + "/run_checkpoint.h5";
  write_checkpoint_file(path, share(whole), MPI_COMM_WORLD);
  write_checkpoint_file(path, share(whole), MPI_COMM_WORLD);  // the second keeps the first as .prev
  if (rank_of() == 0) {
    for (const std::string& f : {path, previous_checkpoint_path(path)}) {
      const CheckpointData back = read_checkpoint_file(f);
      EXPECT_EQ(back.reals, whole.reals);
      EXPECT_EQ(back.ints, whole.ints);
      EXPECT_EQ(back.strings, whole.strings);
      ASSERT_EQ(back.tables.size(), 2u);
      EXPECT_EQ(back.tables.at("u").ncols, 3);
      EXPECT_EQ(back.tables.at("u").ids, whole.tables.at("u").ids);
      EXPECT_EQ(back.tables.at("u").values, whole.tables.at("u").values);
      EXPECT_TRUE(back.tables.at("contact_none").ids.empty());
    }
    EXPECT_FALSE(fs::exists(path + ".tmp"));
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank_of() == 0) fs::remove_all(dir);
}

// A file that cannot be created (its folder is missing): every rank throws the same
// message, and nothing is left behind.
TEST(CheckpointMpi, AFailedWriteThrowsOnEveryRank) {
  const std::string dir = shared_dir("ckpt_mpi_fail");
  const std::string path = dir + "/missing/run_checkpoint.h5";
  std::string what;
  try {
    write_checkpoint_file(path, share(whole_data(3)), MPI_COMM_WORLD);
  } catch (const std::runtime_error& e) {
    what = e.what();
  }
  EXPECT_EQ(what.rfind(path + ".tmp: creating the file failed", 0), 0u) << what;
  int same = 1, all = 0;
  std::string first = what;
  unsigned long long n = first.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  first.resize(n);
  MPI_Bcast(first.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  same = first == what ? 1 : 0;
  MPI_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  EXPECT_EQ(all, 1);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank_of() == 0) fs::remove_all(dir);
}
