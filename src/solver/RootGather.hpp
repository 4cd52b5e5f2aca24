// The rows of a distributed system renumbered contiguously (each rank its owned rows, in
// order, after the ranks before it: 0..N-1) and moved to rank 0 and back: what the direct
// solvers need (KLU2 factors a matrix gathered on rank 0; MUMPS takes global row and column
// numbers 0..N-1 and a right-hand side on rank 0).
#pragma once
#include <vector>

#include "parallel/LinearAlgebra.hpp"

namespace stentor {

class RootGather {
 public:
  // `rows`: the owned row map (any global numbering).
  RootGather(const la::Map& rows, const la::RCP<const la::Comm>& comm);
  std::size_t size() const { return static_cast<std::size_t>(contiguous_->getGlobalNumElements()); }
  bool fits(const la::Map& rows) const { return rows.getNodeNumElements() == contiguous_->getNodeNumElements(); }
  // The contiguous number of owned row i.
  la::GO row(std::size_t i) const { return contiguous_->getGlobalElement(static_cast<la::LO>(i)); }
  // The contiguous numbers of A's columns, per entry of its column map (collective).
  std::vector<la::GO> column_numbers(const la::CrsMatrix& A) const;
  // b's values on rank 0 in contiguous order (empty elsewhere; collective).
  std::vector<double> to_root(const la::Vector& b) const;
  // x from the values on rank 0 in contiguous order (ignored elsewhere; collective).
  void from_root(const std::vector<double>& on_root, la::Vector& x) const;
  const la::RCP<const la::Map>& contiguous_map() const { return contiguous_; }

 private:
  la::RCP<const la::Map> contiguous_, root_;
  la::RCP<la::Import> to_root_;
};

}  // namespace stentor
