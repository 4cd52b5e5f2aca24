#include "solver/MueLuPreconditioner.hpp"

#include <cmath>
#include <cstddef>

#include "deck/Config.hpp"
#include "solver/SolverParams.hpp"

#ifdef STENTOR_HAVE_MUELU
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <MueLu_MasterList.hpp>
#include <MueLu_TpetraOperator.hpp>
#include <MueLu_TrilinosSmoother.hpp>
#ifdef STENTOR_HAVE_AMESOS2
#include <Amesos2.hpp>
#endif
#include <Teuchos_XMLParameterListHelpers.hpp>
#endif

namespace stentor {

namespace {

void check_coordinates(const la::Map& row_map, int dim, const std::vector<double>& owned_xyz) {
  if (dim != 2 && dim != 3) throw InputError("MueLu: dimension must be 2 or 3 (got " + std::to_string(dim) + ")");
  const std::size_t rows = row_map.getNodeNumElements();
  if (rows % static_cast<std::size_t>(dim) != 0 || owned_xyz.size() != 3 * (rows / static_cast<std::size_t>(dim)))
    throw InputError("MueLu: node coordinates (" + std::to_string(owned_xyz.size() / 3) + " nodes) do not match the " +
                     std::to_string(rows) + " owned rows of the matrix (dim " + std::to_string(dim) +
                     "); call LinearSolver::set_node_coordinates before setup");
}


}  // namespace

la::RCP<la::MV> rigid_body_modes(const la::RCP<const la::Map>& row_map, int dim, const std::vector<double>& owned_xyz) {
  check_coordinates(*row_map, dim, owned_xyz);
  const std::size_t nn = owned_xyz.size() / 3;
  // Global centroid: rotations about it keep the modes well scaled against the translations.
  double loc[4] = {0.0, 0.0, 0.0, static_cast<double>(nn)}, glob[4] = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t n = 0; n < nn; ++n)
    for (int k = 0; k < 3; ++k) loc[k] += owned_xyz[3 * n + static_cast<std::size_t>(k)];
  Teuchos::reduceAll(*row_map->getComm(), Teuchos::REDUCE_SUM, 4, loc, glob);
  const double c[3] = {glob[3] > 0 ? glob[0] / glob[3] : 0.0, glob[3] > 0 ? glob[1] / glob[3] : 0.0,
                       glob[3] > 0 ? glob[2] / glob[3] : 0.0};

  const int nmodes = dim == 2 ? 3 : 6;
  auto ns = Teuchos::rcp(new la::MV(row_map, static_cast<std::size_t>(nmodes), true));
  auto v = ns->getLocalViewHost(Tpetra::Access::ReadWrite);
  for (std::size_t n = 0; n < nn; ++n) {
    const double x = owned_xyz[3 * n] - c[0], y = owned_xyz[3 * n + 1] - c[1], z = owned_xyz[3 * n + 2] - c[2];
    const std::size_t r = n * static_cast<std::size_t>(dim);
    for (int k = 0; k < dim; ++k) v(r + static_cast<std::size_t>(k), static_cast<std::size_t>(k)) = 1.0;  // translations
    if (dim == 2) {
      v(r, 2) = -y;  // rotation about z
      v(r + 1, 2) = x;
    } else {
      v(r + 1, 3) = -z;  // rotation about x: (0, -z, y)
      v(r + 2, 3) = y;
      v(r, 4) = z;  // rotation about y: (z, 0, -x)
      v(r + 2, 4) = -x;
      v(r, 5) = -y;  // rotation about z: (-y, x, 0)
      v(r + 1, 5) = x;
    }
  }
  return ns;
}

#ifdef STENTOR_HAVE_MUELU

