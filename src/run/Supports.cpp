#include "run/Supports.hpp"

#include <cmath>

#include "mesh/MeshQuery.hpp"

#include <algorithm>
#include <climits>
#include <numeric>

namespace stentor {

namespace {

int find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
  return i;
}

// Stored node (Mesh::stored_index) -> connected body (-1: in no body); `names`: the bodies
// of each connected body. Bodies sharing nodes are one; so are the two sides of a contact
// pair with a master surface (contact couples them, it does not hold them). On a rank's
// part of the mesh, a node shared by two bodies is seen with both by the ranks whose cells
// hold it (the ghost layer has every cell around it), and each rank sees only some of a
// contact pair's nodes: the links found are combined over the ranks. Collective.
std::vector<int> body_components(const Config& cfg, const Mesh& mesh, MPI_Comm comm, std::vector<std::vector<std::string>>& names) {
  const int nb = static_cast<int>(cfg.bodies.size());
  std::vector<int> parent(static_cast<std::size_t>(nb)), node_body(mesh.num_stored_nodes(), -1);
  std::iota(parent.begin(), parent.end(), 0);
  auto unite = [&](int a, int b) { parent[static_cast<std::size_t>(find(parent, a))] = find(parent, b); };
  for (int b = 0; b < nb; ++b)
    for (const auto& vb : mesh.volumes)
      if (vb.name == cfg.bodies[static_cast<std::size_t>(b)].group)
        for (GId g : vb.conn) {
          int& nbody = node_body[static_cast<std::size_t>(mesh.stored_index(g))];
          if (nbody < 0) nbody = b;
          else unite(b, nbody);
        }
  int nranks = 1;
  MPI_Comm_size(comm, &nranks);
  if (nranks > 1) {  // every rank's links on every rank
    std::vector<int> mine(static_cast<std::size_t>(nb)), all(static_cast<std::size_t>(nb) * static_cast<std::size_t>(nranks));
    for (int b = 0; b < nb; ++b) mine[static_cast<std::size_t>(b)] = find(parent, b);
    MPI_Allgather(mine.data(), nb, MPI_INT, all.data(), nb, MPI_INT, comm);
    for (std::size_t i = 0; i < all.size(); ++i) unite(static_cast<int>(i % static_cast<std::size_t>(nb)), all[i]);
  }
  for (const auto& c : cfg.contact) {
    if (c.master.empty()) continue;
    std::vector<int> seen(static_cast<std::size_t>(nb), 0), any(static_cast<std::size_t>(nb), 0);
    for (const std::string& grp : {c.slave, c.master})
      for (GId g : boundary_nodes(mesh, grp)) {
        const long long i = mesh.stored_index(g);
        if (i >= 0 && node_body[static_cast<std::size_t>(i)] >= 0) seen[static_cast<std::size_t>(node_body[static_cast<std::size_t>(i)])] = 1;
      }
    MPI_Allreduce(seen.data(), any.data(), nb, MPI_INT, MPI_MAX, comm);
    int first = -1;
    for (int b = 0; b < nb; ++b)
      if (any[static_cast<std::size_t>(b)]) {
        if (first < 0) first = b;
        else unite(b, first);
      }
  }
  names.assign(static_cast<std::size_t>(nb), {});
  for (int b = 0; b < nb; ++b) names[static_cast<std::size_t>(find(parent, b))].push_back(cfg.bodies[static_cast<std::size_t>(b)].name);
  for (int& nbody : node_body)
    if (nbody >= 0) nbody = find(parent, nbody);
  return node_body;
}

}  // namespace

int ConnectedBodies::body(const Mesh& mesh, GId g) const {
  const long long i = mesh.stored_index(g);
  return i < 0 ? -1 : body_of_node[static_cast<std::size_t>(i)];
}

std::string ConnectedBodies::who(std::size_t k) const {
  std::string w;
  for (const auto& n : names[k]) w += (w.empty() ? "'" : ", '") + n + "'";
  return "Bodies->" + w + (names[k].size() > 1 ? " (connected)" : "");
}

