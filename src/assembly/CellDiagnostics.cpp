// Assembler::smallest_det_f: the cells of smallest det F at the last assembled state, for
// the message of a step that fails on inverted cells (a diagnostic pass on the host, run
// only then).
#include <algorithm>
#include <array>
#include <limits>
#include <sstream>

#include "assembly/Assembler.hpp"
#include "fem/Geometry.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "parallel/GatherBest.hpp"

namespace stentor {

namespace {
// One cell's record: its smallest det F over the stiffness quadrature points, global id,
// volume block + 1 and reference centre (x, y, z).
using CellRecord = std::array<double, 6>;
}  // namespace

std::string Assembler::smallest_det_f(int k) const {
  auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dist_.coords());
  auto uh = u_overlap_->getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<CellRecord> mine;
  for (const auto& lb : dist_.blocks()) {
    const std::size_t nc = lb.cell_ids.size();
    if (nc == 0) continue;
    auto conn = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lb.conn);
    const QuadRule q = make_rule(lb.type, stiffness_quadrature_degree(lb.type));
    const int nn = lb.nodes_per_cell;
    for (std::size_t c = 0; c < nc; ++c) {
      double Xe[kMaxCellNodes][3], Ue[kMaxCellNodes][3], N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
      CellRecord rec{std::numeric_limits<double>::infinity(), static_cast<double>(lb.cell_ids[c]),
                     static_cast<double>(lb.volume_block) + 1.0, 0.0, 0.0, 0.0};
      for (int a = 0; a < nn; ++a) {
        const int l = conn(c, a);
        for (int d = 0; d < 3; ++d) {
          Xe[a][d] = X(l, d);
          Ue[a][d] = d < dim_ ? uh(l * dim_ + d, 0) : 0.0;
          rec[3 + static_cast<std::size_t>(d)] += Xe[a][d] / nn;
        }
      }
      for (int g = 0; g < q.n; ++g) {
        shape_functions(lb.type, q.xi[g], N, dN);
        if (!(reference_gradients(dim_, nn, Xe, dN, dNdX) > 0.0)) continue;
        const double R = reference_radius(kin_, nn, N, Xe);
        if (kin_ == Kinematics::Axisymmetric && !(R > 0.0)) continue;
        rec[0] = std::min(rec[0], det(point_deformation_gradient(dim_, kin_, nn, N, R, Ue, dNdX)));
      }
      mine.push_back(rec);
    }
  }
  const auto by_det = [](const CellRecord& a, const CellRecord& b) { return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]); };
  const std::vector<CellRecord> recs = gather_best(*dist_.comm(), std::move(mine), static_cast<std::size_t>(std::max(k, 1)), by_det);
  std::ostringstream os;
  os.precision(3);
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const CellRecord& r = recs[i];
    if (i > 0) os << ", ";
    os << "cell " << static_cast<long long>(r[1]) << " of '" << block_names_[static_cast<std::size_t>(r[2]) - 1] << "'";
    os << " (det F " << r[0] << ", reference centre " << r[3] << ", " << r[4];
    if (dim_ == 3) os << ", " << r[5];
    os << ")";
  }
  return os.str();
}

}  // namespace stentor
