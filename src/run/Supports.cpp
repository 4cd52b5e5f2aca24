#include "run/Supports.hpp"

#include "mesh/MeshQuery.hpp"

#include <algorithm>
#include <numeric>

namespace stentor {

namespace {

int find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
  return i;
}

// Node -> connected body (-1: in no body); `names`: the bodies of each connected body.
// Bodies sharing nodes are one; so are the two sides of a contact pair with a master
// surface (contact couples them, it does not hold them).
std::vector<int> body_components(const Config& cfg, const Mesh& mesh, std::vector<std::vector<std::string>>& names) {
  const int nb = static_cast<int>(cfg.bodies.size());
  std::vector<int> parent(static_cast<std::size_t>(nb)), node_body(mesh.num_nodes(), -1);
  std::iota(parent.begin(), parent.end(), 0);
  auto unite = [&](int a, int b) { parent[static_cast<std::size_t>(find(parent, a))] = find(parent, b); };
  for (int b = 0; b < nb; ++b)
    for (const auto& vb : mesh.volumes)
      if (vb.name == cfg.bodies[static_cast<std::size_t>(b)].group)
        for (GId g : vb.conn) {
          int& nbody = node_body[static_cast<std::size_t>(g)];
          if (nbody < 0) nbody = b;
          else unite(b, nbody);
        }
  for (const auto& c : cfg.contact) {
    if (c.master.empty()) continue;
    int first = -1;
    for (const std::string& grp : {c.slave, c.master})
      for (GId g : boundary_nodes(mesh, grp)) {
        const int b = node_body[static_cast<std::size_t>(g)];
        if (b < 0) continue;
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

std::string ConnectedBodies::who(std::size_t k) const {
  std::string w;
  for (const auto& n : names[k]) w += (w.empty() ? "'" : ", '") + n + "'";
  return "Bodies->" + w + (names[k].size() > 1 ? " (connected)" : "");
}

ConnectedBodies connected_bodies(const Config& cfg, const Mesh& mesh, const Loads& loads) {
  ConnectedBodies cb;
  cb.body_of_node = body_components(cfg, mesh, cb.names);
  const std::size_t nb = cb.names.size();
  cb.held.assign(nb, {false, false, false});
  cb.several.assign(nb, 0);
  std::vector<GId> first(nb, -1);
  for (const auto& d : loads.dirichlet)
    for (GId g : d.nodes) {
      const int b = cb.body_of_node[static_cast<std::size_t>(g)];
      if (b < 0) continue;
      const auto k = static_cast<std::size_t>(b);
      for (int c = 0; c < mesh.dim; ++c)
        cb.held[k][static_cast<std::size_t>(c)] = cb.held[k][static_cast<std::size_t>(c)] || d.components[static_cast<std::size_t>(c)];
      if (first[k] < 0) first[k] = g;
      else if (first[k] != g) cb.several[k] = 1;
    }
  return cb;
}

std::vector<std::string> unsupported_bodies(const Config& cfg, const Mesh& mesh, const Loads& loads) {
  std::vector<std::string> lines;
  if (!cfg.any_static() || cfg.bodies.empty()) return lines;
  const ConnectedBodies cb = connected_bodies(cfg, mesh, loads);
  const std::size_t nb = cb.names.size();
  std::vector<char> contact(nb, 0);
  for (const auto& c : cfg.contact)  // a rigid obstacle may hold the body it touches
    if (c.master.empty())
      for (GId g : boundary_nodes(mesh, c.slave))
        if (cb.body_of_node[static_cast<std::size_t>(g)] >= 0) contact[static_cast<std::size_t>(cb.body_of_node[static_cast<std::size_t>(g)])] = 1;
  for (std::size_t k = 0; k < nb; ++k) {
    if (cb.names[k].empty() || contact[k]) continue;
    std::string free_dirs;
    for (int c = 0; c < mesh.dim; ++c)
      if (!cb.held[k][static_cast<std::size_t>(c)]) free_dirs += std::string(free_dirs.empty() ? "" : ", ") + "xyz"[c];
    const bool rotation = free_dirs.empty() && !cb.several[k];
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