ConnectedBodies connected_bodies(const Config& cfg, const Mesh& mesh, const Loads& loads, MPI_Comm comm) {
  ConnectedBodies cb;
  cb.body_of_node = body_components(cfg, mesh, comm, cb.names);
  const std::size_t nb = cb.names.size();
  // Per connected body: prescribed directions, and the smallest and largest prescribed
  // node (more than one node when they differ), over the ranks.
  std::vector<int> held(3 * nb, 0);
  std::vector<long long> lo(nb, LLONG_MAX), hi(nb, LLONG_MIN);
  for (const auto& d : loads.dirichlet)
    for (GId g : d.nodes) {
      const int b = cb.body(mesh, g);
      if (b < 0) continue;
      const auto k = static_cast<std::size_t>(b);
      // A plane (`normal`) counts as holding the axes its normal has a part along, so a body
      // held by planes alone is not warned about when an axis is free; a free direction
      // oblique to the axes (a plane at 45 deg to x and y) is not reported at all.
      for (int c = 0; c < mesh.dim; ++c)
        if (d.normal ? std::abs(d.n[static_cast<std::size_t>(c)]) > 1e-6 : d.components[static_cast<std::size_t>(c)])
          held[3 * k + static_cast<std::size_t>(c)] = 1;
      lo[k] = std::min(lo[k], static_cast<long long>(g));
      hi[k] = std::max(hi[k], static_cast<long long>(g));
    }
  const int n = static_cast<int>(nb);
  MPI_Allreduce(MPI_IN_PLACE, held.data(), 3 * n, MPI_INT, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, lo.data(), n, MPI_LONG_LONG, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, hi.data(), n, MPI_LONG_LONG, MPI_MAX, comm);
  cb.held.assign(nb, {false, false, false});
  cb.several.assign(nb, 0);
  for (std::size_t k = 0; k < nb; ++k) {
    for (std::size_t c = 0; c < 3; ++c) cb.held[k][c] = held[3 * k + c] != 0;
    cb.several[k] = lo[k] < hi[k] ? 1 : 0;
  }
  return cb;
}

std::vector<std::string> unsupported_bodies(const Config& cfg, const Mesh& mesh, const Loads& loads, MPI_Comm comm) {
  std::vector<std::string> lines;
  if (!cfg.any_static() || cfg.bodies.empty()) return lines;
  const ConnectedBodies cb = connected_bodies(cfg, mesh, loads, comm);
  const std::size_t nb = cb.names.size();
  std::vector<int> contact(nb, 0);
  for (const auto& c : cfg.contact)  // a rigid obstacle may hold the body it touches
    if (c.master.empty())
      for (GId g : boundary_nodes(mesh, c.slave))
        if (cb.body(mesh, g) >= 0) contact[static_cast<std::size_t>(cb.body(mesh, g))] = 1;
  MPI_Allreduce(MPI_IN_PLACE, contact.data(), static_cast<int>(nb), MPI_INT, MPI_MAX, comm);
  for (std::size_t k = 0; k < nb; ++k) {
    if (cb.names[k].empty() || contact[k]) continue;
    // Axisymmetric: the only rigid motion is along the axis (y); r is held by the hoop stiffness.
    const bool axi = cfg.problem.axisymmetric();
    std::string free_dirs;
    for (int c = axi ? 1 : 0; c < mesh.dim; ++c)
      if (!cb.held[k][static_cast<std::size_t>(c)]) free_dirs += std::string(free_dirs.empty() ? "" : ", ") + "xyz"[c];
    const bool rotation = free_dirs.empty() && !cb.several[k] && !axi;
    if (free_dirs.empty() && !rotation) continue;
    lines.push_back("warning: static analysis: " + cb.who(k) + ": " +
                    (rotation ? std::string("every support is at one node, so the body can rotate about it")
                              : "no Dirichlet condition holds it in " + free_dirs + " and no rigid obstacle touches it") +
                    ": a free rigid-body motion makes the static tangent singular (add a support in 'Boundary Conditions', "
                    "or use Problem->analysis = dynamic)");
  }
  return lines;
}

}  // namespace stentor
