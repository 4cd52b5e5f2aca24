// Assembler::smallest_det_f: the cells of smallest det F at the last assembled state, for
// the message of a step that fails on inverted cells (a diagnostic pass on the host, run
// only then).
#include <algorithm>
#include <limits>
#include <sstream>

#include <Teuchos_CommHelpers.hpp>

#include "assembly/Assembler.hpp"
#include "fem/Geometry.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"

namespace stentor {

namespace {

// One cell's record: its smallest det F over the stiffness quadrature points, global id,
// volume block + 1 (0: none) and reference centre.
struct CellRecord {
  double det = std::numeric_limits<double>::infinity();
  double gid = -1.0, block = 0.0;
  double centre[3] = {0.0, 0.0, 0.0};
};
constexpr int kRecordSize = 6;

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
      CellRecord rec;
      for (int a = 0; a < nn; ++a) {
        const int l = conn(c, a);
        for (int d = 0; d < 3; ++d) {
          Xe[a][d] = X(l, d);
          Ue[a][d] = d < dim_ ? uh(l * dim_ + d, 0) : 0.0;
          rec.centre[d] += Xe[a][d] / nn;
        }
      }
      for (int g = 0; g < q.n; ++g) {
        shape_functions(lb.type, q.xi[g], N, dN);
        if (!(reference_gradients(dim_, nn, Xe, dN, dNdX) > 0.0)) continue;
        const double R = reference_radius(kin_, nn, N, Xe);
        if (kin_ == Kinematics::Axisymmetric && !(R > 0.0)) continue;
        rec.det = std::min(rec.det, det(point_deformation_gradient(dim_, kin_, nn, N, R, Ue, dNdX)));
      }
      rec.gid = static_cast<double>(lb.cell_ids[c]);
      rec.block = static_cast<double>(lb.volume_block) + 1.0;
      mine.push_back(rec);
    }
  }
  const auto by_det = [](const CellRecord& a, const CellRecord& b) { return a.det < b.det || (a.det == b.det && a.gid < b.gid); };
  const std::size_t kk = static_cast<std::size_t>(std::max(k, 1));
  std::partial_sort(mine.begin(), mine.begin() + static_cast<long>(std::min(kk, mine.size())), mine.end(), by_det);
  mine.resize(std::min(kk, mine.size()));
  // Every rank sends kk records (padded with empty ones) to every rank.
  std::vector<double> send(kk * kRecordSize, 0.0);
  for (std::size_t i = 0; i < kk; ++i) {
    const CellRecord r = i < mine.size() ? mine[i] : CellRecord{};
    const double v[kRecordSize] = {r.det, r.gid, r.block, r.centre[0], r.centre[1], r.centre[2]};
    std::copy(v, v + kRecordSize, send.begin() + static_cast<long>(i * kRecordSize));
  }
  const int ranks = dist_.comm()->getSize();
  std::vector<double> all(send.size() * static_cast<std::size_t>(ranks));
  Teuchos::gatherAll(*dist_.comm(), static_cast<int>(send.size()), send.data(), static_cast<int>(all.size()), all.data());
  std::vector<CellRecord> recs;
  for (std::size_t i = 0; i + kRecordSize <= all.size(); i += kRecordSize) {
    if (!(all[i + 1] >= 0.0)) continue;
    CellRecord r;
    r.det = all[i], r.gid = all[i + 1], r.block = all[i + 2];
    for (int d = 0; d < 3; ++d) r.centre[d] = all[i + 3 + static_cast<std::size_t>(d)];
    recs.push_back(r);
  }
  std::sort(recs.begin(), recs.end(), by_det);
  std::ostringstream os;
  os.precision(3);
  for (std::size_t i = 0; i < std::min(kk, recs.size()); ++i) {
    const CellRecord& r = recs[i];
    if (i > 0) os << ", ";
    os << "cell " << static_cast<long long>(r.gid);
    if (r.block > 0.0) os << " of '" << block_names_[static_cast<std::size_t>(r.block) - 1] << "'";
    os << " (det F " << r.det << ", reference centre " << r.centre[0] << ", " << r.centre[1];
    if (dim_ == 3) os << ", " << r.centre[2];
    os << ")";
  }
  return os.str();
}

}  // namespace stentor
