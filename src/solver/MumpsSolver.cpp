#include "solver/MumpsSolver.hpp"

#ifdef STENTOR_HAVE_MUMPS

#include <dmumps_c.h>
#ifdef STENTOR_MUMPS_OMP
#include <omp.h>

#include <Kokkos_Core.hpp>
#endif

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "parallel/RawComm.hpp"
#include "solver/RootGather.hpp"

namespace stentor {

struct MumpsSolver::Impl {
  la::RCP<const la::Comm> comm;
  DMUMPS_STRUC_C id{};
  bool analysed = false;
  std::vector<MUMPS_INT> irn, jcn;  // the owned rows' triplets, 1-based contiguous numbers
  std::vector<double> a;
  std::unique_ptr<RootGather> rows;
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
    int refit = (!rows || !rows->fits(*om)) ? 1 : 0, any_refit = 0;  // a collective decision
    MPI_Allreduce(&refit, &any_refit, 1, MPI_INT, MPI_MAX, raw_mpi_comm(*comm));
    if (any_refit) rows = std::make_unique<RootGather>(*om, comm);
    const std::vector<la::GO> col = rows->column_numbers(A);
    std::vector<MUMPS_INT> ni, nj;
    a.clear();
    for (size_t i = 0; i < om->getNodeNumElements(); ++i) {
      la::CrsMatrix::local_inds_host_view_type cols;
      la::CrsMatrix::values_host_view_type vals;
      A.getLocalRowView(static_cast<la::LO>(i), cols, vals);
      for (size_t k = 0; k < cols.extent(0); ++k) {
        ni.push_back(static_cast<MUMPS_INT>(rows->row(i) + 1));
        nj.push_back(static_cast<MUMPS_INT>(col[static_cast<size_t>(cols(k))] + 1));
        a.push_back(vals(k));
      }
    }
    int changed = (ni != irn || nj != jcn) ? 1 : 0, any = 0;
    MPI_Allreduce(&changed, &any, 1, MPI_INT, MPI_MAX, raw_mpi_comm(*comm));
    irn.swap(ni), jcn.swap(nj);
    id.n = static_cast<MUMPS_INT>(rows->size());
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
  m.rhs = m.rows->to_root(b);  // all rows on rank 0, none elsewhere
  m.id.nrhs = 1;
  m.id.lrhs = m.id.n;
  m.id.rhs = m.rhs.data();
  m.call(3, "solve");
  m.rows->from_root(m.rhs, x);
}

}  // namespace stentor

#endif  // STENTOR_HAVE_MUMPS
