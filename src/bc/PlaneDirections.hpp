// The constraint directions of a node on Dirichlet sets with `components` = normal (planes
// at any angle; assembly/PlaneConstraints.cpp, docs/deck.md). Trilinos-free: the assembler
// builds its rows from them, contact projects the reactions it sends to master nodes.
#pragma once
#include "bc/Loads.hpp"

namespace stentor {

struct PlaneDirections {
  int m = 0;              // constraint directions (0: the node is on no plane, or its planes add nothing)
  double e[3][3] = {};    // orthonormal, orthogonal to the node's Cartesian-prescribed axes
  int j[3] = {0, 0, 0};   // the free components whose rows carry e_i . du = 0
  int set[3] = {0, 0, 0}; // the set (index into Loads::dirichlet) of each direction
  double n[3][3] = {};    // ... and its plane's unit normal (all components)
};

// Node g on the `normal` sets in deck order: a plane parallel to an earlier one replaces it
// (the later set's value counts, as for Cartesian sets); each normal has the node's fixed
// components removed and the earlier directions subtracted (Gram-Schmidt), and adds a
// direction when more than 1e-6 of it is left. The rows j_i are the free components that
// maximise |det e_i(j_l)|.
PlaneDirections plane_directions(const Loads& loads, GId g, const bool fixed[3], int dim);

// v (dim values) less its parts along the directions e_i: its projection on the planes.
inline void project_on_planes(const PlaneDirections& p, int dim, double* v) {
  for (int i = 0; i < p.m; ++i) {
    double a = 0.0;
    for (int c = 0; c < dim; ++c) a += p.e[i][c] * v[c];
    for (int c = 0; c < dim; ++c) v[c] -= a * p.e[i][c];
  }
}

}  // namespace stentor
