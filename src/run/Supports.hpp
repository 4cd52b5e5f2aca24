// Statics: rigid-body motions the supports leave free. A static analysis of a body that
// no Dirichlet condition holds in some direction (and that no rigid obstacle could hold)
// has a singular tangent: Newton then fails, or GMRES returns some solution of the
// singular system, with a free rigid motion in it. A cheap, conservative check of the
// deck against the mesh (no false positives on bodies held by contact):
//   - bodies that share nodes form one connected body, and so do the slave and master
//     sides of a contact pair with a master surface (contact couples, it does not hold);
//   - a connected body touched by a rigid obstacle pair is left alone: it may hold it;
//   - otherwise each direction x, y (, z) must be prescribed at some node of it, and the
//     prescribed nodes must not all be one node (which leaves the rotation free).
// A run checks the same bodies' unprescribed directions against each converged step's
// tangent, contact included (Stepper::free_translation), and stops when one is free.
#pragma once
#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "bc/Loads.hpp"
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Connected bodies as above, and where Dirichlet conditions hold each of them.
struct ConnectedBodies {
  std::vector<int> body_of_node;                // connected body of each stored mesh node (-1: in no body)
  std::vector<std::vector<std::string>> names;  // its bodies' names (empty: not a connected body's index)
  std::vector<std::array<bool, 3>> held;        // a Dirichlet condition prescribes direction c at some node
  std::vector<char> several;                    // the prescribed nodes are more than one node
  std::string who(std::size_t k) const;         // "Bodies->'a', 'b' (connected)"
  int body(const Mesh& mesh, GId g) const;      // of global node g (-1: in no body, or not stored here)
};
// Collective over comm (the ranks holding the parts of `mesh`).
ConnectedBodies connected_bodies(const Config& cfg, const Mesh& mesh, const Loads& loads, MPI_Comm comm);

// One warning line per connected body whose rigid motion is free, naming its bodies and
// the free directions; none for dynamic analyses.
std::vector<std::string> unsupported_bodies(const Config& cfg, const Mesh& mesh, const Loads& loads, MPI_Comm comm);

}  // namespace stentor
