#include "solver/LinearSolver.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <exception>

#include <BelosLinearProblem.hpp>
#include <BelosPseudoBlockGmresSolMgr.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Ifpack2_Factory.hpp>
#include <sstream>
#include <cstdlib>
#include <iostream>

#include "parallel/Agreement.hpp"
#include "solver/MueLuPreconditioner.hpp"
#include "solver/MumpsSolver.hpp"
#include "solver/RootGather.hpp"
#include "solver/ReusePolicy.hpp"
#include "solver/SolverParams.hpp"
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#ifdef STENTOR_HAVE_AMESOS2
#include <Amesos2.hpp>
#endif

namespace stentor {

namespace {

Teuchos::RCP<Teuchos::ParameterList> parse_xml(const std::string& xml) {
  if (xml.empty()) return Teuchos::rcp(new Teuchos::ParameterList());
  return Teuchos::getParametersFromXmlString(xml);
}

}  // namespace

struct LinearSolver::Impl {
  LinearSolverConfig cfg;
  la::RCP<const la::Comm> comm;
  la::RCP<la::CrsMatrix> A;
  la::RCP<la::CrsMatrix> A_last;  // the matrix of the last setup() (kept through a fallback)
  la::RCP<Ifpack2::Preconditioner<la::SC, la::LO, la::GO, la::Node>> prec;  // schwarz
  la::RCP<la::Operator> mg;  // muelu (a MueLu::TpetraOperator)
  bool prec_initialized = false;
  bool auto_chosen = false;  // preconditioner = auto, resolved for this build
  bool use_mumps = false;    // the direct method's solver: MUMPS (else KLU2)
  bool direct_available = false;  // this build has the direct solver the deck asks for
  std::unique_ptr<MumpsSolver> mumps;
#ifdef STENTOR_HAVE_AMESOS2
  la::RCP<Amesos2::Solver<la::CrsMatrix, la::MV>> direct;
  la::RCP<la::CrsMatrix> Ac;  // A gathered on rank 0, on a one-process communicator (more than one rank)
  bool gathered = false;

  std::unique_ptr<RootGather> rows;  // the gathered path's numbering

  // A gathered on rank 0 as a matrix of a one-process communicator, rows and columns in
  // the contiguous numbering (null on the other ranks). Amesos2's KLU2 (Trilinos 13.2)
  // solved our distributed systems wrongly (|Ax - b| ~ |b| on 2 ranks, with contiguous or
  // non-contiguous maps alike), and its multi-process input path even with every row on
  // rank 0.
  la::RCP<la::CrsMatrix> gathered_copy(const la::CrsMatrix& A) {
    if (!rows) rows = std::make_unique<RootGather>(*A.getRowMap(), comm);
    const std::vector<la::GO> col = rows->column_numbers(A);
    const auto cmap = rows->contiguous_map();
    auto Ac = Teuchos::rcp(new la::CrsMatrix(cmap, A.getNodeMaxNumRowEntries()));
    std::vector<la::GO> gcols;
    std::vector<la::SC> gvals;
    for (size_t i = 0; i < cmap->getNodeNumElements(); ++i) {
      la::CrsMatrix::local_inds_host_view_type cols;
      la::CrsMatrix::values_host_view_type vals;
      A.getLocalRowView(static_cast<la::LO>(i), cols, vals);
      gcols.resize(cols.extent(0));
      gvals.resize(cols.extent(0));
      for (size_t k = 0; k < cols.extent(0); ++k) {
        gcols[k] = col[static_cast<size_t>(cols(k))];
        gvals[k] = vals(k);
      }
      Ac->insertGlobalValues(rows->row(i), Teuchos::ArrayView<const la::GO>(gcols), Teuchos::ArrayView<const la::SC>(gvals));
    }
    Ac->fillComplete(cmap, cmap);
    const size_t n = rows->size();
    auto map0 = Teuchos::rcp(new la::Map(n, comm->getRank() == 0 ? n : 0, 0, comm));
    auto A0 = Teuchos::rcp(new la::CrsMatrix(map0, 0));
    A0->doImport(*Ac, la::Import(cmap, map0), Tpetra::INSERT);
    A0->fillComplete(map0, map0);
    if (comm->getRank() != 0) return Teuchos::null;
    auto self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
    auto smap = Teuchos::rcp(new la::Map(n, 0, self));
    auto As = Teuchos::rcp(new la::CrsMatrix(smap, A0->getNodeMaxNumRowEntries()));
    const auto cm = A0->getColMap();
    for (size_t i = 0; i < n; ++i) {
      la::CrsMatrix::local_inds_host_view_type cols;
      la::CrsMatrix::values_host_view_type vals;
      A0->getLocalRowView(static_cast<la::LO>(i), cols, vals);
      gcols.resize(cols.extent(0));
      gvals.resize(cols.extent(0));
      for (size_t k = 0; k < cols.extent(0); ++k) {
        gcols[k] = cm->getGlobalElement(cols(k));
        gvals[k] = vals(k);
      }
      As->insertGlobalValues(static_cast<la::GO>(i), Teuchos::ArrayView<const la::GO>(gcols), Teuchos::ArrayView<const la::SC>(gvals));
    }
    As->fillComplete(smap, smap);
    return As;
  }
#endif
  Teuchos::RCP<Teuchos::ParameterList> belos_params;
  LinearSolver::Times times;
  // Preconditioner reuse (Linear Solver->preconditioner reuse, ->preconditioner rebuild
  // cost): when a kept preconditioner is rebuilt (solver/ReusePolicy.hpp).
  ReusePolicy reuse;
  bool fresh = false;  // the last setup built the preconditioner (not reused)
  bool keep_preconditioner() {
    const bool built = !prec.is_null() || !mg.is_null();
    return built && reuse.keep();
  }
  int dim = 0;
  std::vector<double> coords;  // owned nodes, 3 each (for multigrid null spaces)

