#include "solver/MumpsSolver.hpp"

#ifdef STENTOR_HAVE_MUMPS

#include <dmumps_c.h>
#ifdef STENTOR_MUMPS_OMP
#include <omp.h>

#include <Kokkos_Core.hpp>
#endif

#include <stdexcept>
#include <string>
#include <vector>

#include "parallel/RawComm.hpp"

namespace stentor {

struct MumpsSolver::Impl {
  la::RCP<const la::Comm> comm;
  DMUMPS_STRUC_C id{};
  bool analysed = false;
  std::vector<MUMPS_INT> irn, jcn;  // the owned rows' triplets, 1-based contiguous ids
  std::vector<double> a;
  la::RCP<const la::Map> cmap, map0;  // contiguous ids (each rank its rows, in order); all rows on rank 0
  la::RCP<la::Import> to0;
  std::vector<double> rhs;  // rank 0: the gathered right-hand side, then the solution

  void call(int job, const char* what) {
    id.job = job;
#ifdef STENTOR_MUMPS_OMP
    // The dense kernels' threads (an OpenMP BLAS such as Debian's OpenBLAS) as many as
    // this rank's Kokkos threads: one in the Serial build. Left to the BLAS's default (all
    // cores, on every rank) they oversubscribe the machine: 5x slower factorizations
    // measured with 2 ranks on 2 cores.
    const int before = omp_get_max_threads();
    omp_set_num_threads(Kokkos::DefaultHostExecutionSpace().concurrency());
    dmumps_c(&id);
    omp_set_num_threads(before);
#else
    dmumps_c(&id);
#endif
    if (id.infog[0] >= 0) return;
    const int e = id.infog[0];
    std::string why = e == -10 ? " (the matrix is numerically singular)"
                    : e == -9 || e == -8 || e == -14 || e == -15 ? " (its workspace is too small)"
                    : e == -13 ? " (out of memory)"
                    : "";
    throw std::runtime_error(std::string("MUMPS ") + what + " failed: INFOG(1) = " + std::to_string(e) +
                             ", INFOG(2) = " + std::to_string(id.infog[1]) + why);
  }

  // The rows of A as triplets in the contiguous numbering; returns whether the indices
  // differ from the last call's on any rank (collective).
  bool triplets(const la::CrsMatrix& A) {
    const auto om = A.getRowMap();
    const size_t nrows = om->getNodeNumElements();
    if (cmap.is_null() || cmap->getNodeNumElements() != nrows) {
      const auto inv = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
      cmap = Teuchos::rcp(new la::Map(inv, nrows, 0, comm));
      const auto n = static_cast<size_t>(cmap->getGlobalNumElements());
      map0 = Teuchos::rcp(new la::Map(n, comm->getRank() == 0 ? n : 0, 0, comm));
      to0 = Teuchos::rcp(new la::Import(cmap, map0));
    }
    la::Vector ids(om), ids_col(A.getColMap());
    {
      auto h = ids.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (size_t i = 0; i < nrows; ++i) h(i, 0) = static_cast<double>(cmap->getGlobalElement(static_cast<la::LO>(i)));
    }
    ids_col.doImport(ids, la::Import(om, A.getColMap()), Tpetra::INSERT);
    std::vector<MUMPS_INT> ni, nj;
    a.clear();
    auto ch = ids_col.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < nrows; ++i) {
      la::CrsMatrix::local_inds_host_view_type cols;
      la::CrsMatrix::values_host_view_type vals;
      A.getLocalRowView(static_cast<la::LO>(i), cols, vals);
      for (size_t k = 0; k < cols.extent(0); ++k) {
        ni.push_back(static_cast<MUMPS_INT>(cmap->getGlobalElement(static_cast<la::LO>(i)) + 1));
        nj.push_back(static_cast<MUMPS_INT>(ch(cols(k), 0) + 1.0));
        a.push_back(vals(k));
      }
    }
    int changed = (ni != irn || nj != jcn) ? 1 : 0, any = 0;
    MPI_Allreduce(&changed, &any, 1, MPI_INT, MPI_MAX, raw_mpi_comm(*comm));
    irn.swap(ni), jcn.swap(nj);
    id.n = static_cast<MUMPS_INT>(cmap->getGlobalNumElements());
    id.nnz_loc = static_cast<MUMPS_INT8>(a.size());
    id.irn_loc = irn.data();
    id.jcn_loc = jcn.data();
    id.a_loc = a.data();
    return any != 0;
  }
};

MumpsSolver::MumpsSolver(const la::RCP<const la::Comm>& comm) : impl_(new Impl) {
  Impl& m = *impl_;
  m.comm = comm;
  m.id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(raw_mpi_comm(*comm)));
  m.id.par = 1;  // rank 0 works too
  m.id.sym = 0;  // unsymmetric (contact rows)
  m.call(-1, "initialisation");
  // Quiet: no messages on any stream (errors come back through INFOG).
  m.id.icntl[0] = -1, m.id.icntl[1] = -1, m.id.icntl[2] = -1, m.id.icntl[3] = 0;
  m.id.icntl[17] = 3;   // ICNTL(18): the matrix distributed, each rank its triplets
  m.id.icntl[13] = 30;  // ICNTL(14): 30 % more workspace than the analysis estimates (pivoting)
}

MumpsSolver::~MumpsSolver() {
  impl_->id.job = -2;  // collective, like every MUMPS call
  dmumps_c(&impl_->id);
}

void MumpsSolver::factor(const la::CrsMatrix& A) {
  Impl& m = *impl_;
  const bool changed = m.triplets(A);
  if (changed || !m.analysed) {
    m.analysed = false;
    m.call(1, "analysis");
    m.analysed = true;
  }
  try {
    m.call(2, "factorization");
  } catch (const std::runtime_error&) {
    const int e = m.id.infog[0];
    if (e != -9 && e != -8 && e != -14 && e != -15) throw;
    m.id.icntl[13] *= 4;  // once more with four times the relaxation
    m.call(2, "factorization");
  }
}

void MumpsSolver::solve(const la::Vector& b, la::Vector& x) {
  Impl& m = *impl_;
  la::Vector bc(m.cmap), b0(m.map0), x0(m.map0), xc(m.cmap);
  {
    auto bh = b.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto ch = bc.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < b.getLocalLength(); ++i) ch(i, 0) = bh(i, 0);
  }
  b0.doImport(bc, *m.to0, Tpetra::INSERT);
  const size_t n = m.map0->getNodeNumElements();  // all rows on rank 0, none elsewhere
  m.rhs.resize(n);
  {
    auto h = b0.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < n; ++i) m.rhs[i] = h(i, 0);
  }
  m.id.nrhs = 1;
  m.id.lrhs = m.id.n;
  m.id.rhs = m.rhs.data();
  m.call(3, "solve");
  {
    auto h = x0.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < n; ++i) h(i, 0) = m.rhs[i];
  }
  xc.doExport(x0, *m.to0, Tpetra::INSERT);
  auto xh = x.getLocalViewHost(Tpetra::Access::OverwriteAll);
  auto ch = xc.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < x.getLocalLength(); ++i) xh(i, 0) = ch(i, 0);
}

}  // namespace stentor

#endif  // STENTOR_HAVE_MUMPS
