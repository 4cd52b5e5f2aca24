#include "contact/Contact.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <TpetraExt_MatrixMatrix.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "bc/PlaneDirections.hpp"
#include "contact/MasterSurface.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "mesh/MeshQuery.hpp"
#include "mesh/SurfaceProjection.hpp"

namespace stentor {
namespace {

const char* kAxes[3] = {"x", "y", "z"};

using contact::dot3;

}  // namespace

std::unique_ptr<Contact> Contact::create(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler) {
  if (cfg.contact.empty()) return nullptr;
  return std::make_unique<Contact>(cfg, mesh, dist, assembler);
}

Contact::~Contact() = default;

Contact::Contact(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler)
    : dim_(mesh.dim), axi_(cfg.problem.axisymmetric()), end_time_(cfg.stepping.end_time), dist_(dist) {
  model_size_ = mesh.bounding_box().diagonal();
  gap_tol_ = 1e-12 * model_size_;
  mixed_analysis_ = cfg.any_dynamic() && cfg.any_static();
  dynamic_ = cfg.dynamic_in(0);

  // Master surfaces first: their nodes may not be slaves of a pair active with them.
  // Node sets below are sorted lists of the surfaces' nodes, not flags per mesh node: a
  // rank holds only its part of the mesh (mesh/Mesh.hpp).
  std::vector<GId> master_set;
  for (const auto& pc : cfg.contact) {
    Pair p;
    p.cfg = pc;
    if (!pc.master.empty()) {
      p.master = std::make_unique<MasterSurface>(mesh, pc.master, "'Contact->" + pc.name + "->master'");
      master_set.insert(master_set.end(), p.master->nodes().begin(), p.master->nodes().end());
      has_master_ = true;
    }
    linearised_ = linearised_ || pc.linearised_sets;
    pairs_.push_back(std::move(p));
  }
  // The surface whose positions ranks import (ContactGhosts.cpp: only the part near their
  // slave nodes): master nodes, and the slave nodes of mortar pairs (a mortar node's
  // conditions read its neighbours' positions).
  auto sort_unique = [](std::vector<GId>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  sort_unique(master_set);
  std::vector<GId> surface_set = master_set;
  for (auto& p : pairs_)
    if (p.master && p.cfg.discretization == "mortar") {
      p.mortar = true;
      p.slave_faces = std::make_unique<MasterSurface>(mesh, p.cfg.slave, "'Contact->" + p.cfg.name + "->slave'");
      surface_set.insert(surface_set.end(), p.slave_faces->nodes().begin(), p.slave_faces->nodes().end());
    }
  sort_unique(surface_set);
  std::multimap<GId, int> slave_of;
  for (std::size_t ip = 0; ip < pairs_.size(); ++ip) setup_slaves(ip, cfg, mesh, assembler, master_set, slave_of);
  if (has_master_) setup_master_maps(mesh, surface_set, assembler);
  for (auto& p : pairs_)
    if (p.mortar) setup_mortar(p);
  if (has_master_) {
    u_n_ = Teuchos::rcp(new la::Vector(dist.owned_map()));
    rebuild_ghosts(*u_n_);
  }
}

// Pair ip's slave nodes owned here (checks: the mesh dimension of an obstacle, a node in
// no other pair active with it, as a slave or on its master surface, at least one usable node over all ranks).
void Contact::setup_slaves(std::size_t ip, const Config& cfg, const Mesh& mesh, const Assembler& assembler, const std::vector<GId>& master_set,
                           std::multimap<GId, int>& slave_of) {
  const Distribution& dist = dist_;
  const auto& colmap = assembler.matrix()->getColMap();
  Pair& p = pairs_[ip];
  const ContactPairConfig& pc = p.cfg;
  const std::string where = "'Contact->" + pc.name + "'";
  if (p.master == nullptr) {
    if (pc.point_len != dim_)
      throw InputError(where + "->point must have " + std::to_string(dim_) + " values (the mesh is " + std::to_string(dim_) + "D)");
    if (pc.obstacle == "plane" && pc.normal_len != dim_)
      throw InputError(where + "->normal must have " + std::to_string(dim_) + " values (the mesh is " + std::to_string(dim_) + "D)");
    if (pc.obstacle == "circle" && dim_ != 2) throw InputError(where + "->obstacle = circle is 2D only; use cylinder or sphere in 3D");
    if ((pc.obstacle == "cylinder" || pc.obstacle == "sphere") && dim_ != 3)
      throw InputError(where + "->obstacle = " + pc.obstacle + " is 3D only; use circle in 2D");
  }
  p.persistence = pc.formulation == "persistence" || (pc.formulation == "auto" && cfg.dynamic_in(0));
  if (pc.formulation == "persistence" && !cfg.any_dynamic())  // static stages with the pair active: refused by the deck reader
    throw InputError(where + "->formulation = persistence needs a dynamic analysis ('Problem->analysis' = dynamic); use gap in statics");
  const std::vector<GId> nodes = boundary_nodes(mesh, pc.slave);  // throws InputError naming the group
  const auto areas = tributary_areas(mesh, pc.slave, axi_);
  // The slave surface's connected parts: only `Stepping->contact approach` reads them.
  const auto parts = cfg.stepping.contact_approach > 0.0 ? surface_parts(mesh, pc.slave) : std::map<GId, int>{};
  for (const auto& [g, part] : parts) p.parts = std::max(p.parts, part + 1);
  p.surface = std::make_unique<SurfaceProjection>(mesh, std::vector<std::string>{pc.slave}, axi_);
  long excluded = 0, partial = 0, planar = 0;
  for (GId g : nodes) {
    if (std::binary_search(master_set.begin(), master_set.end(), g)) {
      // A node may be a slave of one pair and a master node of another only when no stage
      // activates both (a stent's outer edge: the crimper's slave while crimping, the
      // balloon's master while expanding): an active slave's residual row is its condition,
      // which holds no other pair's reaction.
      std::string of;  // the pairs active with this one whose master surface holds the node
      for (std::size_t iq = 0; iq < pairs_.size(); ++iq) {
        const Pair& q = pairs_[iq];
        if (q.master && cfg.pairs_meet(ip, iq) && std::binary_search(q.master->nodes().begin(), q.master->nodes().end(), g))
          of += std::string(of.empty() ? "" : ", ") + "'Contact->" + q.cfg.name + "->master' = '" + q.cfg.master + "'";
      }
      if (!of.empty())
        throw InputError(where + "->slave: node " + std::to_string(g) + " of group '" + pc.slave + "' also lies on the master surface of " + of +
                         ", active in the same stage; a node may be a slave and a master node only of pairs that no stage "
                         "activates together (two-pass and self-contact are not implemented)");
    }
    // A node may be a slave of several pairs that no stage activates together (a stent's
    // outer surface: the crimper's slave while crimping, the lumen's while expanding); each
    // pair keeps its own state of the node, and an inactive pair leaves the node free.
    const auto [lo, hi] = slave_of.equal_range(g);
    for (auto at = lo; at != hi; ++at)
      if (cfg.pairs_meet(ip, static_cast<std::size_t>(at->second)))
        throw InputError(where + "->slave: node " + std::to_string(g) + " of group '" + pc.slave + "' is also a slave node of 'Contact->" +
                         pairs_[static_cast<std::size_t>(at->second)].cfg.name +
                         "', active in the same stage; a node may be a slave of several pairs only when no stage activates two of them");
    slave_of.emplace(g, static_cast<int>(ip));
    if (!dist.owns_node(g)) continue;
    const la::LO l = dist.local_node(g);
    Slave nd;
    int nfixed = 0;
    for (int c = 0; c < dim_; ++c) nfixed += nd.fixed[c] = assembler.is_dirichlet(l * dim_ + c);
    nd.planes = assembler.plane_normals(l, nd.e, nd.pj);
    planar += nd.planes > 0;
    if (nfixed == dim_) {
      ++excluded;
      continue;
    }
    partial += nfixed > 0;
    nd.lid = l;
    nd.gid = g;
    auto it = areas.find(g);
    nd.area = it == areas.end() ? 0.0 : it->second;
    const auto at = parts.find(g);
    nd.part = at == parts.end() ? -1 : at->second;
    const double r = mesh.coord(g)[0];
    nd.size = dim_ == 3 ? std::sqrt(nd.area) : axi_ ? (r > 1e-12 * model_size_ ? nd.area / (2.0 * M_PI * r) : 0.0) : nd.area;
    for (int c = 0; c < 3; ++c) nd.X[c] = mesh.coord(g)[c];
    for (int c = 0; c < dim_; ++c) nd.col[static_cast<std::size_t>(c)] = colmap->getLocalElement(static_cast<la::GO>(g) * dim_ + c);
    p.nodes.push_back(nd);
  }
  p.out.resize(p.nodes.size());
  Teuchos::reduceAll(*dist.comm(), Teuchos::REDUCE_SUM, 1, &excluded, &p.excluded);
  Teuchos::reduceAll(*dist.comm(), Teuchos::REDUCE_SUM, 1, &partial, &p.partial);
  long planar_all = 0;
  Teuchos::reduceAll(*dist.comm(), Teuchos::REDUCE_SUM, 1, &planar, &planar_all);
  if (planar_all > 0 && p.master && pc.discretization == "mortar")
    throw InputError(where + "->slave: " + std::to_string(planar_all) + " nodes of group '" + pc.slave +
                     "' slide on a plane of a Dirichlet set with components 'normal', which dual mortar contact does not "
                     "implement; use 'discretization' = node-to-segment for this pair, or Cartesian components");
  long mine = static_cast<long>(p.nodes.size()), usable = 0;
  Teuchos::reduceAll(*dist.comm(), Teuchos::REDUCE_SUM, 1, &mine, &usable);
  if (usable == 0)
    throw InputError(where + "->slave: none of the " + std::to_string(nodes.size()) + " nodes of group '" + pc.slave +
                     "' can touch anything: every one has all its components prescribed by a Dirichlet condition");
}

// Master nodes on `normal` Dirichlet planes (the groups are read whole, so every rank finds
// the same directions): the reactions sent to them are projected on their planes, and the
// rows that carry the planes' constraints take none (bc/PlaneDirections.hpp).
void Contact::setup_master_planes(const Assembler& assembler) {
  Loads planes;
  for (const auto& d : assembler.dirichlet_sets())
    if (d.normal) planes.dirichlet.push_back(d);
  for (const auto& p : pairs_)
    if (p.mortar)
      for (GId g : p.master->nodes())
        for (const auto& d : planes.dirichlet)
          if (std::binary_search(d.nodes.begin(), d.nodes.end(), g))
            throw InputError("'Contact->" + p.cfg.name + "->master': node " + std::to_string(g) + " lies on group '" + d.group +
                             "' ('Boundary Conditions->" + d.name + "->components' = normal), which dual mortar contact does "
                             "not implement; use 'discretization' = node-to-segment for this pair, or Cartesian components");
  for (std::size_t pos = 0; pos < master_nodes_.size(); ++pos) {
    bool fixed[3] = {false, false, false};
    for (int c = 0; c < dim_; ++c) fixed[c] = master_fixed_[pos * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(c)] != 0;
    const PlaneDirections d = plane_directions(planes, master_nodes_[pos], fixed, dim_);
    if (d.m == 0) continue;
    master_plane_[static_cast<int>(pos)] = d;
    for (int i = 0; i < d.m; ++i) master_fixed_[pos * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(d.j[i])] = 1;
  }
}

void Contact::project_on_master_planes(int pos, double* v) const {
  const auto it = master_plane_.find(pos);
  if (it != master_plane_.end()) project_on_planes(it->second, dim_, v);
}

// The surface nodes' numbering (master_pos), reference positions, prescribed dofs,
// tributary areas and the ghosting margin; rebuild_ghosts() makes the import/export.
void Contact::setup_master_maps(const Mesh& mesh, const std::vector<GId>& surface_set, const Assembler& assembler) {
  const Distribution& dist = dist_;

  master_nodes_ = surface_set;  // sorted: master_pos() searches it
  for (GId g : master_nodes_)
    for (int c = 0; c < 3; ++c) master_X_.push_back(mesh.coord(g)[c]);
  for (auto& p : pairs_)
    if (p.master) p.master->index([this](GId g) { return master_pos(g); });
  // Prescribed master dofs keep their identity rows: the reaction goes to the support.
  master_fixed_.assign(master_nodes_.size() * static_cast<std::size_t>(dim_), 0);
  bool on_plane = false;
  for (const auto& d : assembler.dirichlet_sets())
    for (GId g : d.nodes) {
      const int pos = master_pos(g);
      if (pos < 0) continue;
      if (d.normal) {
        on_plane = true;
        continue;
      }
      for (int c = 0; c < dim_; ++c)
        if (d.components[static_cast<std::size_t>(c)]) master_fixed_[static_cast<std::size_t>(pos * dim_ + c)] = 1;
    }
  {  // a rank's part of the mesh has of a Dirichlet group only the facets near its cells
    std::vector<int> mine(master_fixed_.begin(), master_fixed_.end()), any(mine.size(), 0);
    Teuchos::reduceAll(*dist.comm(), Teuchos::REDUCE_MAX, static_cast<int>(mine.size()), mine.data(), any.data());
    for (std::size_t k = 0; k < any.size(); ++k) master_fixed_[k] = static_cast<char>(any[k]);
  }
  if (on_plane) setup_master_planes(assembler);
  master_x_ = master_X_;
  master_xn_ = master_X_;
  double h = 0.0;
  for (const auto& p : pairs_) {
    if (p.master) h = std::max(h, p.master->size());
    if (p.slave_faces) h = std::max(h, p.slave_faces->size());
  }
  ghost_margin_ = 8.0 * h;
  master_area_.assign(master_nodes_.size(), 0.0);
  for (const auto& p : pairs_)
    if (p.master)
      for (const auto& [g, a] : tributary_areas(mesh, p.cfg.master, axi_)) {
        const int pos = master_pos(g);
        if (pos >= 0) master_area_[static_cast<std::size_t>(pos)] = a;
      }
}


int Contact::master_pos(GId g) const {
  const auto it = std::lower_bound(master_nodes_.begin(), master_nodes_.end(), g);
  return it != master_nodes_.end() && *it == g ? static_cast<int>(it - master_nodes_.begin()) : -1;
}

std::string Contact::description() const {
  std::ostringstream os;
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    const auto& p = pairs_[i];
    long loc = static_cast<long>(p.nodes.size()), glob = 0;
    Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &loc, &glob);
    os << (i ? "\n           " : "") << p.cfg.name << ": " << glob << " nodes of '" << p.cfg.slave << "' vs ";
    if (p.master)
      os << "master surface '" << p.cfg.master << "' (" << p.master->facets().size() << " facets, "
         << (p.mortar ? "dual mortar" : "node-to-segment") << ")";
    else
      os << p.cfg.obstacle;
    if (mixed_analysis_ && p.cfg.formulation == "auto")
      os << ", persistence (leapfrog) in dynamic stages, gap in static ones";
    else
      os << ", " << (p.persistence ? "persistence (leapfrog)" : "gap");
    os << ", mu " << p.cfg.friction;
    if (p.excluded) os << " (" << p.excluded << " slave nodes with every component prescribed left out)";
    if (p.partial) os << " (" << p.partial << " slave nodes with some prescribed components: contact on the free ones)";
  }
  if (has_master_) {
    // Surface ghosting: how many surface nodes each rank imports (rebuild_ghosts).
    long loc = static_cast<long>(ghost_pos_.size()), lo = 0, hi = 0;
    Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MIN, 1, &loc, &lo);
    Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 1, &loc, &hi);
    os << "\n           surface: " << master_nodes_.size() << " nodes; each rank imports those near its slave nodes: " << lo << " to " << hi;
  }
  return os.str();
}