  static Teuchos::RCP<Teuchos::ParameterList> parse(const std::string& xml) { return parse_xml(xml); }
};

Teuchos::RCP<Teuchos::ParameterList> belos_parameters(const LinearSolverConfig& cfg) {
  auto p = Teuchos::rcp(new Teuchos::ParameterList("Belos"));
  p->set("Convergence Tolerance", cfg.tolerance);
  p->set("Maximum Iterations", cfg.max_iterations);
  p->set("Num Blocks", cfg.restart);
  p->set("Maximum Restarts", std::max(1, cfg.max_iterations / std::max(1, cfg.restart)));
  p->set("Verbosity", Belos::Errors);
  p->setParameters(*parse_xml(cfg.belos_xml));  // user pass-through wins
  return p;
}

Teuchos::ParameterList schwarz_parameters(const LinearSolverConfig& cfg) {
  Teuchos::ParameterList pl;
  pl.set("schwarz: overlap level", cfg.overlap);
  pl.set("inner preconditioner name", cfg.subdomain_solver == "KLU2" ? std::string("AMESOS2") : cfg.subdomain_solver);
  Teuchos::ParameterList& inner = pl.sublist("inner preconditioner parameters");
  if (cfg.subdomain_solver == "RILUK") inner.set("fact: iluk level-of-fill", cfg.fill_level);
  if (cfg.subdomain_solver == "ILUT") inner.set("fact: ilut level-of-fill", static_cast<double>(std::max(1, cfg.fill_level)));
  if (cfg.subdomain_solver == "KLU2") {
    // Ifpack2's Amesos2 wrapper takes the solver's name here and its options from a
    // sublist that must be called "Amesos2" (without it: "The ParameterList passed to
    // Amesos2 must be called Amesos2", exit 1, before this fix).
    inner.set("Amesos2 solver name", std::string("KLU2"));
    inner.sublist("Amesos2");
  }
  pl.setParameters(*parse_xml(cfg.ifpack2_xml));
  return pl;
}

LinearSolver::LinearSolver(const LinearSolverConfig& cfg, const la::RCP<const la::Comm>& comm) : impl_(new Impl) {
  impl_->cfg = cfg;
  impl_->comm = comm;
  impl_->reuse.max_age = cfg.preconditioner_reuse;
  impl_->reuse.build_cost = cfg.preconditioner_rebuild_cost;
  rebuild_on_change_ = cfg.preconditioner_rebuild_on_change;
  if (cfg.preconditioner == "auto") {
    // The default: multigrid where this Trilinos has MueLu. Its GMRES iteration counts stay
    // flat under mesh refinement and weak scaling, one-level Schwarz's grow
    // (docs/performance.md, "Preconditioners under weak scaling").
#ifdef STENTOR_HAVE_MUELU
    impl_->cfg.preconditioner = "muelu";
#else
    impl_->cfg.preconditioner = "schwarz";
#endif
    impl_->auto_chosen = true;
  }
  impl_->belos_params = belos_parameters(cfg);
  // The direct solver: KLU2 unless MUMPS is asked for (`auto` is KLU2: MUMPS' results on
  // several ranks vary at round-off from run to run, docs/solvers.md).
#ifdef STENTOR_HAVE_MUMPS
  impl_->use_mumps = cfg.direct_solver == "mumps";
  impl_->direct_available = impl_->use_mumps;
#else
  if (cfg.direct_solver == "mumps")
    throw InputError("'Linear Solver->direct solver' = mumps needs MUMPS (Debian's libmumps-dev), which this build lacks; use klu2");
#endif
#ifdef STENTOR_HAVE_AMESOS2
  impl_->direct_available = true;
#else
  if (cfg.direct_solver == "klu2")
    throw InputError("'Linear Solver->direct solver' = klu2 needs Trilinos with Amesos2, which this build lacks");
  if (!impl_->use_mumps && cfg.method == "direct")
    throw InputError("Linear Solver->method: 'direct' needs Trilinos with Amesos2 or MUMPS, which this build lacks; use 'gmres'");
#endif
}

LinearSolver::~LinearSolver() = default;

void LinearSolver::set_node_coordinates(int dim, const std::vector<double>& owned_xyz) {
  impl_->dim = dim;
  impl_->coords = owned_xyz;
}

namespace {
// Adds the scope's wall time to `acc` and counts one call.
struct Clock {
  double& acc;
  long& calls;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  ~Clock() {
    acc += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++calls;
  }
};
}  // namespace

const LinearSolver::Times& LinearSolver::times() const { return impl_->times; }

void LinearSolver::setup(const la::RCP<la::CrsMatrix>& A) {
  Clock clock{impl_->times.setup, impl_->times.setups};
  setup_or_fall_back(A);
}

// setup_once, stepping down the fallback chain while it fails on any rank.
void LinearSolver::setup_or_fall_back(const la::RCP<la::CrsMatrix>& A) {
  for (;;) {
    std::string why;
    try {
      setup_once(A);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      why = "set-up failed (" + teuchos_short_message(e.what()) + ")";
    }
    const Agreement vote = agree(why);
    if (!vote.failed()) return;
    if (!fall_back(vote.failure)) throw LinearSolverFailure(vote.failure);
  }
}

// Every rank's failure of this call ("" if none) put to a vote (parallel/Agreement.hpp):
// all ranks get the first failing rank's message (named when that is not rank 0).
Agreement LinearSolver::agree(const std::string& why) const {
  Agreement vote = agree_on_failure(*impl_->comm, why);
  if (vote.failed_rank > 0) vote.failure = "on rank " + std::to_string(vote.failed_rank) + ": " + vote.failure;
  return vote;
}

// One step down muelu -> schwarz (RILUK) -> direct; false where none is left. The next
// setup_once() builds the new configuration from scratch.
bool LinearSolver::fall_back(const std::string& why) {
  Impl& m = *impl_;
  const std::string from = description();
  if (m.cfg.method == "direct") return false;
  if (m.cfg.preconditioner == "muelu") {
    m.cfg.preconditioner = "schwarz";
    m.cfg.subdomain_solver = "RILUK";
  } else {
    if (!m.direct_available) return false;
    m.cfg.method = "direct";
  }
  m.auto_chosen = false;
  m.mg = Teuchos::null;
  m.prec = Teuchos::null;
  m.A = Teuchos::null;  // not "the same matrix": the new preconditioner starts afresh
#ifdef STENTOR_HAVE_AMESOS2
  m.direct = Teuchos::null;
#endif
  m.reuse.built();
  ++m.times.fallbacks;
  if (m.comm->getRank() == 0)
    std::cout << "warning: linear solver " << from << ": " << why << "; using " << description() << " from here on\n"
              << std::flush;
  return true;
}

void LinearSolver::setup_once(const la::RCP<la::CrsMatrix>& A) {
  Impl& m = *impl_;
  const bool same = (m.A.get() == A.get());
  m.A = A;
  m.A_last = A;
  if (m.cfg.method == "direct" && m.use_mumps) {
#ifdef STENTOR_HAVE_MUMPS
    if (!m.mumps) m.mumps = std::make_unique<MumpsSolver>(m.comm);
    m.mumps->factor(*A);
#endif
    return;
  }
  if (m.cfg.method == "direct") {
#ifdef STENTOR_HAVE_AMESOS2
    if (m.comm->getSize() > 1) {
      // Factor a copy gathered on rank 0 (Impl::gathered_copy says why).
      m.Ac = m.gathered_copy(*A);
      m.gathered = true;
      if (m.Ac.is_null()) return;  // ranks other than 0 only send and receive
      m.direct = Amesos2::create<la::CrsMatrix, la::MV>("KLU2", m.Ac);
      if (!m.cfg.amesos2_xml.empty()) m.direct->setParameters(Impl::parse(m.cfg.amesos2_xml));
      m.direct->symbolicFactorization();
    } else if (!same || m.direct.is_null()) {
      m.direct = Amesos2::create<la::CrsMatrix, la::MV>("KLU2", A);
      if (!m.cfg.amesos2_xml.empty()) m.direct->setParameters(Impl::parse(m.cfg.amesos2_xml));
      m.direct->symbolicFactorization();
    }
    if (!m.direct.is_null()) m.direct->numericFactorization();
#endif
    return;
  }
  m.fresh = true;
  if (m.cfg.preconditioner == "none") return;
  m.fresh = false;
  const bool forced = force_rebuild_;
  force_rebuild_ = false;
  if (same && !forced && m.keep_preconditioner()) return;
  m.reuse.built();
  m.fresh = true;
  ++m.times.builds;
  if (m.cfg.preconditioner == "muelu") {
#ifdef STENTOR_HAVE_MUELU
    // Built once per matrix; later Newton iterations recompute it for the new values
    // through MueLu's reuse path (same graph), which skips parsing and setup of the factories.
    // Not on several ranks: there the coarse levels are repartitioned, and a recompute could
    // move a level's rows while keeping its smoother, which then failed on one rank only
    // (Ifpack2's "numRows == m_offsets.extent(0)", the other ranks waiting in a collective;
    // the S6 stent's sector on 2 ranks at its first contact, perf/scaling/s6_weak.sh).
    if (!same || m.mg.is_null() || m.comm->getSize() > 1)
      m.mg = make_muelu_preconditioner(A, m.dim, m.coords, m.cfg.muelu_xml);
    else
      recompute_muelu_preconditioner(A, m.mg);
    return;
#else
    throw InputError("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
#endif
  }
  if (!same || m.prec.is_null()) {
    if (m.cfg.preconditioner != "schwarz")
      throw InputError("Linear Solver->preconditioner: '" + m.cfg.preconditioner + "' is not available in this build (expected 'schwarz', 'muelu' or 'none')");
    const Teuchos::ParameterList pl = schwarz_parameters(m.cfg);
    const std::string type = "SCHWARZ";
    m.prec = Ifpack2::Factory::create<la::RowMatrix>(type, A);
    m.prec->setParameters(pl);
    m.prec->initialize();
  }
  m.prec->compute();
}

double LinearSolver::tolerance() const {
  if (impl_->cfg.method == "direct") return 0.0;
  return impl_->belos_params->get<double>("Convergence Tolerance");
}

LinearSolver::Result LinearSolver::solve(const la::Vector& b, la::Vector& x, double tolerance) {
  Clock clock{impl_->times.solve, impl_->times.solves};
  for (;;) {
    Result res;
    std::string why;
    try {
      res = solve_once(b, x, tolerance);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      why = "the solve failed (" + teuchos_short_message(e.what()) + ")";
    }
    const Agreement vote = agree(why);
    const bool threw = vote.failed();
    why = vote.failure;
    // An unconverged but finite result is Newton's to judge (an inexact step); a
    // non-finite one is a breakdown (collective norms: every rank agrees).
    if (why.empty() && impl_->cfg.method != "direct" && !(std::isfinite(res.residual) && std::isfinite(x.norm2())))
      why = "GMRES ended with a non-finite residual";
    // Less than one digit gained (solve_once stops after the first GMRES cycle then): a
    // reused preconditioner is rebuilt for this matrix and the solve repeated; one built for
    // this very matrix is no use as a Newton direction, and rebuilding it would give the same.
    const bool stalled = impl_->cfg.method != "direct" && !res.converged && res.residual > 0.1;
    if (why.empty() && stalled && !impl_->fresh && impl_->cfg.preconditioner != "none") {
      ++impl_->times.stale_rebuilds;
      force_rebuild_ = true;
      setup_or_fall_back(impl_->A_last);
      continue;
    }
    if (why.empty() && stalled && impl_->fresh) {
      std::ostringstream os;
      os << "GMRES gained less than one digit (relative residual " << std::setprecision(3) << res.residual << " after "
         << res.iterations << " iterations) with a freshly built preconditioner";
      why = os.str();
    }
    if (why.empty()) return res;
    if (!fall_back(why)) {
      if (threw) throw LinearSolverFailure(why);
      return res;
    }
    setup_or_fall_back(impl_->A_last);  // the same matrix, new configuration (further down if need be; timed as this solve)
  }
}

namespace {

// GMRES from x = 0. Where more iterations than one cycle (Num Blocks) are allowed, the
// first cycle runs alone: if it gains less than one digit (relative residual > 0.1) the
// solve stops there (solve() rebuilds or falls back, instead of spending the whole
// iteration budget on a preconditioner that does not work, e.g. 1000 iterations on a
// contact tangent); otherwise GMRES goes on from the cycle's iterate, which is what its
// restart does anyway, with the residual scaled by |b| (= the first cycle's |r0|).
void gmres_in_two_phases(Belos::LinearProblem<la::SC, la::MV, la::Operator>& problem,
                         const la::RCP<Teuchos::ParameterList>& params, LinearSolver::Result& res) {
  const int max_its = params->get<int>("Maximum Iterations");
  const int cycle = params->isType<int>("Num Blocks") ? params->get<int>("Num Blocks") : 300;  // Belos's default
  auto run = [&](const la::RCP<Teuchos::ParameterList>& pl) {
    Belos::PseudoBlockGmresSolMgr<la::SC, la::MV, la::Operator> solver(Teuchos::rcpFromRef(problem), pl);
    const Belos::ReturnType ret = solver.solve();
    res.converged = (ret == Belos::Converged);
    res.iterations += solver.getNumIters();
    res.residual = solver.achievedTol();
  };
  if (max_its <= cycle) {
    run(params);
    return;
  }
  auto first = Teuchos::rcp(new Teuchos::ParameterList(*params));
  first->set("Maximum Iterations", cycle);
  run(first);
  if (res.converged || res.residual > 0.1) return;
  auto rest = Teuchos::rcp(new Teuchos::ParameterList(*params));
  rest->set("Maximum Iterations", max_its - res.iterations);
  rest->set("Implicit Residual Scaling", std::string("Norm of RHS"));
  rest->set("Explicit Residual Scaling", std::string("Norm of RHS"));
  problem.setProblem();  // x now holds the first cycle's iterate: the new initial guess
  run(rest);
}

}  // namespace

LinearSolver::Result LinearSolver::solve_once(const la::Vector& b, la::Vector& x, double tolerance) {
  Impl& m = *impl_;
  Result res;
  x.putScalar(0.0);
  if (m.cfg.method == "direct" && m.use_mumps) {
#ifdef STENTOR_HAVE_MUMPS
    m.mumps->solve(b, x);
#endif
    res.converged = true;
    res.iterations = 1;
    return res;
  }
  if (m.cfg.method == "direct") {
#ifdef STENTOR_HAVE_AMESOS2
    if (m.gathered) {
      // b gathered on rank 0 in the contiguous numbering, solved there, x sent back.
      std::vector<double> v = m.rows->to_root(b);
      if (!m.Ac.is_null()) {
        la::Vector bs(m.Ac->getRowMap()), xs(m.Ac->getRowMap());
        {
          auto hs = bs.getLocalViewHost(Tpetra::Access::OverwriteAll);
          for (size_t i = 0; i < v.size(); ++i) hs(i, 0) = v[i];
        }
        m.direct->setX(Teuchos::rcpFromRef(static_cast<la::MV&>(xs)));
        m.direct->setB(Teuchos::rcpFromRef(static_cast<const la::MV&>(bs)));
        m.direct->solve();
        auto hs = xs.getLocalViewHost(Tpetra::Access::ReadOnly);
        for (size_t i = 0; i < v.size(); ++i) v[i] = hs(i, 0);
      }
      m.rows->from_root(v, x);
    } else {
      m.direct->setX(Teuchos::rcpFromRef(static_cast<la::MV&>(x)));
      m.direct->setB(Teuchos::rcpFromRef(static_cast<const la::MV&>(b)));
      m.direct->solve();
    }
    res.converged = true;
    res.iterations = 1;
#endif
    return res;
  }
  auto problem = Teuchos::rcp(new Belos::LinearProblem<la::SC, la::MV, la::Operator>(
      m.A, Teuchos::rcpFromRef(static_cast<la::MV&>(x)), Teuchos::rcpFromRef(static_cast<const la::MV&>(b))));
  if (!m.prec.is_null()) problem->setRightPrec(m.prec);
  if (!m.mg.is_null()) problem->setRightPrec(m.mg);
  problem->setProblem();
  auto params = m.belos_params;
  // GMRES never needs more Krylov vectors than the system has rows, and Belos allocates
  // all of them at once: 'restart' or Belos->Num Blocks = 1e9 asked for 119 GB (exit 1).
  const auto rows = static_cast<long long>(m.A->getDomainMap()->getGlobalNumElements());
  const bool clamp = params->isType<int>("Num Blocks") && params->get<int>("Num Blocks") > std::max(rows, 1LL);
  if (tolerance > 0.0 || clamp) {
    params = Teuchos::rcp(new Teuchos::ParameterList(*m.belos_params));
    if (tolerance > 0.0) params->set("Convergence Tolerance", tolerance);
    if (clamp) params->set("Num Blocks", static_cast<int>(std::max(rows, 1LL)));
  }
  gmres_in_two_phases(*problem, params, res);
  m.reuse.solved(res.iterations, res.residual, res.converged);
  return res;
}

std::string LinearSolver::description() const {
  const auto& c = impl_->cfg;
  if (c.method == "direct" && impl_->use_mumps) return "direct (MUMPS, " + std::to_string(impl_->comm->getSize()) + " rank(s))";
  if (c.method == "direct") return "direct (Amesos2 KLU2)";
  std::ostringstream tol;
  tol << c.tolerance;
  std::string s = "Belos GMRES(" + std::to_string(c.restart) + "), tol " + tol.str();
  if (c.preconditioner == "schwarz")
    s += ", Ifpack2 Schwarz overlap " + std::to_string(c.overlap) + " / " + c.subdomain_solver +
         (c.subdomain_solver == "RILUK" ? "(" + std::to_string(c.fill_level) + ")" : "");
  else if (c.preconditioner == "muelu")
    s += ", MueLu smoothed-aggregation AMG (rigid-body modes)";
  else
    s += ", no preconditioner";
  if (impl_->auto_chosen) s += " (preconditioner = auto)";
  return s;
}

}  // namespace stentor
