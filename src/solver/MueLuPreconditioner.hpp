// Smoothed-aggregation algebraic multigrid (MueLu) for the elasticity tangent, as a
// Tpetra::Operator for Belos. Kept Trilinos-light: MueLu's (heavy) headers are seen only by
// MueLuPreconditioner.cpp, and only builds with MueLu compile it (STENTOR_HAVE_MUELU).
//
// Defaults (see make_muelu_preconditioner): SA-AMG, uncoupled aggregation of dim-dof
// nodes, rigid-body-mode near null space (dim=2: 3 modes, dim=3: 6), one sweep of
// symmetric Gauss-Seidel, KLU2 coarse solve below 1000 rows, "reuse: type" "S". The deck's
// "Linear Solver"->"MueLu" sublist (MueLu parameter names) overrides any of them; setting
// "smoother: type" there drops the default "smoother: params" too. Numbers: docs/solvers.md.
#pragma once
#include <string>
#include <vector>

#include "parallel/LinearAlgebra.hpp"

namespace stentor {

// Builds the hierarchy for A. owned_xyz: reference coordinates of the nodes behind A's
// owned rows, 3 per node (z ignored in 2D), in row order: row lid = node*dim + c.
// user_xml: MueLu ParameterList as XML text ("" for none); its entries win over the defaults.
// Throws InputError on bad input (coordinates that do not match A's rows, bad XML).
la::RCP<la::Operator> make_muelu_preconditioner(const la::RCP<la::CrsMatrix>& A, int dim, const std::vector<double>& owned_xyz,
                                                const std::string& user_xml);

// New values in A (same object and graph as when `prec` was built): recomputes `prec` in
// place through MueLu's reuse path (MueLu::ReuseTpetraPreconditioner). What is kept follows
// "reuse: type": default "S" keeps the aggregates, which with "aggregation: drop tol" 0 depend
// on the graph only, so the result equals a rebuild; "none" recomputes all; "RP" keeps P and R
// (cheaper, more iterations); "tP" fails in Trilinos 13.2 (static-graph insert). See docs/solvers.md.
void recompute_muelu_preconditioner(const la::RCP<la::CrsMatrix>& A, const la::RCP<la::Operator>& prec);

// Rigid-body modes of dim-dimensional elasticity on A's row map (dim=2: 3 columns, x/y
// translations and the in-plane rotation; dim=3: 6 columns, 3 translations and rotations
// about x, y, z), about the global centroid of the nodes. Exposed for tests.
la::RCP<la::MV> rigid_body_modes(const la::RCP<const la::Map>& row_map, int dim, const std::vector<double>& owned_xyz);

}  // namespace stentor
