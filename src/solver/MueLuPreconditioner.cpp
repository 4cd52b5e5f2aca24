#include "solver/MueLuPreconditioner.hpp"

#include <cmath>
#include <cstddef>

#include "deck/Config.hpp"

#ifdef STENTOR_HAVE_MUELU
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <MueLu_TpetraOperator.hpp>
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

#ifdef STENTOR_HAVE_MUELU
// Teuchos' validation message without the file/line header and the list of every valid
// parameter (MueLu's "Did you mean ...?" hint is kept).
std::string short_message(const std::string& what) {
  std::size_t b = what.find("Error, the parameter");
  if (b == std::string::npos) b = what.find("Error,");
  if (b == std::string::npos) return what;
  std::size_t e = what.find("The valid parameters", b);
  std::string msg = what.substr(b, e == std::string::npos ? std::string::npos : e - b);
  const std::size_t hint = what.find("The parameter name \"");
  if (hint != std::string::npos) msg += " " + what.substr(hint);
  std::string out;
  for (char c : msg) {
    if (c == '\n') c = ' ';
    if (c != ' ' || (!out.empty() && out.back() != ' ')) out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}
#endif

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
  p.set("repartition: enable", false);
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
    throw InputError("Linear Solver->MueLu: " + short_message(e.what()));
  }
}

void recompute_muelu_preconditioner(const la::RCP<la::CrsMatrix>& A, const la::RCP<la::Operator>& prec) {
  auto mg = Teuchos::rcp_dynamic_cast<MueLu::TpetraOperator<la::SC, la::LO, la::GO, la::Node>>(prec, true);
  MueLu::ReuseTpetraPreconditioner<la::SC, la::LO, la::GO, la::Node>(A, *mg);
}

#else

la::RCP<la::Operator> make_muelu_preconditioner(const la::RCP<la::CrsMatrix>&, int, const std::vector<double>&, const std::string&) {
  throw InputError("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
}

void recompute_muelu_preconditioner(const la::RCP<la::CrsMatrix>&, const la::RCP<la::Operator>&) {
  throw InputError("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
}

#endif

}  // namespace stentor