std::array<double, 3> Contact::translation(const Pair& p, double t) const {
  const double f = p.cfg.translation_ramp(t, end_time_);
  return {p.cfg.translation[0] * f, p.cfg.translation[1] * f, p.cfg.translation[2] * f};
}

contact::Obstacle Contact::obstacle(const Pair& p, double t) const {
  contact::Obstacle o;
  const auto& c = p.cfg;
  o.kind = c.obstacle == "plane" ? 0 : c.obstacle == "cylinder" ? 2 : c.obstacle == "capsule" ? 3 : 1;
  o.length = c.length;
  const auto w = translation(p, t), w0 = translation(p, t0_);
  for (int k = 0; k < 3; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    o.point[k] = c.point[kk] + w[kk];
    o.normal[k] = c.normal[kk];
    o.axis[k] = c.axis[kk];
    o.dw[k] = w[kk] - w0[kk];
  }
  o.radius = c.radius + c.radius_change * c.radius_ramp(t, end_time_);
  o.inside = c.side == "inside";
  return o;
}

std::vector<contact::Obstacle> Contact::rigid_obstacles(double t) const {
  std::vector<contact::Obstacle> out;
  for (const auto& p : pairs_)
    if (!p.master) out.push_back(obstacle(p, t));
  return out;
}

