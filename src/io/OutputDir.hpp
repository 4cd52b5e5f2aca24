// Results are never half-written over earlier ones: a run writes into a staging
// directory <final_dir>.partial and commit() swaps it in place of <final_dir> at the end.
// Without commit() (the run failed) the staging directory stays as <final_dir>.partial
// for inspection and an earlier <final_dir> is left untouched.
// Use it on one rank only (rank 0); other ranks must wait for it (barrier) before writing.
#pragma once
#include <string>

namespace stentor {

class OutputDir {
 public:
  // Removes a leftover <final_dir>.partial, then creates it (and missing parents).
  // Throws std::runtime_error naming the path.
  explicit OutputDir(const std::string& final_dir);
  // The staging directory to write into.
  const std::string& path() const { return staging_; }
  const std::string& final_path() const { return final_; }
  // Replaces final_dir by the staging dir: final -> final.old, staging -> final, remove
  // .old. Each rename is atomic; if the second fails the old results are put back.
  // Throws on failure or when called twice.
  void commit();
  bool committed() const { return committed_; }

 private:
  std::string final_;
  std::string staging_;
  bool committed_ = false;
};

}  // namespace stentor