la::RCP<la::Operator> make_muelu_preconditioner(const la::RCP<la::CrsMatrix>& A, int dim, const std::vector<double>& owned_xyz,
                                                const std::string& user_xml) {
  const la::RCP<const la::Map> rows = A->getRowMap();
  auto nullspace = rigid_body_modes(rows, dim, owned_xyz);

  // Coordinates on a node map (one entry per owned node; dof gid = node gid * dim + c).
  const std::size_t nn = owned_xyz.size() / 3;
  std::vector<la::GO> node_gids(nn);
  for (std::size_t n = 0; n < nn; ++n) node_gids[n] = rows->getGlobalElement(static_cast<la::LO>(n * static_cast<std::size_t>(dim))) / dim;
  auto node_map = Teuchos::rcp(new la::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                           Teuchos::ArrayView<const la::GO>(node_gids), rows->getIndexBase(), rows->getComm()));
  using CoordMV = Tpetra::MultiVector<typename Teuchos::ScalarTraits<la::SC>::coordinateType, la::LO, la::GO, la::Node>;
  auto coords = Teuchos::rcp(new CoordMV(node_map, static_cast<std::size_t>(dim), false));
  {
    auto cv = coords->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (std::size_t n = 0; n < nn; ++n)
      for (int k = 0; k < dim; ++k) cv(n, static_cast<std::size_t>(k)) = owned_xyz[3 * n + static_cast<std::size_t>(k)];
  }

  Teuchos::ParameterList p;
  p.set("verbosity", std::string("none"));
  p.set("problem: symmetric", true);
  p.set("number of equations", dim);
  p.set("multigrid algorithm", std::string("sa"));
  p.set("max levels", 10);
  p.set("coarse: max size", 1000);
  p.set("coarse: type", std::string("KLU2"));
  p.set("aggregation: type", std::string("uncoupled"));
  p.set("aggregation: drop tol", 0.0);
  // Symmetric Gauss-Seidel (one sweep; Jacobi between ranks). Measured against Chebyshev of
  // degree 2/3/4 on the 3D block (docs/solvers.md): fewest GMRES iterations and least time.
  p.set("smoother: type", std::string("RELAXATION"));
  p.sublist("smoother: params").set("relaxation: type", std::string("Symmetric Gauss-Seidel"));
  p.sublist("smoother: params").set("relaxation: sweeps", 1);
  // On several ranks the coarse levels (from level 2 on) move onto fewer ranks where they
  // would hold under 2000 rows each (Zoltan2, on the node coordinates): measured on 16
  // cores, the GMRES iterations per Newton iteration of the cube grow 1.17x from 1 to 16
  // ranks at fixed work per rank, against 1.85x without (docs/performance.md).
  const bool several = A->getComm()->getSize() > 1;
  p.set("repartition: enable", several);
  if (several) p.set("repartition: min rows per proc", 2000);
  // Newton keeps the graph: keep the aggregates (with drop tol 0 they depend on the graph
  // only, so the hierarchy is the same as a rebuild's) and recompute P, R, RAP, smoothers.
  p.set("reuse: type", std::string("S"));
  if (!user_xml.empty()) {
    Teuchos::RCP<Teuchos::ParameterList> user;
    try {
      user = Teuchos::getParametersFromXmlString(user_xml);
    } catch (const std::exception& e) {
      throw InputError(std::string("Linear Solver->MueLu: ") + e.what());
    }
    // A user smoother replaces ours whole (our Gauss-Seidel parameters would not fit another type).
    if (user->isParameter("smoother: type")) p.remove("smoother: params");
    p.setParameters(*user);  // user pass-through wins
  }
  // The modes are kept whole on constrained (identity) rows: zeroing them there gains ~5% in
  // iterations but leaves zero columns in aggregates on a constrained face, which MueLu's
  // tentative prolongator rejects.
  Teuchos::ParameterList& ud = p.sublist("user data");
  ud.set("Nullspace", nullspace);
  ud.set("Coordinates", coords);

  la::RCP<la::Operator> Aop = A;
  try {
    return MueLu::CreateTpetraPreconditioner<la::SC, la::LO, la::GO, la::Node>(Aop, p);
  } catch (const Teuchos::Exceptions::InvalidParameter& e) {  // unknown name, wrong type or value
    throw InputError("Linear Solver->MueLu: " + teuchos_short_message(e.what()));
  }
}