void Contact::initialize(const la::Vector& u0, double end_time, const la::Vector* v0, double dt0) {
  end_time_ = end_time;
  t0_ = t1_ = 0.0;
  if (has_master_) {
    u_n_->assign(u0);
    rebuild_ghosts(u0);
    update_master_positions(u0, master_x_);
    master_xn_ = master_x_;
  }
  auto uh = u0.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (auto& p : pairs_) {
    if (p.mortar) {
      mortar_geometry(p);
      for (auto& nd : p.nodes) nd.d_n = nd.d_prev = nd.gap;
      continue;
    }
    if (p.master) p.master->build(master_x_, &present_);
    const contact::Obstacle ob = obstacle(p, 0.0);
    for (auto& nd : p.nodes) {
      double x[3] = {nd.X[0], nd.X[1], nd.X[2]};
      for (int c = 0; c < dim_; ++c) x[c] += uh(nd.lid * dim_ + c, 0);
      double n[3];
      if (p.master) {
        locate(p, nd, x);
        double rel[3];
        nd.d_n = facet_gap(p, nd, x, n, rel);
        for (int c = 0; c < 3; ++c) nd.normal[c] = nd.facet >= 0 ? n[c] : 0.0;
      } else {
        nd.d_n = contact::rigid_gap(ob, x, n);
      }
      nd.d_prev = nd.d_n;
      nd.gap = nd.d_n;
    }
  }
  if (v0 && dt0 > 0.0) initial_gap_rates(u0, *v0, dt0);
}

// The first step's leapfrog test d_0 + dt/2 (d_0 - d_-1) then sees the initial motion:
// d_-1 = d_0 - dt0 ddot_0 with the gap rate from the initial velocities (rigid obstacles:
// the gap of x_0 + dt0 v_0 against the obstacle at dt0, minus d_0; master surfaces: the
// normal relative velocity n . (v_p - sum_a N_a v_a), mortar: with the weights w_pk).
// Without it a body thrown from close by was free in the first step whatever its speed,
// and crossed the obstacle in that step (docs/studies/README.md, S2 stability map).
void Contact::initial_gap_rates(const la::Vector& u0, const la::Vector& v0, double dt0) {
  auto uh = u0.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto vh = v0.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> vm;  // surface node velocities (3 each)
  if (has_master_) {
    master_u_->doImport(v0, *master_import_, Tpetra::INSERT);
    auto mh = master_u_->getLocalViewHost(Tpetra::Access::ReadOnly);
    vm.assign(master_x_.size(), 0.0);
    for (std::size_t i = 0; i < ghost_pos_.size(); ++i)
      for (int c = 0; c < dim_; ++c)
        vm[3 * static_cast<std::size_t>(ghost_pos_[i]) + static_cast<std::size_t>(c)] = mh(i * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(c), 0);
  }
  for (std::size_t ip = 0; ip < pairs_.size(); ++ip) {
    Pair& p = pairs_[ip];
    const contact::Obstacle ob1 = obstacle(p, dt0);
    for (std::size_t i = 0; i < p.nodes.size(); ++i) {
      Slave& nd = p.nodes[i];
      double v[3] = {0, 0, 0}, vbar[3] = {0, 0, 0};
      for (int c = 0; c < dim_; ++c) v[c] = vh(nd.lid * dim_ + c, 0);
      double rate = 0.0;
      if (!p.master) {
        double x1[3] = {nd.X[0], nd.X[1], nd.X[2]}, n[3];
        for (int c = 0; c < dim_; ++c) x1[c] += uh(nd.lid * dim_ + c, 0) + dt0 * v[c];
        rate = (contact::rigid_gap(ob1, x1, n) - nd.d_n) / dt0;
      } else if (p.mortar) {
        const contact::MortarRows& mo = p.mortar_out[i];
        if (mo.masters.empty()) continue;
        for (std::size_t k = 0; k < mo.masters.size(); ++k)
          for (int c = 0; c < 3; ++c) vbar[c] += mo.w[k] * vm[3 * static_cast<std::size_t>(mo.masters[k]) + static_cast<std::size_t>(c)];
        rate = dot3(nd.normal, v) - dot3(nd.normal, vbar);
      } else {
        if (nd.facet < 0) continue;
        const auto& fc = p.master->facets()[static_cast<std::size_t>(nd.facet)];
        double N[facet::kMaxNodes], dN[facet::kMaxNodes][2];
        facet::shape(fc.type, nd.xi, N, dN);
        for (int a = 0; a < fc.nn; ++a)
          for (int c = 0; c < 3; ++c) vbar[c] += N[a] * vm[3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(c)];
        rate = dot3(nd.normal, v) - dot3(nd.normal, vbar);
      }
      nd.d_prev = nd.d_n - dt0 * rate;
    }
  }
}

std::vector<std::string> Contact::initial_penetrations() const {
  std::vector<std::string> lines;
  const double tol = 1e-6 * model_size_;
  for (const auto& p : pairs_) {
    double loc[2] = {0.0, 0.0}, glob[2] = {0.0, 0.0};  // count, deepest (as a positive depth)
    for (const auto& nd : p.nodes)
      if (nd.d_n < -tol) {
        loc[0] += 1.0;
        loc[1] = std::max(loc[1], -nd.d_n);
      }
    Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &loc[0], &glob[0]);
    Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 1, &loc[1], &glob[1]);
    if (glob[0] == 0.0) continue;
    std::ostringstream os;
    os << "warning: Contact->" << p.cfg.name << ": " << static_cast<long>(glob[0]) << " slave node(s) start inside the "
       << (p.master ? "master surface '" + p.cfg.master + "'" : "obstacle") << ", the deepest by " << std::setprecision(3)
       << glob[1] << " (tolerance " << tol << " = 1e-6 of the model size); contact pushes them out in the first steps "
       << "(check the geometry, 'point' or the initial displacement)";
    lines.push_back(os.str());
  }
  return lines;
}

Contact::NodalFields Contact::step_history(std::size_t pair) const {
  NodalFields h;
  for (const auto& nd : pairs_[pair].nodes) {
    h.nodes.push_back(nd.gid);
    h.values.insert(h.values.end(), {nd.d_n, nd.d_prev, nd.was_active ? 1.0 : 0.0, double(nd.prev_state), double(nd.prev_facet), nd.scale,
                                         double(nd.facet), nd.inside ? 1.0 : 0.0});
  }
  return h;
}

long Contact::restore_step_history(std::size_t pair, const NodalFields& sorted) {
  long missing = 0;
  for (auto& nd : pairs_[pair].nodes) {
    const auto it = std::lower_bound(sorted.nodes.begin(), sorted.nodes.end(), static_cast<long long>(nd.gid));
    if (it == sorted.nodes.end() || *it != nd.gid) {
      ++missing;
      continue;
    }
    const double* v = &sorted.values[static_cast<std::size_t>(it - sorted.nodes.begin()) * kHistoryValues];
    nd.d_n = v[0];
    nd.d_prev = v[1];
    nd.was_active = v[2] != 0.0;
    nd.state = nd.prev_state = static_cast<int>(v[3]);
    nd.prev_facet = static_cast<int>(v[4]);
    nd.scale = v[5];
    nd.facet = static_cast<int>(v[6]);
    nd.inside = v[7] != 0.0;  // the facet hysteresis (keep_facet) reads it
  }
  return missing;
}

void Contact::set_active_pairs(const std::vector<bool>& active) {
  for (std::size_t i = 0; i < pairs_.size() && i < active.size(); ++i) pairs_[i].active = active[i];
}

void Contact::set_analysis(bool dynamic) {
  dynamic_ = dynamic;
  for (auto& p : pairs_)
    if (p.cfg.formulation == "auto") p.persistence = dynamic;
}

