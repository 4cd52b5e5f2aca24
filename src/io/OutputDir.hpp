// A run's result folder, safe for the user's files and for concurrent runs.
//
// A run writes into a staging folder <final>.partial; commit() moves the files into
// <final> only when the run succeeds, so a failed run never touches earlier results (its
// partial results stay in <final>.partial for inspection).
//
// Nothing a run did not write is ever deleted or overwritten:
// - <final> must be new, empty, or a Stentor results folder: one holding the manifest
//   kManifest, which lists the files the run that wrote it created, each with its size and
//   FNV-1a hash (names encoded: bytes other than letters, digits and . _ - + as %XX), the
//   whole closed by a hash of its text. Any other non-empty folder is refused unless
//   `overwrite` (--overwrite) is given.
// - The manifest is data to verify, not an instruction: commit() replaces or removes only
//   the listed files that still have the listed size and hash (checked again just before
//   each removal), moves the new files in and writes a new manifest; every other file in
//   <final> stays as it is: the user's, a listed file changed since, and every file a
//   malformed or foreign manifest lists (reported in notice()). A file of the same name as
//   a new result that is not such a verified entry is never replaced without `overwrite`.
// - <final> (and <final>.partial) must not hold the deck or mesh being read.
// - A leftover <final>.partial is reused only when it holds the lock file (Stentor's own
//   staging folder); any other is refused.
//
// Concurrent runs: the staging folder holds the lock file kLockFile, locked with flock()
// for the whole run and naming the run (pid, host, start time, deck). A second run into
// the same folder is refused with that description; a lock file nobody holds (the run
// died, or failed and kept its partial results) is taken over. The lock file is opened without
// following a symbolic link: a link there (or a staging folder that is a link) is refused,
// never written through. Where the file system
// does not support flock(), a lock whose pid is dead on this host is taken over, its
// files removed; but a staging folder holding a checkpoint (<name>_checkpoint.h5) is
// never emptied without `overwrite`: the run is refused, naming the checkpoint, its time
// and step, --restart <checkpoint> to resume and --overwrite to discard it.
//
// Use it on one rank only (rank 0); other ranks must wait for it (barrier) before writing.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace stentor {

class OutputDir {
 public:
  static constexpr const char* kManifest = "stentor-manifest.txt";
  static constexpr const char* kLockFile = ".stentor.lock";

  struct Options {
    std::vector<std::string> inputs;  // files the run reads (deck, mesh): the folder must not hold them
    std::string prefix;               // every result file's name starts with it: such a file of
                                      // the user's in <final> is refused at once, before the run
    std::string deck;                 // named in the lock and the manifest
    bool overwrite = false;           // write into a non-empty folder that is not Stentor's
  };

  // Checks <final_dir>, takes the lock and prepares an empty staging folder (creating
  // missing parents). Throws std::runtime_error with a message for the user (naming the
  // folder and what to do) when the folder may not be used or another run holds it.
  OutputDir(const std::string& final_dir, const Options& opts);
  OutputDir(const std::string& final_dir) : OutputDir(final_dir, Options{}) {}
  // Whether a running run holds the lock of <final_dir>.partial: its description (pid,
  // host, start, deck, lock file), or "" when none does. Follows no link; writes nothing.
  static std::string running_in(const std::string& final_dir);
  // Releases the lock. Without commit() or discard() the staging folder stays, with the
  // (now free) lock file naming the run that wrote it.
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  // The staging directory to write into.
  const std::string& path() const { return staging_; }
  const std::string& final_path() const { return final_; }
  // What the user should know about the folder (a lock taken over, earlier results to be
  // replaced); empty when nothing.
  const std::string& notice() const { return notice_; }

  // Copies `file` into the staging folder as `name`. Throws WriteError.
  void copy_in(const std::string& file, const std::string& name);
  // Moves the staged files into <final> as described above, then removes the staging
  // folder and the lock. Throws WriteError (the files not moved yet stay staged) on a
  // failed write, std::runtime_error when called twice.
  void commit();
  bool committed() const { return committed_; }
  // Removes the staging folder and the lock (an input error: nothing worth keeping).
  void discard();

 private:
  void check_final(const Options& opts);
  void lock(const Options& opts);
  void keep_checkpoints();
  // Name -> (size, FNV-1a hex) of each file listed.
  using Files = std::map<std::string, std::pair<std::uint64_t, std::string>>;
  void write_manifest(const Files& files) const;
  void release();

  std::string final_;
  std::string staging_;
  std::string deck_;
  std::string notice_;
  bool overwrite_ = false;
  int lock_fd_ = -1;
  bool committed_ = false;
};

}  // namespace stentor