namespace {

// A smoother type MueLu's factory can build (Ifpack2 types such as RELAXATION, CHEBYSHEV,
// RILUK, ILUT, SCHWARZ; Belos; an Amesos2 solver for "coarse: type"). `params`: the
// matching "smoother: params" list, if any.
void check_smoother(const std::string& where, const std::string& type, const Teuchos::ParameterList& params, bool coarse) {
  if (type == "none") return;
#ifdef STENTOR_HAVE_AMESOS2
  if (coarse && Amesos2::query(type)) return;
#endif
  try {
    MueLu::TrilinosSmoother<la::SC, la::LO, la::GO, la::Node> s(type, params);
  } catch (const std::exception& e) {
    throw InputError(where + " = '" + type + "': MueLu cannot build this smoother (expected an Ifpack2 type such as "
                     "RELAXATION, CHEBYSHEV, RILUK, ILUT or SCHWARZ" + std::string(coarse ? ", or an Amesos2 solver such as KLU2" : "") +
                     ", or none)");
  }
}

// One level's list (the main one or "level N"): names and types, smoothers, ranges.
void check_muelu_list(const Teuchos::ParameterList& user, const std::string& where) {
  const Teuchos::ParameterList& valid = *MueLu::MasterList::List();
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    if (name == "user data" || name.rfind("level ", 0) == 0) continue;
    Teuchos::ParameterList one(user.name());
    one.setEntry(name, user.entry(it));
    try {
      one.validateParameters(valid, 0);
    } catch (const std::exception& e) {
      throw InputError(where + "->" + name + ": " + teuchos_short_message(e.what()) +
                       (valid.isParameter(name) ? "" : did_you_mean(name, valid)));
    }
  }
  const Teuchos::ParameterList none;
  for (const char* n : {"smoother: type", "smoother: pre type", "smoother: post type"})
    if (user.isType<std::string>(n)) {
      const std::string t = n, k = t.substr(0, t.size() - 4) + "params";  // "smoother: pre type" -> "smoother: pre params"
      check_smoother(where + "->" + n, user.get<std::string>(n), user.isSublist(k) ? user.sublist(k) : none, false);
    }
  if (user.isType<std::string>("coarse: type"))
    check_smoother(where + "->coarse: type", user.get<std::string>("coarse: type"),
                   user.isSublist("coarse: params") ? user.sublist("coarse: params") : none, true);
  // Petrov-Galerkin needs a non-symmetric problem, and Stentor's default says symmetric:
  // MueLu's set-up would throw and the run fall back to Schwarz with only a warning.
  if (user.isType<std::string>("multigrid algorithm") && user.get<std::string>("multigrid algorithm") == "pg" &&
      !(user.isType<bool>("problem: symmetric") && !user.get<bool>("problem: symmetric")))
    throw InputError(where + "->multigrid algorithm = 'pg' (Petrov-Galerkin) needs 'problem: symmetric' = false in the same "
                     "list (Stentor's default is true)");
  // Ranges MueLu does not check: "max levels" = 0 crashes (SIGSEGV) in Trilinos 13.2.
  for (const char* n : {"max levels", "coarse: max size", "number of equations"})
    if (user.isType<int>(n) && user.get<int>(n) < 1)
      throw InputError(where + "->" + n + " = " + std::to_string(user.get<int>(n)) + ": expected an integer >= 1");
  // MueLu sets up every level it may use: 1000 levels cost 4 s and 60 MB, 100000 more
  // than 100 s and 2 GB (found by the corpus). Each level coarsens at least twofold, so
  // 100 is more than any mesh needs.
  if (user.isType<int>("max levels") && user.get<int>("max levels") > 100)
    throw InputError(where + "->max levels = " + std::to_string(user.get<int>("max levels")) +
                     ": expected an integer from 1 to 100 (each level is at least twice as coarse as the one above)");
}

}  // namespace

void validate_muelu_parameters(const std::string& xml) {
  const std::string where = "Linear Solver->MueLu";
  if (xml.empty()) return;
  Teuchos::RCP<Teuchos::ParameterList> user;
  try {
    user = Teuchos::getParametersFromXmlString(xml);
  } catch (const std::exception& e) {
    throw InputError(where + ": " + teuchos_short_message(e.what()));
  }
  check_muelu_list(*user, where);
  for (auto it = user->begin(); it != user->end(); ++it)
    if (user->name(it).rfind("level ", 0) == 0 && user->entry(it).isList())
      check_muelu_list(user->sublist(user->name(it)), where + "->" + user->name(it));
}

void recompute_muelu_preconditioner(const la::RCP<la::CrsMatrix>& A, const la::RCP<la::Operator>& prec) {
  auto mg = Teuchos::rcp_dynamic_cast<MueLu::TpetraOperator<la::SC, la::LO, la::GO, la::Node>>(prec, true);
  MueLu::ReuseTpetraPreconditioner<la::SC, la::LO, la::GO, la::Node>(A, *mg);
}

#else

void validate_muelu_parameters(const std::string&) {}

la::RCP<la::Operator> make_muelu_preconditioner(const la::RCP<la::CrsMatrix>&, int, const std::vector<double>&, const std::string&) {
  throw InputError("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
}

void recompute_muelu_preconditioner(const la::RCP<la::CrsMatrix>&, const la::RCP<la::Operator>&) {
  throw InputError("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
}

#endif

}  // namespace stentor