void Contact::begin_step(double t_n, double dt, const la::Vector& u_n) {
  t0_ = t_n;
  t1_ = t_n + dt;
  dt_ = dt;
  alpha_ = 1.0;
  for (auto& p : pairs_)
    for (auto& nd : p.nodes) {
      nd.lam_valid = false;  // the step's first iterate decides from r
      nd.normal_flips = nd.tangent_flips = 0;
      nd.hold_active = nd.hold_inactive = false;
      nd.hold_revisions = 0;
      nd.hold_tangent = 0;
      nd.solve_facet = -1;
      nd.facet_flips = 0;
      nd.hold_facet = -1;
    }
  if (has_master_) {
    u_n_->assign(u_n);
    rebuild_ghosts(u_n);
    update_master_positions(u_n, master_xn_);
    master_x_ = master_xn_;
  }
  auto uh = u_n.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (auto& p : pairs_)
    for (auto& nd : p.nodes)
      for (int c = 0; c < 3; ++c) nd.x_n[c] = nd.X[c] + (c < dim_ ? uh(nd.lid * dim_ + c, 0) : 0.0);
}

// The closest facet of the pair's master surface to x (current positions), recorded in nd
// (facet -1: none within the search radius). Thread-safe for distinct nodes.
void Contact::locate(const Pair& p, Slave& nd, const double* x) const {
  const auto hit = p.master->closest(dim_, x, master_x_);
  nd.facet = hit.facet;
  nd.xi[0] = hit.xi[0], nd.xi[1] = hit.xi[1];
  nd.xi_free[0] = hit.xi_free[0], nd.xi_free[1] = hit.xi_free[1];
  nd.inside = hit.inside;
}

// Facet hysteresis: a node active at the last evaluation with its projection inside its
// facet keeps that facet while the projection stays on it or past its edge by at most
// kFacetBand (parametric; the facet extended). A node that was held at a facet's end
// (clamped) looks again, as before: switching it to the extended facet would change its
// conditions (xi fixed vs moving) between evaluations. Where the
// master surface has a kink (a vertex between two line2 facets, an edge in 3D) the closest
// facet of a node sitting on the vertex flips between Newton iterates, and with it the
// normal: the iteration then cycles (measured: Hertz between two cylinders with a slave node
// over a master vertex, |r| cycling 4.0e-7 -> 2.1e-7 -> 1.0e-7 -> 4.0e-7 for 40 iterations;
// docs/contact.md, Hertz). Keeping the facet over a small overlap makes the choice
// piecewise constant along the iteration; the gap against the extended facet differs from
// the neighbour's by O(band^2 h^2 kappa).
bool Contact::keep_facet(const Pair& p, Slave& nd, const double* x) const {
  if (nd.prev_state < contact::Stick || nd.facet < 0 || !nd.inside) return false;
  const auto hit = p.master->on_facet(nd.facet, dim_, x, master_x_, kFacetBand);
  if (hit.facet < 0) return false;
  nd.xi[0] = nd.xi_free[0] = hit.xi[0], nd.xi[1] = nd.xi_free[1] = hit.xi[1];
  nd.inside = true;
  return true;
}

bool Contact::hold_facet_projection(const Pair& p, Slave& nd, const double* x) const {
  if (nd.hold_facet == -2) {  // revised: held on its closest facet from now on
    locate(p, nd, x);
    nd.hold_facet = nd.facet;
    if (nd.facet < 0) return false;
  }
  const auto hit = p.master->on_facet(nd.hold_facet, dim_, x, master_x_, kHoldReach);
  if (hit.facet < 0) {
    nd.hold_facet = -1;
    return false;
  }
  nd.hold_in_band = p.master->on_facet(nd.hold_facet, dim_, x, master_x_, kHoldBand).facet >= 0;
  nd.facet = hit.facet;
  nd.xi[0] = nd.xi_free[0] = hit.xi[0], nd.xi[1] = nd.xi_free[1] = hit.xi[1];
  nd.inside = true;
  return true;
}

// Gap, normal and relative displacement of slave node nd at x against its facet (double);
// the search radius when it has none.
double Contact::facet_gap(const Pair& p, const Slave& nd, const double* x, double* n, double* rel) const {
  if (nd.facet < 0) return p.master->search_radius();
  contact::NodeInput in;
  node_input(p, nd, x, in);
  double N[facet::kMaxNodes], a1[3];
  return contact::geometry(in, nullptr, in.xs, in.xa, n, rel, N, a1);
}

void Contact::node_input(const Pair& p, const Slave& nd, const double* x, contact::NodeInput& in) const {
  in.dim = dim_;
  for (int c = 0; c < 3; ++c) {
    in.xs[c] = x[c];
    in.xs_n[c] = nd.x_n[c];
    in.r[c] = nd.f[c];
  }
  in.d_n = nd.d_n;
  for (int c = 0; c < 3; ++c) in.fixed[c] = nd.fixed[c];
  if (!p.master) return;
  const auto& fc = p.master->facets()[static_cast<std::size_t>(nd.facet)];
  in.nm = fc.nn;
  in.facet = fc.type;
  in.orient = fc.orient;
  in.xi[0] = nd.xi[0], in.xi[1] = nd.xi[1];
  in.xi_free[0] = nd.xi_free[0], in.xi_free[1] = nd.xi_free[1];
  in.xi_inside = nd.inside;
  for (int a = 0; a < fc.nn; ++a)
    for (int c = 0; c < 3; ++c) {
      const auto k = 3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(c);
      in.xa[a][c] = master_x_[k];
      in.xa_n[a][c] = master_xn_[k];
    }
}

// c_tau of a node: the deck's value per unit area times the node's tributary area, or
// automatic, the node's stiffness scale times dt.
double Contact::tangent_penalty(const Pair& p, const Slave& nd, double dt) {
  const double area = nd.area > 0.0 ? nd.area : 1.0;
  return p.cfg.c_tangent > 0.0 ? p.cfg.c_tangent * area : nd.scale * dt;
}

contact::LawParams Contact::node_params(const Pair& p, const Slave& nd, const contact::LawParams& lp) const {
  contact::LawParams q = lp;
  q.sp = nd.scale;
  if (nd.prev_state < contact::Stick) q.release = 0.0;
  // Deck values are per unit area (the multipliers then compare as pressures, so one
  // c has one meaning on every mesh); automatic: the node's stiffness scale.
  const double area = nd.area > 0.0 ? nd.area : 1.0;
  q.cn = p.cfg.c_normal > 0.0 ? p.cfg.c_normal * area : nd.scale * (p.persistence ? lp.dt : 1.0);
  q.ct = tangent_penalty(p, nd, lp.dt);
  q.planes = nd.planes;
  for (int i = 0; i < 3; ++i) {
    q.pj[i] = nd.pj[i];
    for (int c = 0; c < 3; ++c) q.e[i][c] = nd.e[i][c];
  }
  q.force_active = nd.hold_active;
  q.force_inactive = nd.hold_inactive;
  q.force_tangent = nd.hold_tangent;
  if (nd.hold_tangent == contact::Slip) {
    q.has_slip_dir = true;
    for (int c = 0; c < 3; ++c) q.slip_dir[c] = nd.hold_dir[c];
  }
  if (nd.lam_valid) {
    q.has_lam = true;
    const bool active = nd.base_state >= contact::Stick;
    for (int c = 0; c < 3; ++c) q.lam[c] = active && !nd.fixed[c] ? nd.lam_base[c] + alpha_ * nd.kdu[c] : 0.0;
    if (active && nd.planes > 0) contact::complete_on_planes(q, q.lam);
    q.base = nd.base_state;
  }
  return q;
}

// The bulk tangent rows of the slave dofs of every pair that decides its sets from the
// last linear solve, before the contact rows replace them (linearised_step reads them).
void Contact::capture_rows(const la::RCP<la::CrsMatrix>& K) {
  rows_of_ = K;
  auto Kl = K->getLocalMatrixHost();
  for (auto& p : pairs_) {
    p.krow_ptr.assign(1, 0);
    p.krow_col.clear();
    p.krow_val.clear();
    if (!p.cfg.linearised_sets) continue;
    for (const auto& nd : p.nodes)
      for (int c = 0; c < dim_; ++c) {
        const la::LO row = nd.lid * dim_ + c;
        for (auto k = Kl.graph.row_map(row); k < Kl.graph.row_map(row + 1); ++k) {
          p.krow_col.push_back(Kl.graph.entries(k));
          p.krow_val.push_back(Kl.values(k));
        }
        p.krow_ptr.push_back(p.krow_col.size());
      }
  }
}

