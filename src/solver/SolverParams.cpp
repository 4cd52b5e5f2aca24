#include "solver/SolverParams.hpp"

#include <BelosPseudoBlockGmresSolMgr.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Ifpack2_AdditiveSchwarz.hpp>
#include <Ifpack2_Factory.hpp>
#include <Ifpack2_Parameters.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <sstream>
#ifdef STENTOR_HAVE_AMESOS2
#include <Amesos2.hpp>
#endif

#include "deck/Schema.hpp"
#include "parallel/LinearAlgebra.hpp"
#include "solver/LinearSolver.hpp"

namespace stentor {

std::string teuchos_short_message(const std::string& what) {
  std::size_t b = what.find("Error, the parameter");
  if (b == std::string::npos) b = what.find("Error,");
  if (b == std::string::npos) b = what.find("Error!");
  std::string msg = what;
  if (b != std::string::npos) {
    const std::size_t e = what.find("The valid parameters", b);
    msg = what.substr(b, e == std::string::npos ? std::string::npos : e - b);
    const std::size_t hint = what.find("The parameter name \"");
    if (hint != std::string::npos) msg += " " + what.substr(hint);
  } else {
    // A TEUCHOS_TEST_FOR_EXCEPTION text: drop its "file:line:\n\nThrow number ...\n\nThrow test ...\n\n" header.
    const std::size_t t = what.find("Throw test that evaluated to true:");
    if (t != std::string::npos) {
      const std::size_t body = what.find("\n\n", t);
      if (body != std::string::npos) msg = what.substr(body + 2);
    }
  }
  const std::size_t throw_no = msg.find("Throw number");
  if (throw_no != std::string::npos && throw_no > 0) msg.erase(throw_no);
  std::string out;
  for (char c : msg) {
    if (c == '\n') c = ' ';
    if (c != ' ' || (!out.empty() && out.back() != ' ')) out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  for (const std::string junk : {" in the parameter (sub)list \"ANONYMOUS\"", "Error, the parameter ", "Error! "}) {
    std::size_t j;
    while ((j = out.find(junk)) != std::string::npos) out.erase(j, junk.size());
  }
  return out;
}

std::string did_you_mean(const std::string& name, const Teuchos::ParameterList& valid) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(3, name.size() / 4) + 1;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const auto dist = static_cast<std::size_t>(edit_distance_ci(name, valid.name(it)));
    if (dist < best_d) best_d = dist, best = valid.name(it);
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

namespace {

using Teuchos::ParameterList;

Teuchos::RCP<ParameterList> parse(const std::string& xml, const std::string& where) {
  if (xml.empty()) return Teuchos::rcp(new ParameterList());
  try {
    return Teuchos::getParametersFromXmlString(xml);
  } catch (const std::exception& e) {
    throw InputError(where + ": " + teuchos_short_message(e.what()));
  }
}

// Each entry of `user` (not its sublists, unless `sublists`) alone against `valid`: the
// message names the entry. Names in `skip` are not checked here.
void check_entries(const ParameterList& user, const ParameterList& valid, const std::string& where,
                   const std::vector<std::string>& skip = {}, bool sublists = false) {
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    if (std::find(skip.begin(), skip.end(), name) != skip.end()) continue;
    if (user.entry(it).isList() && !sublists) continue;
    ParameterList one(user.name());
    one.setEntry(name, user.entry(it));
    try {
      one.validateParameters(valid, 0);
    } catch (const std::exception& e) {
      const bool unknown = !valid.isParameter(name);
      throw InputError(where + "->" + name + ": " + teuchos_short_message(e.what()) + (unknown ? did_you_mean(name, valid) : ""));
    }
  }
}

// A 1D Laplacian of n rows on this process alone: enough to set a package up.
la::RCP<la::CrsMatrix> tiny_matrix(int n) {
  auto self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  auto map = Teuchos::rcp(new la::Map(static_cast<Tpetra::global_size_t>(n), 0, self));
  auto A = Teuchos::rcp(new la::CrsMatrix(map, 3));
  for (la::GO i = 0; i < n; ++i) {
    std::vector<la::GO> c{i};
    std::vector<la::SC> v{2.0};
    if (i > 0) c.push_back(i - 1), v.push_back(-1.0);
    if (i + 1 < n) c.push_back(i + 1), v.push_back(-1.0);
    A->insertGlobalValues(i, Teuchos::ArrayView<const la::GO>(c), Teuchos::ArrayView<const la::SC>(v));
  }
  A->fillComplete();
  return A;
}

double number(const ParameterList& p, const std::string& name) {
  const auto& e = p.getEntry(name);
  if (e.isType<double>()) return Teuchos::getValue<double>(e);
  if (e.isType<int>()) return Teuchos::getValue<int>(e);
  return 1.0;  // other types: the type check reports them
}

void check_belos(const LinearSolverConfig& cfg) {
  const std::string where = "Linear Solver->Belos";
  const auto user = parse(cfg.belos_xml, where);
  Belos::PseudoBlockGmresSolMgr<la::SC, la::MV, la::Operator> gmres;
  check_entries(*user, *gmres.getValidParameters(), where, {}, true);
  // Ranges Belos does not check (it would loop or stop at once).
  if (user->isParameter("Convergence Tolerance")) {
    const double tol = number(*user, "Convergence Tolerance");
    if (!(tol > 0.0) || !std::isfinite(tol))
      throw InputError(where + "->Convergence Tolerance = " + std::to_string(tol) + ": expected a finite number > 0");
  }
  for (const char* n : {"Maximum Iterations", "Maximum Restarts"})
    if (user->isParameter(n) && number(*user, n) < 0)
      throw InputError(where + "->" + n + " = " + std::to_string(static_cast<long>(number(*user, n))) + ": expected an integer >= 0");
  // Belos' own range checks ("Num Blocks" must be strictly positive, ...).
  auto all = belos_parameters(cfg);
  try {
    gmres.setParameters(all);
  } catch (const std::exception& e) {
    throw InputError(where + ": " + teuchos_short_message(e.what()));
  }
}

void check_ifpack2(const LinearSolverConfig& cfg) {
  const std::string where = "Linear Solver->Ifpack2";
  const auto user = parse(cfg.ifpack2_xml, where);
  const auto A = tiny_matrix(8);
  auto prec = Ifpack2::Factory::create<la::RowMatrix>("SCHWARZ", la::RCP<const la::RowMatrix>(A));
  const std::vector<std::string> inner = {"inner preconditioner name", "subdomain solver name", "schwarz: inner preconditioner name",
                                          "schwarz: subdomain solver name", "inner preconditioner parameters",
                                          "subdomain solver parameters", "schwarz: inner preconditioner parameters",
                                          "schwarz: subdomain solver parameters"};
  const auto* schwarz = dynamic_cast<const Ifpack2::AdditiveSchwarz<la::RowMatrix>*>(prec.get());
  if (schwarz) check_entries(*user, *schwarz->getValidParameters(), where, inner, true);
  // The subdomain solver's list against every parameter Ifpack2 knows.
  ParameterList known;
  Ifpack2::getValidParameters(known);
  for (const char* n : {"inner preconditioner parameters", "subdomain solver parameters", "schwarz: inner preconditioner parameters",
                        "schwarz: subdomain solver parameters"})
    if (user->isSublist(n)) check_entries(user->sublist(n), known, where + "->" + n);
  // Set up on the tiny matrix with the run's settings (the subdomain solver by name).
  try {
    prec->setParameters(schwarz_parameters(cfg));
    prec->initialize();
    prec->compute();
  } catch (const std::exception& e) {
    throw InputError(where + " (with 'Linear Solver->subdomain solver' = " + cfg.subdomain_solver +
                     "): Ifpack2 refused the settings: " + teuchos_short_message(e.what()));
  }
}

void check_amesos2(const LinearSolverConfig& cfg) {
#ifdef STENTOR_HAVE_AMESOS2
  const std::string where = "Linear Solver->Amesos2";
  const auto user = parse(cfg.amesos2_xml, where);
  if (user->numParams() == 0) return;
  const auto A = tiny_matrix(8);
  auto klu = Amesos2::create<la::CrsMatrix, la::MV>("KLU2", A);
  // Amesos2's valid list: its control parameters and a sublist "KLU2" of the solver's own.
  const auto valid = klu->getValidParameters();
  check_entries(*user, *valid, where, {}, true);
  if (user->isSublist("KLU2") && valid->isSublist("KLU2")) check_entries(user->sublist("KLU2"), valid->sublist("KLU2"), where + "->KLU2");
  user->setName("Amesos2");
  try {
    klu->setParameters(user);
    klu->symbolicFactorization().numericFactorization();
  } catch (const std::exception& e) {
    throw InputError(where + ": Amesos2 refused the settings: " + teuchos_short_message(e.what()));
  }
#else
  (void)cfg;
#endif
}

}  // namespace

void validate_linear_solver(const LinearSolverConfig& cfg) {
  auto pass = [](const std::string& xml) { return !xml.empty(); };
  std::string prec = cfg.preconditioner;
#ifdef STENTOR_HAVE_MUELU
  if (prec == "auto") prec = "muelu";
#else
  if (prec == "auto") prec = "schwarz";
#endif
  if (cfg.method == "gmres") {
    check_belos(cfg);
    if (prec == "schwarz" && (pass(cfg.ifpack2_xml) || cfg.subdomain_solver != "RILUK")) check_ifpack2(cfg);
#ifdef STENTOR_HAVE_MUELU
    if (prec == "muelu" && pass(cfg.muelu_xml)) validate_muelu_parameters(cfg.muelu_xml);
#endif
  } else if (pass(cfg.amesos2_xml)) {
    check_amesos2(cfg);
  }
}

}  // namespace stentor
