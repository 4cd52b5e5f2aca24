#include "solver/LinearSolver.hpp"

#include <BelosLinearProblem.hpp>
#include <BelosPseudoBlockGmresSolMgr.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Ifpack2_Factory.hpp>
#include <sstream>

#include "solver/MueLuPreconditioner.hpp"
#include <Teuchos_XMLParameterListHelpers.hpp>
#ifdef STENTOR_HAVE_AMESOS2
#include <Amesos2.hpp>
#endif

namespace stentor {

struct LinearSolver::Impl {
  LinearSolverConfig cfg;
  la::RCP<const la::Comm> comm;
  la::RCP<la::CrsMatrix> A;
  la::RCP<Ifpack2::Preconditioner<la::SC, la::LO, la::GO, la::Node>> prec;  // schwarz
  la::RCP<la::Operator> mg;  // muelu (a MueLu::TpetraOperator)
  bool prec_initialized = false;
#ifdef STENTOR_HAVE_AMESOS2
  la::RCP<Amesos2::Solver<la::CrsMatrix, la::MV>> direct;
#endif
  Teuchos::RCP<Teuchos::ParameterList> belos_params;
  int dim = 0;
  std::vector<double> coords;  // owned nodes, 3 each (for multigrid null spaces)

  static Teuchos::RCP<Teuchos::ParameterList> parse(const std::string& xml) {
    if (xml.empty()) return Teuchos::rcp(new Teuchos::ParameterList());
    return Teuchos::getParametersFromXmlString(xml);
  }
};

LinearSolver::LinearSolver(const LinearSolverConfig& cfg, const la::RCP<const la::Comm>& comm) : impl_(new Impl) {
  impl_->cfg = cfg;
  impl_->comm = comm;
  auto& p = impl_->belos_params;
  p = Teuchos::rcp(new Teuchos::ParameterList("Belos"));
  p->set("Convergence Tolerance", cfg.tolerance);
  p->set("Maximum Iterations", cfg.max_iterations);
  p->set("Num Blocks", cfg.restart);
  p->set("Maximum Restarts", std::max(1, cfg.max_iterations / std::max(1, cfg.restart)));
  p->set("Verbosity", Belos::Errors);
  p->setParameters(*Impl::parse(cfg.belos_xml));  // user pass-through wins
#ifndef STENTOR_HAVE_AMESOS2
  if (cfg.method == "direct")
    throw InputError("Linear Solver->method: 'direct' needs Trilinos with Amesos2, which this build lacks; use 'gmres'");
#endif
}

LinearSolver::~LinearSolver() = default;

void LinearSolver::set_node_coordinates(int dim, const std::vector<double>& owned_xyz) {
  impl_->dim = dim;
  impl_->coords = owned_xyz;
}

void LinearSolver::setup(const la::RCP<la::CrsMatrix>& A) {
  Impl& m = *impl_;
  const bool same = (m.A.get() == A.get());
  m.A = A;
  if (m.cfg.method == "direct") {
#ifdef STENTOR_HAVE_AMESOS2
    if (!same || m.direct.is_null()) {
      m.direct = Amesos2::create<la::CrsMatrix, la::MV>("KLU2", A);
      if (!m.cfg.amesos2_xml.empty()) m.direct->setParameters(Impl::parse(m.cfg.amesos2_xml));
      m.direct->symbolicFactorization();
    }
    m.direct->numericFactorization();
#endif
    return;
  }
  if (m.cfg.preconditioner == "none") return;
  if (m.cfg.preconditioner == "muelu") {
#ifdef STENTOR_HAVE_MUELU
    // Built once per matrix; later Newton iterations recompute it for the new values
    // through MueLu's reuse path (same graph), which skips parsing and setup of the factories.
    if (!same || m.mg.is_null())
      m.mg = make_muelu_preconditioner(A, m.dim, m.coords, m.cfg.muelu_xml);
    else
      recompute_muelu_preconditioner(A, m.mg);
    return;
#else
    throw InputError("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
#endif
  }
  if (!same || m.prec.is_null()) {
    Teuchos::ParameterList pl;
    std::string type;
    if (m.cfg.preconditioner == "schwarz") {
      type = "SCHWARZ";
      pl.set("schwarz: overlap level", m.cfg.overlap);
      pl.set("inner preconditioner name", m.cfg.subdomain_solver == "KLU2" ? std::string("AMESOS2") : m.cfg.subdomain_solver);
      Teuchos::ParameterList& inner = pl.sublist("inner preconditioner parameters");
      if (m.cfg.subdomain_solver == "RILUK") inner.set("fact: iluk level-of-fill", m.cfg.fill_level);
      if (m.cfg.subdomain_solver == "ILUT") inner.set("fact: ilut level-of-fill", static_cast<double>(std::max(1, m.cfg.fill_level)));
      if (m.cfg.subdomain_solver == "KLU2") inner.set("Amesos2 solver name", std::string("KLU2"));
    } else {
      throw InputError("Linear Solver->preconditioner: '" + m.cfg.preconditioner + "' is not available in this build (expected 'schwarz', 'muelu' or 'none')");
    }
    pl.setParameters(*Impl::parse(m.cfg.ifpack2_xml));
    m.prec = Ifpack2::Factory::create<la::RowMatrix>(type, A);
    m.prec->setParameters(pl);
    m.prec->initialize();
  }
  m.prec->compute();
}

LinearSolver::Result LinearSolver::solve(const la::Vector& b, la::Vector& x) {
  Impl& m = *impl_;
  Result res;
  x.putScalar(0.0);
  if (m.cfg.method == "direct") {
#ifdef STENTOR_HAVE_AMESOS2
    m.direct->setX(Teuchos::rcpFromRef(static_cast<la::MV&>(x)));
    m.direct->setB(Teuchos::rcpFromRef(static_cast<const la::MV&>(b)));
    m.direct->solve();
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
  Belos::PseudoBlockGmresSolMgr<la::SC, la::MV, la::Operator> solver(problem, m.belos_params);
  const Belos::ReturnType ret = solver.solve();
  res.converged = (ret == Belos::Converged);
  res.iterations = solver.getNumIters();
  res.residual = solver.achievedTol();
  return res;
}

std::string LinearSolver::description() const {
  const auto& c = impl_->cfg;
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
  return s;
}

}  // namespace stentor