void Contact::linearised_step(const la::Vector& du) {
  if (!linearised_ || rows_of_.is_null()) return;
  la::Vector du_col(rows_of_->getColMap());
  const auto importer = rows_of_->getGraph()->getImporter();
  if (importer.is_null())
    du_col.assign(du);
  else
    du_col.doImport(du, *importer, Tpetra::INSERT);
  alpha_ = 1.0;
  auto dh = du_col.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (auto& p : pairs_) {
    if (!p.cfg.linearised_sets || p.krow_ptr.size() != p.nodes.size() * static_cast<std::size_t>(dim_) + 1) continue;
    for (std::size_t i = 0; i < p.nodes.size(); ++i) {
      Slave& nd = p.nodes[i];
      if (nd.lam_valid) count_flips(p, nd);
      nd.lam_valid = true;
      nd.base_state = nd.state;  // the set of the solve: the last apply()'s
      for (int c = 0; c < 3; ++c) nd.lam_base[c] = nd.f[c], nd.kdu[c] = 0.0;
      for (int c = 0; c < dim_; ++c) {
        const std::size_t row = i * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(c);
        double v = 0.0;
        for (std::size_t k = p.krow_ptr[row]; k < p.krow_ptr[row + 1]; ++k) v += p.krow_val[k] * dh(p.krow_col[k], 0);
        nd.kdu[c] = v;
      }
    }
  }
}

// s_p: the largest tangent diagonal entry of the node's dofs (a force/length scale).
void Contact::read_scales(const la::CrsMatrix& K) {
  auto Kl = K.getLocalMatrixHost();
  for (auto& p : pairs_)
    for (auto& nd : p.nodes) {
      double s = 0.0;
      for (int c = 0; c < dim_; ++c) {
        const la::LO row = nd.lid * dim_ + c;
        for (auto k = Kl.graph.row_map(row); k < Kl.graph.row_map(row + 1); ++k)
          if (Kl.graph.entries(k) == nd.col[static_cast<std::size_t>(c)]) s = std::max(s, std::abs(Kl.values(k)));
      }
      if (s > 0.0) nd.scale = s;
    }
}

// Per slave node (one Kokkos kernel per pair): leapfrog test, closest facet, the node's
// conditions and their derivatives; active nodes' residual rows are replaced in place.
void Contact::evaluate_nodes(const la::Vector& u, la::Vector& r) {
  static_assert(Kokkos::SpaceAccessibility<la::ExecSpace, Kokkos::HostSpace>::accessible,
                "contact kernels read host-side node records");
  const int dim = dim_;
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto rh = r.getLocalViewHost(Tpetra::Access::ReadWrite);
  if (has_master_) {
    if (ghosts_outrun(u)) {  // a node moved far within the step: import the surface near it now
      rebuild_ghosts(u);
      update_master_positions(*u_n_, master_xn_);
    }
    update_master_positions(u, master_x_);
  }
  for (auto& p : pairs_) {
    if (!p.active) {
      for (std::size_t i = 0; i < p.nodes.size(); ++i) p.nodes[i].state = p.out[i].state = contact::Free;
      continue;
    }
    if (p.master) p.master->build(master_x_, &present_);
    const contact::Obstacle ob = obstacle(p, t1_);
    contact::LawParams lp;
    lp.persistence = p.persistence;
    lp.dt = dt_;
    lp.mu = p.cfg.friction;
    {
      // Release hysteresis: a node active at the last evaluation stays active while
      // lambda_nu + c_nu g <= 1e-8 max_p |r_p| (the pair's largest bulk residual entry at a slave
      // node: its largest nodal contact force once converged), not only while it is <= 0. A node
      // whose multiplier is zero in exact arithmetic at zero gap (the corner nodes of tri6 slave
      // facets under a uniform pressure: their consistent nodal force is 0) otherwise flips
      // between active and inactive on round-off at every iterate once Newton has converged, and
      // the active set never settles (measured: the tet10 patch test, 37..46 of 49 nodes active,
      // |r| at 3e-10 below its target for 25 iterations). Stateless and reduced over all ranks:
      // restarts and partitions see the same value.
      double loc = 0.0, glob = 0.0;
      for (const auto& nd : p.nodes)
        for (int c = 0; c < dim; ++c) loc = std::max(loc, std::abs(rh(nd.lid * dim + c, 0)));
      Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 1, &loc, &glob);
      lp.release = 1e-8 * glob;
    }
    const double lf = dt_last_ > 0.0 ? 0.5 * dt_ / dt_last_ : 0.5;
    if (p.mortar) {
      evaluate_mortar(p, lp, lf, uh.data(), rh.data());
      continue;
    }
    const Contact* self = this;
    Slave* nodes = p.nodes.data();
    contact::NodeOutput* outs = p.out.data();
    const Pair* pp = &p;
    const contact::Obstacle* obp = &ob;
    const double gap_tol = gap_tol_;
    Kokkos::parallel_for(
        "stentor::contact_nodes", Kokkos::RangePolicy<la::ExecSpace>(0, p.nodes.size()), [=](const std::size_t i) {
          Slave& nd = nodes[i];
          contact::NodeOutput& o = outs[i];
          double x[3] = {nd.X[0], nd.X[1], nd.X[2]};
          for (int c = 0; c < dim; ++c) {
            x[c] += uh(nd.lid * dim + c, 0);
            nd.f[c] = rh(nd.lid * dim + c, 0);
          }
          nd.state = o.state = contact::Free;
          // Leapfrog: free this step, unless the node ended the last step in contact (then
          // the persistence condition itself decides whether it separates).
          if (pp->persistence && !nd.was_active && nd.d_n + lf * (nd.d_n - nd.d_prev) > gap_tol) return;
          if (pp->master) {
            if (!(nd.hold_facet != -1 && self->hold_facet_projection(*pp, nd, x)) && !keep_facet(*pp, nd, x)) locate(*pp, nd, x);
            if (nd.facet < 0) return;
          }
          contact::NodeInput in;
          node_input(*pp, nd, x, in);
          contact::evaluate(in, self->node_params(*pp, nd, lp), obp, o);
          nd.state = o.state;
          nd.gap = o.gap;
          for (int c = 0; c < 3; ++c) nd.normal[c] = o.normal[c], nd.rel[c] = o.rel[c];
          if (o.state >= contact::Stick)
            for (int c = 0; c < dim; ++c)
              if (!nd.fixed[c]) rh(nd.lid * dim + c, 0) = o.res[c];
        });
    Kokkos::fence();
  }
}

// Master rows: r_a += N_a r_p for every active node touching a facet (prescribed master
// dofs excepted), summed across ranks.
void Contact::send_reactions(la::Vector& r) {
  if (!has_master_) return;
  master_r_->putScalar(0.0);
  {
    auto mh = master_r_->getLocalViewHost(Tpetra::Access::ReadWrite);
    for (const auto& p : pairs_) {
      if (!p.master) continue;
      for (std::size_t i = 0; i < p.nodes.size(); ++i) {
        const Slave& nd = p.nodes[i];
        if (nd.state < contact::Stick) continue;
        if (p.mortar) {
          const contact::MortarRows& mo = p.mortar_out[i];
          for (std::size_t k = 0; k < mo.masters.size(); ++k)
            for (int c = 0; c < dim_; ++c) {
              const auto kk = static_cast<std::size_t>(mo.masters[k] * dim_ + c);
              const auto gi = static_cast<std::size_t>(ghost_index_[static_cast<std::size_t>(mo.masters[k])] * dim_ + c);
              if (!master_fixed_[kk]) mh(gi, 0) += mo.add[k * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(c)];
            }
          continue;
        }
        const auto& fc = p.master->facets()[static_cast<std::size_t>(nd.facet)];
        for (int a = 0; a < fc.nn; ++a) {
          double add[3] = {p.out[i].add[a][0], p.out[i].add[a][1], p.out[i].add[a][2]};
          project_on_master_planes(fc.node[a], add);
          for (int c = 0; c < dim_; ++c) {
            const auto k = static_cast<std::size_t>(fc.node[a] * dim_ + c);
            const auto gi = static_cast<std::size_t>(ghost_index_[static_cast<std::size_t>(fc.node[a])] * dim_ + c);
            if (!master_fixed_[k]) mh(gi, 0) += add[c];
          }
        }
      }
    }
  }
  r.doExport(*master_r_, *master_export_, Tpetra::ADD_ASSIGN);  // ADD would replace owned entries
}

