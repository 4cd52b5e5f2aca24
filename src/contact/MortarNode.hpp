// One slave node of a dual mortar pair (docs/contact.md, "Dual mortar"): the integrals of
// its facets against the master facets (FaceCoupling, from contact/Mortar.hpp), gathered
// into its local unknowns (Stencil), its nodal normal, and the contact law chained to
// them (the rows of its conditions and the master rows, MortarRows). Host code: values
// with dense derivatives over the node's local unknowns (Grad).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "contact/MasterSurface.hpp"
#include "contact/Mortar.hpp"
#include "contact/NodeLaw.hpp"

namespace stentor::contact {

// Slave facet e against one master facet: M_ab = int_e Phi_a N_b^m and its derivatives
// with respect to the slave facet's positions (3 per node) and then the master facet's.
struct FaceCoupling {
  int master = -1;
  double M[4][4] = {};
  double dM[4][4][mortar::kPairVars] = {};
};

// A value and its derivatives with respect to a node's local unknowns.
struct Grad {
  double v = 0.0;
  std::vector<double> d;
  explicit Grad(std::size_t n = 0) : d(n, 0.0) {}
};

// A slave node's local unknowns (surface positions, dim each: vars[0] the node itself, then
// its facets' nodes, then the coupled master nodes) and M_pk per coupled master node k.
struct Stencil {
  int dim = 2;
  std::vector<int> vars, masters;
  std::vector<Grad> M;
  std::size_t nv() const { return static_cast<std::size_t>(dim) * vars.size(); }
  std::size_t var(int pos);   // index of a surface position among vars (appended if new)
  std::size_t slot(int pos);  // index of a master node among masters (appended if new)
};

// The conditions of an active node: its rows (res, dres: dim x nvar) and the master rows
// w_k r_p (add: masters x dim; dadd: masters x dim x nvar), nvar = dim (vars + 1): the
// positions of vars, then r_p.
struct MortarRows {
  std::vector<int> vars, masters;
  std::vector<double> w;
  int nvar = 0;
  double res[3] = {0, 0, 0};
  std::vector<double> dres, add, dadd;
};

using Facets = std::vector<MasterSurface::Facet>;

// Node j's (surface position) stencil from the couplings of its slave facets `faces`.
Stencil gather_stencil(int dim, int j, const std::vector<int>& faces, const Facets& slave, const Facets& master,
                       const std::vector<std::vector<FaceCoupling>>& cpl);
// n = -v / |v|, v the sum of the unit outward normals of its facets at node j (x: surface positions, 3 each).
std::array<Grad, 3> nodal_normal(Stencil& st, int j, const std::vector<int>& faces, const Facets& slave, const std::vector<double>& x);

// The mortar geometry of a node: weights w_k = M_k / S, the mortar master point xbar and
// the master motion over the step mbar = sum w_k (x_k - x_k,n) (x, xn: surface positions).
struct MortarPoint {
  Grad S;
  std::vector<Grad> w;
  std::array<Grad, 3> xbar, mbar;
};
MortarPoint mortar_point(Stencil& st, const std::vector<double>& x, const std::vector<double>& xn);

// The law (NodeLaw.hpp law()) in z = (x_p, n, xbar, mbar, r_p), chained to the node's
// unknowns: the rows of an active node into out (its vars/masters/w are set by the caller).
// Returns the state.
int mortar_law(int dim, const bool fixed[3], const double r[3], const LawParams& law, const double xp[3], const double xpn[3],
               const std::array<Grad, 3>& n, const MortarPoint& mp, std::size_t nv, MortarRows& out);

}  // namespace stentor::contact
