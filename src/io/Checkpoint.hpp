// Checkpoint files: the state a run needs to continue, as plain named data in HDF5.
//
// What the data mean is the run's business (src/run/Restart.cpp); this layer only stores
// named scalars and named tables whose rows are keyed by a global id (node id, cell id),
// so that a file written on R ranks can be read back on any other number of ranks.
//
// <file>.h5
//   attributes of /      format = "stentor checkpoint", version = 2, checksum (below)
//   /reals, /ints, /strings   one attribute per named scalar (double, int64, string)
//   /tables/<name>/ids        n int64, sorted ascending
//   /tables/<name>/values     n x ncols doubles (row i belongs to ids[i])
//
// Writing is atomic: the file is written as <file>.tmp, flushed to disk, and renamed over
// <file>; the file it replaces is kept as <stem>.prev.h5 (hard link + rename), so at every
// instant <file> is either absent (before the first checkpoint) or complete.
// Writing: serial, or on several ranks each writing its rows (MPI-IO, independent
// transfers); the ranks vote on a failure before the file is closed, so that a write
// failing on one rank (a full disk on its node) fails on every rank instead of hanging
// the job (io/RankVote.hpp). Reading: serial (the caller sends the rows on).
//
// A checkpoint is untrusted input (any HDF5 tool edits it). Reading checks its form: each
// scalar one value of its type (no arrays, no variable-length strings), reals finite;
// each table's ids integers, values floating-point, 1 or 2 dimensions, no more values
// than the file can hold, all finite, ids not negative and none twice; and the checksum:
// FNV-1a of the scalars plus the sum (mod 2^64) of one FNV-1a per table row, so that a
// changed byte is found. What the values mean is checked by run/CheckpointCheck.hpp.
#pragma once
#include <mpi.h>

#include <map>
#include <string>
#include <vector>

namespace stentor {

struct CheckpointTable {
  int ncols = 0;
  std::vector<long long> ids;   // sorted ascending (sort_rows() makes them so)
  std::vector<double> values;   // ids.size() x ncols, row-major
  // Sorts the rows by id (stable for equal ids).
  void sort_rows();
  // Row of `id`, or nullptr when absent (binary search).
  const double* find(long long id) const;
};

struct CheckpointData {
  std::map<std::string, double> reals;
  std::map<std::string, long long> ints;
  std::map<std::string, std::string> strings;
  std::map<std::string, CheckpointTable> tables;

  // Accessors that throw std::runtime_error("missing '<name>'") when absent.
  double real(const std::string& name) const;
  long long integer(const std::string& name) const;
  const std::string& string(const std::string& name) const;
  const CheckpointTable& table(const std::string& name) const;
};

// Writes `data` to `path` atomically (see above). Throws std::runtime_error naming the file.
// Test hooks: with STENTOR_TEST_KILL_CHECKPOINT=N in the environment, the process kills
// itself with SIGKILL in the middle of writing its N-th checkpoint (after the tables, before
// the temporary file is closed and renamed), as a crash or `kill -9` would; with
// STENTOR_TEST_FAIL_CHECKPOINT_RANK=R rank R's writes fail (ENOSPC) after its rows.
void write_checkpoint_file(const std::string& path, const CheckpointData& data);
// The same, collective over `comm`: every rank passes the same scalars and the same tables
// (names, columns), each table holding this rank's rows, which follow those of the lower
// ranks in the file (so the caller hands rank r the r-th range of ids, each sorted). The
// file is written with MPI-IO, each rank its rows; rank 0 renames it into place. Throws
// std::runtime_error on every rank, with the first failing rank's message, when any rank
// failed. One rank: the serial write.
void write_checkpoint_file(const std::string& path, const CheckpointData& mine, MPI_Comm comm);
// Reads a checkpoint file. Throws std::runtime_error (starting with `path`, naming the
// attribute or dataset) when the file is missing, unreadable, not a Stentor checkpoint, or
// fails the checks above.
CheckpointData read_checkpoint_file(const std::string& path);
// Where write_checkpoint_file keeps the checkpoint it replaced.
std::string previous_checkpoint_path(const std::string& path);

// Byte image of the data (for broadcasting it to other ranks) and back.
std::vector<char> pack_checkpoint(const CheckpointData& data);
CheckpointData unpack_checkpoint(const std::vector<char>& bytes);

}  // namespace stentor