// Rigid obstacles: the node's new rows are combinations of its own bulk rows plus terms
// on its own columns, all inside the static graph: rewritten in place, one node per
// kernel iteration.
void Contact::rewrite_rigid_rows(la::CrsMatrix& K) {
  using LocalMatrix = la::CrsMatrix::local_matrix_device_type;
  LocalMatrix Kl = K.getLocalMatrixDevice();
  Kokkos::View<int, la::ExecSpace> bad_pattern("contact_bad_pattern");
  const int dim = dim_;
  for (auto& p : pairs_) {
    if (p.master) continue;
    Slave* nodes = p.nodes.data();
    const contact::NodeOutput* outs = p.out.data();
    Kokkos::parallel_for(
        "stentor::contact_rigid_rows", Kokkos::RangePolicy<la::ExecSpace>(0, p.nodes.size()), KOKKOS_LAMBDA(const std::size_t i) {
          const Slave& nd = nodes[i];
          if (nd.state < contact::Stick) return;
          const contact::NodeOutput& o = outs[i];
          // The node's dim rows share one column pattern: row c is values(b[c] .. b[c] + len - 1).
          const la::LO row0 = nd.lid * dim;
          const auto len = static_cast<std::size_t>(Kl.graph.row_map(row0 + 1) - Kl.graph.row_map(row0));
          std::size_t b[3] = {0, 0, 0};
          for (int c = 0; c < dim; ++c) {
            b[c] = static_cast<std::size_t>(Kl.graph.row_map(row0 + c));
            bool same = static_cast<std::size_t>(Kl.graph.row_map(row0 + c + 1)) - b[c] == len;
            for (std::size_t k = 0; same && k < len; ++k) same = Kl.graph.entries(b[c] + k) == Kl.graph.entries(b[0] + k);
            if (!same) {
              Kokkos::atomic_increment(&bad_pattern());
              return;
            }
          }
          // new row k = sum_j dPhi_k/dr_j (bulk row j) + dPhi_k/dx on the node's own columns.
          for (std::size_t e = 0; e < len; ++e) {
            const la::LO col = Kl.graph.entries(b[0] + e);
            double old[3] = {0, 0, 0}, out[3] = {0, 0, 0};
            for (int c = 0; c < dim; ++c) old[c] = Kl.values(b[c] + e);
            for (int k = 0; k < dim; ++k) {
              if (nd.fixed[k]) {  // a Dirichlet row stays as it is
                out[k] = old[k];
                continue;
              }
              double v = 0.0;
              for (int j = 0; j < dim; ++j) v += o.dres[k][dim + j] * old[j];
              for (int c = 0; c < dim; ++c)
                if (col == nd.col[static_cast<std::size_t>(c)]) v += o.dres[k][c];
              out[k] = v;
            }
            for (int c = 0; c < dim; ++c) Kl.values(b[c] + e) = out[c];
          }
        });
  }
  Kokkos::fence();
  auto bad = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), bad_pattern);
  if (bad() > 0) throw std::logic_error("stentor contact: the rows of a node do not share one column pattern");
}

// Master surfaces: K' = Q K + G = K + ((Q - I) K + G), with Q = I except the active slaves'
// rows (dPhi/dr_p) and the master rows' columns of the slave (dPsi/dr_p = N_a), and G the
// derivatives at fixed r. Q - I and G have rows only at contact dofs, so the sparse
// product touches only those rows of K. Entries of rows owned elsewhere (master nodes)
// are sent at fillComplete.
la::RCP<la::CrsMatrix> Contact::coupled_tangent(const la::RCP<la::CrsMatrix>& K) {
  const auto& map = dist_.owned_map();
  const std::size_t nown = map->getNodeNumElements();
  std::vector<Row> q(nown), g(nown);
  std::map<la::GO, Row> q_far, g_far;
  auto row_of = [&](la::GO gid, std::vector<Row>& loc, std::map<la::GO, Row>& far) -> Row& {
    const la::LO l = map->getLocalElement(gid);
    return l >= 0 ? loc[static_cast<std::size_t>(l)] : far[gid];
  };
  long active = 0;
  for (const auto& p : pairs_) {
    if (!p.master) continue;
    for (std::size_t i = 0; i < p.nodes.size(); ++i) {
      const Slave& nd = p.nodes[i];
      if (nd.state < contact::Stick) continue;
      ++active;
      if (p.mortar) {
        mortar_rows(p, i, q, g, q_far, g_far);
        continue;
      }
      const contact::NodeOutput& o = p.out[i];
      const auto& fc = p.master->facets()[static_cast<std::size_t>(nd.facet)];
      const int off_r = dim_ * (1 + fc.nn);
      auto ydof = [&](int l) -> la::GO {
        const GId node = l < dim_ ? nd.gid : fc.gid[l / dim_ - 1];
        return static_cast<la::GO>(node) * dim_ + l % dim_;
      };
      for (int k = 0; k < dim_; ++k) {
        if (nd.fixed[k]) continue;  // Dirichlet rows stay identity rows of Q
        Row& qr = q[static_cast<std::size_t>(nd.lid * dim_ + k)];
        Row& gr = g[static_cast<std::size_t>(nd.lid * dim_ + k)];
        for (int j = 0; j < dim_; ++j) qr.push_back({static_cast<la::GO>(nd.gid) * dim_ + j, o.dres[k][off_r + j] - (j == k ? 1.0 : 0.0)});
        for (int l = 0; l < off_r; ++l) gr.push_back({ydof(l), o.dres[k][l]});
      }
      for (int a = 0; a < fc.nn; ++a) {
        // The derivatives of the node's additions, projected on its planes (if any).
        double dadd[3][contact::kMaxLocal] = {};
        for (int l = 0; l < off_r + dim_; ++l) {
          double v[3] = {0, 0, 0};
          for (int c = 0; c < dim_; ++c) v[c] = o.dadd[a][c][l];
          project_on_master_planes(fc.node[a], v);
          for (int c = 0; c < dim_; ++c) dadd[c][l] = v[c];
        }
        for (int c = 0; c < dim_; ++c) {
          if (master_fixed_[static_cast<std::size_t>(fc.node[a] * dim_ + c)]) continue;
          const la::GO row = static_cast<la::GO>(fc.gid[a]) * dim_ + c;
          Row& qr = row_of(row, q, q_far);
          Row& gr = row_of(row, g, g_far);
          for (int j = 0; j < dim_; ++j) qr.push_back({static_cast<la::GO>(nd.gid) * dim_ + j, dadd[c][off_r + j]});
          for (int l = 0; l < off_r; ++l) gr.push_back({ydof(l), dadd[c][l]});
        }
      }
    }
  }
  long active_glob = 0;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &active, &active_glob);
  if (active_glob == 0) return K;
  auto build = [&](std::vector<Row>& loc, std::map<la::GO, Row>& far) {
    std::vector<std::size_t> counts(nown);
    for (std::size_t i = 0; i < nown; ++i) counts[i] = loc[i].size();
    auto M = Teuchos::rcp(new la::CrsMatrix(map, Teuchos::ArrayView<const std::size_t>(counts)));
    std::vector<la::GO> cols;
    std::vector<double> vals;
    auto insert = [&](la::GO row, const Row& entries) {
      if (entries.empty()) return;
      cols.clear(), vals.clear();
      for (const auto& [c, v] : entries) cols.push_back(c), vals.push_back(v);
      M->insertGlobalValues(row, Teuchos::ArrayView<const la::GO>(cols), Teuchos::ArrayView<const double>(vals));
    };
    for (std::size_t i = 0; i < nown; ++i) insert(map->getGlobalElement(static_cast<la::LO>(i)), loc[i]);
    for (const auto& [row, entries] : far) insert(row, entries);
    M->fillComplete(map, map);
    return M;
  };
  auto Qm = build(q, q_far);  // Q - I
  auto G = build(g, g_far);
  auto QmK = Teuchos::rcp(new la::CrsMatrix(map, 0));
  Tpetra::MatrixMatrix::Multiply(*Qm, false, *K, false, *QmK);
  auto D = Tpetra::MatrixMatrix::add(1.0, false, *QmK, 1.0, false, *G, map, map);
  // While the contact pairs (slave, facet) are the same, K' keeps its graph: only its values
  // are refilled (and the linear solver reuses its symbolic set-up for the same matrix).
  const auto sig = pattern_signature();
  if (!Kp_.is_null() && sig == Kp_signature_ && refill(*K, *D)) return Kp_;
  Kp_ = Tpetra::MatrixMatrix::add(1.0, false, *K, 1.0, false, *D, map, map);
  Kp_signature_ = sig;
  return Kp_;
}

// (count, sum of hashed (slave, facet)) of the active master-surface nodes, over all ranks.
std::array<long, 2> Contact::pattern_signature() const {
  long loc[2] = {0, 0}, glob[2] = {0, 0};
  for (const auto& p : pairs_) {
    if (!p.master) continue;
    for (const auto& nd : p.nodes) {
      if (nd.state < contact::Stick) continue;
      auto h = static_cast<unsigned long>(nd.gid) * 2654435761ul + static_cast<unsigned long>(nd.facet) * 40503ul + 12345ul;
      if (p.mortar) {
        const contact::MortarRows& mo = p.mortar_out[static_cast<std::size_t>(&nd - p.nodes.data())];
        for (int v : mo.vars) h += (static_cast<unsigned long>(v) + 1ul) * 40503ul;
      }
      loc[0] += 1;
      loc[1] += static_cast<long>(h & 0xffffffffffful);  // 44 bits: no overflow over 2^19 nodes
    }
  }
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 2, loc, glob);
  return {glob[0], glob[1]};
}

// Kp_ = K + D on Kp_'s graph. False (collectively) when an entry has no slot in it.
bool Contact::refill(const la::CrsMatrix& K, const la::CrsMatrix& D) {
  Kp_->resumeFill();
  Kp_->setAllToScalar(0.0);
  const auto& kp_cols = Kp_->getColMap();
  long missing = 0;
  std::vector<la::LO> cols;
  auto sum_rows = [&](const la::CrsMatrix& A) {
    // A's local column -> Kp_'s local column.
    const auto& acols = A.getColMap();
    std::vector<la::LO> to(acols->getNodeNumElements());
    for (std::size_t j = 0; j < to.size(); ++j) to[j] = kp_cols->getLocalElement(acols->getGlobalElement(static_cast<la::LO>(j)));
    for (la::LO i = 0; i < static_cast<la::LO>(A.getNodeNumRows()); ++i) {
      la::CrsMatrix::local_inds_host_view_type ind;
      la::CrsMatrix::values_host_view_type val;
      A.getLocalRowView(i, ind, val);
      cols.resize(ind.extent(0));
      for (std::size_t k = 0; k < cols.size(); ++k) {
        cols[k] = to[static_cast<std::size_t>(ind(k))];
        missing += cols[k] < 0;
      }
      const auto n = Kp_->sumIntoLocalValues(i, Teuchos::ArrayView<const la::LO>(cols), Teuchos::ArrayView<const double>(val.data(), val.extent(0)));
      missing += static_cast<long>(cols.size()) - n;
    }
  };
  sum_rows(K);
  sum_rows(D);
  long glob = 0;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &missing, &glob);
  Kp_->fillComplete(dist_.owned_map(), dist_.owned_map());
  return glob == 0;
}

void Contact::update_changed() {
  long loc = 0, glob = 0;
  // A change of state, or of the master facet under an active node (the residual is only
  // piecewise smooth across facet edges), counts as a change.
  for (auto& p : pairs_)
    for (auto& nd : p.nodes) {
      loc += nd.state != nd.prev_state || (nd.state >= contact::Stick && nd.facet != nd.prev_facet);
      nd.prev_state = nd.state;
      nd.prev_facet = nd.facet;
    }
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &loc, &glob);
  changed_ = glob > 0;
}

la::RCP<la::CrsMatrix> Contact::apply(const la::Vector& u, la::Vector& r, const la::RCP<la::CrsMatrix>& K) {
  if (K) read_scales(*K);
  if (K && linearised_) capture_rows(K);
  evaluate_nodes(u, r);
  send_reactions(r);
  update_changed();
  if (!K) return K;
  // fillComplete is collective: every rank reopens and closes the tangent.
  K->resumeFill();
  rewrite_rigid_rows(*K);
  K->fillComplete(dist_.owned_map(), dist_.owned_map());
  if (!has_master_) return K;
  return coupled_tangent(K);
}

std::string Contact::iteration_summary() const {
  std::vector<long> loc, glob;
  for (const auto& p : pairs_) {
    long a = 0, st = 0, sl = 0, ends = 0, held = 0;
    for (const auto& nd : p.nodes) {
      held += nd.held();
      a += nd.state >= contact::Stick;
      st += nd.state == contact::Stick;
      sl += nd.state == contact::Slip;
      ends += p.master && nd.state >= contact::Stick && !nd.inside;
    }
    loc.insert(loc.end(), {a, st, sl, ends, held});
  }
  glob.resize(loc.size());
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), glob.data());
  std::ostringstream os;
  os << "      contact";
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    const long* g = &glob[5 * i];
    os << "  " << pairs_[i].cfg.name << ": active " << g[0] << " (stick " << g[1] << ", slip " << g[2] << ")";
    // Nodes whose closest point is held at a facet's end (outside every facet, e.g. over a
    // concave kink): their conditions are not smooth there.
    if (g[3] > 0) os << " [" << g[3] << " projected past a facet end]";
    if (g[4] > 0) os << " [" << g[4] << " held after cycling]";
    os << (changed_ ? "" : ", settled");
  }
  return os.str();
}

void Contact::contact_force_of(const Slave& nd, const double* n, double* F) const {
  // nd.f is the bulk residual, zero on the planes' rows: completed on the planes first, as
  // the conditions take it (NodeLaw.hpp, evaluate).
  contact::LawParams lp;
  lp.planes = nd.planes;
  for (int i = 0; i < 3; ++i) {
    lp.pj[i] = nd.pj[i];
    for (int c = 0; c < 3; ++c) lp.e[i][c] = nd.e[i][c];
  }
  double r[3] = {nd.f[0], nd.f[1], nd.f[2]};
  contact::complete_on_planes(lp, r);
  contact::contact_force(dim_, nd.fixed, lp, n, r, F);
}

Contact::StepStats Contact::accept(const la::Vector& u_np1) {
  auto uh = u_np1.getLocalViewHost(Tpetra::Access::ReadOnly);
  if (has_master_) update_master_positions(u_np1, master_x_);
  const std::size_t np = pairs_.size();
  constexpr std::size_t kPer = 7;  // per pair: active, stick, slip, force x y z, normal force
  std::vector<double> loc(np * kPer + 3, 0.0), glob(loc.size(), 0.0), mloc(np, 1e300), mglob(np, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    auto& p = pairs_[i];
    if (p.mortar)
      mortar_geometry(p);  // builds both surfaces' bins itself
    else if (p.master)
      p.master->build(master_x_, &present_);
    const contact::Obstacle ob = obstacle(p, t1_);
    for (auto& nd : p.nodes) {
      double x[3] = {nd.X[0], nd.X[1], nd.X[2]}, n[3] = {0, 0, 0};
      for (int c = 0; c < dim_; ++c) x[c] += uh(nd.lid * dim_ + c, 0);
      double d = 0.0, rel[3] = {0, 0, 0};
      if (p.mortar) {
        d = nd.gap;
        for (int c = 0; c < 3; ++c) n[c] = nd.normal[c], rel[c] = nd.rel[c];
      } else if (p.master) {
        // Active nodes keep the facet of their last evaluation; others look again.
        if (nd.state < contact::Stick) locate(p, nd, x);
        d = facet_gap(p, nd, x, n, rel);
      } else {
        d = contact::rigid_gap(ob, x, n);
        for (int c = 0; c < 3; ++c) rel[c] = x[c] - nd.x_n[c] - ob.dw[c];
      }
      nd.gap = d;
      for (int c = 0; c < 3; ++c) nd.normal[c] = n[c], nd.rel[c] = rel[c];
      mloc[i] = std::min(mloc[i], d);
      if (nd.state >= contact::Stick) {
        loc[kPer * i] += 1;
        loc[kPer * i + 1] += nd.state == contact::Stick;
        loc[kPer * i + 2] += nd.state == contact::Slip;
        for (int c = 0; c < 3; ++c) loc[kPer * i + 3 + static_cast<std::size_t>(c)] += nd.f[c];
        // F = r_p on the slave (and -F at the master's contact point): its work over the
        // step is F . rel (+ F . dw for a moving rigid obstacle, work done by the obstacle's
        // motion). Normal part: contact work; tangential part: -(frictional dissipation).
        // On symmetry planes the force between the bodies is F_c (NodeLaw.hpp,
        // contact_force), the rest of r_p the planes' reaction.
        double F[3];
        contact_force_of(nd, n, F);
        const double fn = dot3(F, n);
        loc[kPer * i + 6] += fn;
        double ft[3], relt[3], dwt[3];
        const double reln = dot3(rel, n), dwn = dot3(ob.dw, n);
        for (int c = 0; c < 3; ++c) {
          ft[c] = F[c] - fn * n[c];
          relt[c] = rel[c] - reln * n[c];
          dwt[c] = p.master ? 0.0 : ob.dw[c] - dwn * n[c];
        }
        const double dun = p.master ? reln : reln + dwn;
        loc[kPer * np] += fn * dun + dot3(ft, dwt);
        loc[kPer * np + 1] += -dot3(ft, relt);
      }
      nd.d_prev = nd.d_n;
      nd.d_n = d;
      loc[kPer * np + 2] += nd.was_active != (nd.state >= contact::Stick);
      nd.was_active = nd.state >= contact::Stick;
    }
  }
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), glob.data());
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MIN, static_cast<int>(np), mloc.data(), mglob.data());
  dt_last_ = dt_;
  StepStats s;
  for (std::size_t i = 0; i < np; ++i) {
    PairStats ps;
    ps.active = static_cast<long>(glob[kPer * i]);
    ps.stick = static_cast<long>(glob[kPer * i + 1]);
    ps.slip = static_cast<long>(glob[kPer * i + 2]);
    ps.force = {glob[kPer * i + 3], glob[kPer * i + 4], glob[kPer * i + 5]};
    ps.normal_force = glob[kPer * i + 6];
    Pair& p = pairs_[i];
    const double w = dynamic_ ? p.last_dt : 0.0;
    ps.normal_force_mean = (w * p.last_normal_force + dt_ * ps.normal_force) / (w + dt_);
    p.last_normal_force = ps.normal_force;
    p.last_dt = dynamic_ ? dt_ : 0.0;
    ps.min_gap = mglob[i];
    if (round_obstacle(p)) ps.obstacle_diameter = 2.0 * obstacle(p, t1_).radius;
    s.pairs.push_back(ps);
  }
  s.work = glob[kPer * np];
  s.friction_dissipation = glob[kPer * np + 1];
  s.events = static_cast<long>(glob[kPer * np + 2]);
  return s;
}

// Pair p's contact pressure at its owned slave nodes (in p.nodes order): the normal forces
// of its active nodes summed over the ranks into one vector over the slave surface's nodes,
// projected on the surface by every rank alike (the same sums, the same solve: the same
// pressures on any number of ranks).
std::vector<double> Contact::slave_pressures(const Pair& p) const {
  const SurfaceProjection& s = *p.surface;
  std::vector<double> loc(s.nodes().size(), 0.0), f(loc.size(), 0.0);
  for (const Slave& nd : p.nodes)
    if (nd.state >= contact::Stick) loc[static_cast<std::size_t>(s.index(nd.gid))] = dot3(nd.normal, nd.f);
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), f.data());
  const std::vector<double> pressure = s.project(f, 1);
  std::vector<double> out;
  for (const Slave& nd : p.nodes) out.push_back(pressure[static_cast<std::size_t>(s.index(nd.gid))]);
  return out;
}

double Contact::contact_area(const std::string& group) const {
  double loc = 0.0, glob = 0.0;
  for (const Pair& p : pairs_)
    if (p.active && p.cfg.slave == group)
      for (const Slave& nd : p.nodes)
        if (nd.state >= contact::Stick) loc += nd.area;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &loc, &glob);
  return glob;
}

Contact::NodalFields Contact::nodal_fields() const {
  NodalFields out;
  std::map<GId, std::size_t> row;  // a node slave of several pairs (never active together): the active pair's values
  for (const Pair& p : pairs_) {
    const std::vector<double> pressure = slave_pressures(p);
    for (std::size_t i = 0; i < p.nodes.size(); ++i) {
      const Slave& nd = p.nodes[i];
      const auto [at, fresh] = row.emplace(nd.gid, out.nodes.size());
      if (!fresh && !p.active) continue;
      if (fresh) {
        out.nodes.push_back(static_cast<long long>(nd.gid));
        out.values.resize(out.values.size() + kNodalValues);
      }
      double* v = &out.values[at->second * kNodalValues];
      const bool active = nd.state >= contact::Stick;
      const double fn = dot3(nd.normal, nd.f);
      v[0] = static_cast<double>(nd.state);
      v[1] = nd.gap;
      v[2] = active ? -fn : 0.0;
      v[3] = pressure[i];
      for (int c = 0; c < 3; ++c) v[4 + c] = active ? -(nd.f[c] - fn * nd.normal[c]) : 0.0;
      const double reln = dot3(nd.rel, nd.normal);
      for (int c = 0; c < 3; ++c) v[7 + c] = active ? nd.rel[c] - reln * nd.normal[c] : 0.0;
    }
  }
  return out;
}

Contact::NodalFields Contact::master_fields() const {
  std::map<int, std::array<double, 4>> force;  // master position -> force, normal force
  for (const Pair& p : pairs_) {
    if (!p.master) continue;
    for (const Slave& nd : p.nodes) {
      if (nd.state < contact::Stick || nd.facet < 0) continue;
      double F[3] = {nd.f[0], nd.f[1], nd.f[2]};  // what the master receives: F_c from a node-to-segment slave on symmetry planes
      if (!p.mortar) contact_force_of(nd, nd.normal, F);
      const double fn = dot3(F, nd.normal);
      if (p.mortar) {
        const contact::MortarRows& mo = p.mortar_out[static_cast<std::size_t>(&nd - p.nodes.data())];
        for (std::size_t k = 0; k < mo.masters.size(); ++k) {
          auto& f = force[mo.masters[k]];
          for (int c = 0; c < 3; ++c) f[static_cast<std::size_t>(c)] -= mo.w[k] * nd.f[c];
          f[3] += mo.w[k] * fn;
        }
        continue;
      }
      const auto& fc = p.master->facets()[static_cast<std::size_t>(nd.facet)];
      double xa[facet::kMaxNodes][3];
      for (int a = 0; a < fc.nn; ++a)
        for (int c = 0; c < 3; ++c) xa[a][c] = master_x_[3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(c)];
      facet::Frame<double> fr;
      facet::frame(fc.type, fc.nn, dim_, fc.orient, xa, nd.xi, fr);
      for (int a = 0; a < fc.nn; ++a) {
        auto& f = force[fc.node[a]];
        for (int c = 0; c < 3; ++c) f[static_cast<std::size_t>(c)] -= fr.N[a] * F[c];
        f[3] += fr.N[a] * fn;
      }
    }
  }
  NodalFields out;
  for (const auto& [pos, f] : force) {
    out.nodes.push_back(static_cast<long long>(master_nodes_[static_cast<std::size_t>(pos)]));
    out.values.insert(out.values.end(), {f[0], f[1], f[2], master_area_[static_cast<std::size_t>(pos)], f[3]});
  }
  return out;
}

std::vector<std::string> Contact::history_columns() const {
  std::vector<std::string> c;
  for (const auto& p : pairs_) {
    const std::string b = "contact_" + p.cfg.name + "_";
    c.push_back(b + "active");
    c.push_back(b + "stick");
    c.push_back(b + "slip");
    for (int k = 0; k < dim_; ++k) c.push_back(b + "force_" + kAxes[k]);
    c.push_back(b + "normal_force");
    c.push_back(b + "two_step_mean_normal_force");
    c.push_back(b + "min_gap");
    if (round_obstacle(p)) c.push_back(b + "obstacle_diameter");
  }
  return c;
}

std::vector<double> Contact::history_values(const StepStats& s) const {
  std::vector<double> v;
  for (std::size_t i = 0; i < s.pairs.size(); ++i) {
    const PairStats& ps = s.pairs[i];
    v.push_back(static_cast<double>(ps.active));
    v.push_back(static_cast<double>(ps.stick));
    v.push_back(static_cast<double>(ps.slip));
    for (int k = 0; k < dim_; ++k) v.push_back(ps.force[static_cast<std::size_t>(k)]);
    v.push_back(ps.normal_force);
    v.push_back(ps.normal_force_mean);
    v.push_back(ps.min_gap);
    if (round_obstacle(pairs_[i])) v.push_back(ps.obstacle_diameter);
  }
  return v;
}

std::string Contact::progress(const StepStats& s) const {
  std::ostringstream os;
  os << "  contact";
  for (const auto& ps : s.pairs) os << " " << ps.active << "/" << ps.stick << "/" << ps.slip;
  return os.str();
}

}  // namespace stentor
