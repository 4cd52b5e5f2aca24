// Frictional contact of slave boundary nodes against rigid analytic obstacles and against
// the boundary facets of other deformable bodies, solved by the primal-dual active set
// (semi-smooth Newton) method inside the global Newton loop (docs/contact.md).
//
// Layers (one file each):
//   contact/Dual.hpp           forward-mode derivatives for the local conditions;
//   contact/FacetGeometry.hpp  master facets: shape functions, normal, closest point;
//   contact/NodeLaw.hpp        the conditions of one slave node (gap or persistence,
//                              Coulomb stick/slip) as a function of its local unknowns;
//   contact/MasterSurface.*    master facets of a boundary group and their search bins;
//   contact/Mortar.hpp         dual mortar integrals of a slave facet against a master facet;
//   contact/MortarNode.hpp     a mortar slave node: its stencil, nodal normal, weights, law;
//   contact/Contact.*          pairs, slave nodes, the active set, and the enforcement
//                              (ContactMortar.cpp: the mortar discretization's nodes;
//                              ContactGhosts.cpp: which surface nodes a rank imports).
//
// Multipliers are condensed: the contact force on a slave node is its bulk residual
// F = r_p (talk's signs: lambda_nu = -n . r_p <= 0 in compression). An active node's
// rows are replaced by its conditions, and (master surfaces) the master facet's nodes
// receive the reaction r_a += N_a(xi) r_p (mortar: r_k += w_pk r_p, the master nodes' mortar
// weights, and the normal is the slave surface's nodal normal). The modified residual is R = Q r + c(u), so
// its tangent is K' = Q K + G with G = (dR/du at fixed r): for rigid obstacles Q and G
// only touch a node's own rows and columns and K is rewritten in place; with master
// surfaces K' = Q K + G is formed with Tpetra's sparse matrix product (the graph follows
// the contact couplings, across ranks). Without active nodes K is used as it is.
#pragma once
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "assembly/Assembler.hpp"
#include "bc/PlaneDirections.hpp"
#include "contact/MortarNode.hpp"
#include "contact/NodeLaw.hpp"
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"
#include "parallel/Distribution.hpp"

namespace stentor {

class MasterSurface;
class SurfaceProjection;

class Contact {
 public:
  // nullptr when the deck has no "Contact" sublist: a run without contact pays nothing.
  static std::unique_ptr<Contact> create(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler);
  Contact(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler);
  ~Contact();

  // Gap history at t = 0 from u_0: d_{-1} = d_0, or with the initial velocities v0 and the
  // first step dt0 (dynamics), d_{-1} = d_0 - dt0 (gap rate), so the first step's leapfrog
  // test sees the initial motion. Collective.
  void initialize(const la::Vector& u0, double end_time, const la::Vector* v0 = nullptr, double dt0 = 0.0);
  // Pairs whose slave nodes start inside their obstacle or master surface (initialize()'s
  // gaps) deeper than 1e-6 of the model's size: one warning line each, naming the pair, the
  // number of such nodes and the deepest penetration. Collective; the same lines on every rank.
  std::vector<std::string> initial_penetrations() const;
  // The step t_n -> t_n + dt from the converged u_n.
  void begin_step(double t_n, double dt, const la::Vector& u_n);
  // After Assembler::assemble(): active sets from u, then the contact rows of r and, when
  // K is given, the tangent: K itself (rewritten in place for rigid obstacles) or, when a
  // node touches a master surface, the new matrix Q K + G. Collective.
  la::RCP<la::CrsMatrix> apply(const la::Vector& u, la::Vector& r, const la::RCP<la::CrsMatrix>& K);
  // Whether the active set (per slave node: free, inactive, stick, slip, and the master
  // facet of an active node) of the last apply() differs from the one before it
  // (collective result, computed in apply()).
  bool active_set_changed() const { return changed_; }
  // Newton's correction du from the tangent of the last apply() (collective): the
  // multipliers of that linear solve become the ones that decide the sets ("set update" =
  // linearised; Hintermueller-Ito-Kunisch's primal-dual active set): zero on the nodes that
  // were inactive in it, f_p + K_p du on the active ones (f_p, K_p: the node's bulk residual
  // and tangent rows there). set_step_length(alpha): the next apply() is at u + alpha du, its
  // deciding multipliers f_p + alpha K_p du.
  void linearised_step(const la::Vector& du);
  void set_step_length(double alpha) { alpha_ = alpha; }
  // Cycle control: a node whose set in the solves went back and forth kFreezeAfter times in
  // this step is held for the rest of the step, so the iteration cannot cycle on it: active
  // (contact entered and left), slipping with a fixed friction direction (stick and slip),
  // on one master facet (its closest facet, or whether its projection fell inside it,
  // changed kFacetFreezeAfter times, e.g. over a master vertex or past the surface's edge: the facet
  // extended past its ends, no clamping, so its conditions are smooth; at convergence its
  // projection must lie on the facet or within kHoldBand of it, else the node is held on
  // its closest facet as a revision, once).
  // At convergence its conditions are checked from the converged contact force and slip,
  // each to kKktTolerance of the pair's largest nodal force or slip (lengths at least
  // kKktTolerance of the node's size, Slave::size): a held active node must
  // press, a held slipping node must slip along its friction force (neither reversed nor,
  // in 3D, across it), a held sticking node must stay inside the Coulomb cone. Returns 0
  // when every held node meets them; 1 when a node failed and is held in its next state
  // (slip -> stick -> slip along the sticking force, each once; Newton iterates on); 2 when
  // a held node fails with no state left, `why` naming the node (the step is then cut
  // back). Collective.
  static constexpr int kFreezeAfter = 3;
  static constexpr double kFacetBand = 0.02;  // facet hysteresis (keep_facet)
  static constexpr int kFacetFreezeAfter = 2;  // facet changes (A -> B -> A: a cycle) before a facet hold
  // A node held on a facet passes when its projection is within kHoldBand (parametric: a
  // tenth of a line2 or quad facet's side) past the facet's edge, the master surface
  // extended there as Abaqus extends its master surfaces.
  static constexpr double kHoldBand = 0.2;
  static constexpr double kKktTolerance = 1e-3;
  int verify_held(std::string& why);
  // After a failed attempt at a step: the k slave nodes whose set changed most often in the
  // attempt's linear solves (pairs that decide their sets from them), as "node <gid> of
  // 'Contact-><pair>' (reference position x, y[, z]; entered or left contact N times,
  // stick/slip M times[, held])",
  // the most changed first; "" when none changed. Collective.
  std::string most_changed_nodes(int k) const;
  // Stepping->contact approach: the largest fraction f <= 1 of the step t_n -> t_n + dt
  // after which no slave node on a part of its slave surface that is out of contact at u_n
  // (a connected part of the group without an active node: a strut before it touches, a
  // ring before the balloon reaches it) is predicted deeper than `depth` times
  // its size (its tributary length, or the square root of its tributary area in 3D) inside
  // its obstacle or master surface: the nodes and master nodes moved from u_n to u_pred (a
  // predicted state), the rigid obstacles to t_n + dt, the gap against the master facet of
  // the last evaluation linearly interpolated. The node that sets f, with its gap now and
  // the predicted one (f = 1, pair -1: no node limits the step). Node-to-segment and rigid
  // pairs; mortar pairs are not predicted. Collective.
  struct Approach {
    double fraction = 1.0;
    GId node = 0;
    int pair = -1;
    double gap = 0.0, predicted = 0.0, allowed = 0.0;
  };
  Approach approach(const la::Vector& u_n, const la::Vector& u_pred, double t_n, double dt, double depth) const;
  // Which pairs enforce contact (one flag per Config::contact entry; all by default): the
  // slave nodes of an inactive pair are free. "Stages" switch pairs per stage.
  void set_active_pairs(const std::vector<bool>& active);
  // The analysis of the stage about to run: pairs with formulation `auto` enforce
  // persistence in a dynamic stage and the gap condition in a static one. The gap history
  // (d_n, d_{n-1}) is kept in both, so a switch needs nothing else.
  void set_analysis(bool dynamic);

  struct PairStats {
    long active = 0, stick = 0, slip = 0;
    std::array<double, 3> force{};  // total contact force on the slave body (sum over active nodes)
    double normal_force = 0.0;      // sum of the active nodes' normal forces n . f (compression > 0): radial for a cylinder
    // The impulse-weighted mean of normal_force over this step and the one before it,
    // (dt_{n-1} F_{n-1/2} + dt_n F_{n+1/2}) / (dt_{n-1} + dt_n): the midpoint rule's
    // multipliers are impulses per step, and in sustained persistent contact they carry a
    // mode that alternates from step to step, which this mean removes (docs/contact.md,
    // "Sustained contact"). In a static step (and the first step after one): normal_force.
    double normal_force_mean = 0.0;
    double min_gap = 0.0;
    // A rigid circle, sphere, cylinder or capsule (a balloon): its diameter at the step's
    // end (history column contact_<pair>_obstacle_diameter; NaN for other pairs).
    double obstacle_diameter = std::numeric_limits<double>::quiet_NaN();
  };
  struct StepStats {
    std::vector<PairStats> pairs;
    double work = 0.0;                 // normal work of the contact forces over the step (both bodies; + tangential work of a moving obstacle)
    double friction_dissipation = 0.0; // -F_tau . rel_tau >= 0 over the step
    long events = 0;                   // nodes that entered or left contact over the step
  };
  // Global set sizes of the last apply() (collective), e.g. "contact 3 active (1 stick, 2 slip)".
  std::string iteration_summary() const;
  // After a converged step at u_{n+1} (the last apply() was at u_{n+1}): forces, energy
  // terms, set sizes (collective); then d_{n-1} <- d_n <- d(x_{n+1}, t_{n+1}).
  StepStats accept(const la::Vector& u_np1);

  // Per owned slave node, for the HDF5 output: global node id and kNodalValues values
  // (state: 0 free, 1 inactive, 2 stick, 3 slip; gap; lambda_nu; contact pressure;
  // lambda_tau x, y, z; slip increment x, y, z), from the last apply(). The contact
  // pressure is the projection M_s p = f of the active nodes' normal forces -lambda_nu on
  // the pair's slave surface (mesh/SurfaceProjection.hpp): force per reference area.
  // Collective (the forces of each slave surface are summed over the ranks).
  static constexpr int kNodalValues = 10;
  struct NodalFields {
    std::vector<long long> nodes;
    std::vector<double> values;
  };
  NodalFields nodal_fields() const;
  // The reference tributary area of the slave nodes of `group` in contact (stick or slip)
  // in the active pairs, summed over the ranks (collective; 0 when no pair has that slave).
  double contact_area(const std::string& group) const;
  // Per master node touched by an active slave of this rank: global node id and 5 values
  // (the reaction force on the master node, -sum N_a F, x y z; its HRZ tributary area; the
  // normal force it carries, sum N_a F . n, compression > 0, n the slave's contact normal).
  // The same node may come from several ranks: sum the forces, keep the area. (The
  // output's contact_master_traction and contact_master_pressure project the summed forces
  // instead: mesh/SurfaceProjection.hpp.)
  static constexpr int kMasterValues = 5;
  bool has_master_surfaces() const { return has_master_; }
  // The rigid obstacles at time t (position and radius), in deck order (for drawing).
  std::vector<contact::Obstacle> rigid_obstacles(double t) const;
  NodalFields master_fields() const;

  // Restart (src/run/Restart.cpp): what one step hands to the next besides u, per owned
  // slave node of a pair (kHistoryValues values: d_n, d_{n-1}, active at the end of the
  // last step, state and master facet of the last evaluation, which the next active-set
  // change test compares with, the stiffness scale s_p, the master facet found after
  // the step and whether the projection on it was inside it), and the size of the last
  // accepted step (leapfrog factor). initialize() sets everything else that lasts (end
  // time, master positions), begin_step() the rest.
  static constexpr int kHistoryValues = 8;
  std::size_t num_pairs() const { return pairs_.size(); }
  const std::string& pair_name(std::size_t pair) const { return pairs_[pair].cfg.name; }
  NodalFields step_history(std::size_t pair) const;
  // From records sorted by node id (of any ranks: a whole checkpoint table). Returns the
  // number of this rank's slave nodes without a record (left as initialize() set them).
  long restore_step_history(std::size_t pair, const NodalFields& sorted);
  double last_step() const { return dt_last_; }
  void set_last_step(double dt) { dt_last_ = dt; }
  // The last accepted step's normal force of a pair and the step's length in the two-step
  // mean (0 after a static step): what the next step's PairStats::normal_force_mean needs.
  std::array<double, 2> normal_force_history(std::size_t pair) const {
    return {pairs_[pair].last_normal_force, pairs_[pair].last_dt};
  }
  void restore_normal_force_history(std::size_t pair, double force, double dt) {
    pairs_[pair].last_normal_force = force;
    pairs_[pair].last_dt = dt;
  }

  std::vector<std::string> history_columns() const;
  std::vector<double> history_values(const StepStats& s) const;
  std::string progress(const StepStats& s) const;
  std::string description() const;

  struct Slave {
    la::LO lid = 0;                    // owned node index
    GId gid = 0;
    std::array<la::LO, 3> col{};       // local column indices (tangent's column map) of the node's dofs
    bool fixed[3] = {false, false, false};  // prescribed components (symmetry planes): rows stay Dirichlet rows
    int planes = 0;                    // on `normal` Dirichlet planes (Assembler::plane_normals): e_i . u fixed
    double e[3][3] = {};               // ... their orthonormal directions
    int pj[3] = {0, 0, 0};             // ... and the components whose rows carry e_i . du = 0
    double X[3] = {0, 0, 0};
    double x_n[3] = {0, 0, 0};
    double d_n = 0.0, d_prev = 0.0;
    double scale = 1.0;                // s_p
    double area = 0.0;                 // tributary area A_p (reference, HRZ-lumped): scales the deck's c_normal, c_tangent
    double size = 0.0;                 // its length scale: A_p in 2D (per unit thickness, or A_p / 2 pi r), sqrt(A_p) in 3D
    int part = -1;                     // the connected part of the slave surface it lies on (surface_parts, with
                                       // Stepping->contact approach only; -1: on no facet, or not computed)
    bool was_active = false;           // active at the end of the last accepted step
    int state = contact::Free;
    int prev_state = contact::Free;
    double f[3] = {0, 0, 0};           // bulk residual at the node at the last apply()
    int facet = -1;                    // master facet of the last apply() (-1: none / rigid)
    int prev_facet = -1;               // ... and of the apply() before it
    double xi[2] = {0, 0};
    double xi_free[2] = {0, 0};        // the projection's parameters before clamping (MasterSurface::Hit)
    bool inside = true;
    double gap = 0.0, normal[3] = {0, 0, 0}, rel[3] = {0, 0, 0};
    // linearised_step(): whether the step's deciding multiplier is set, the node's set in
    // that solve, its bulk residual there (lam_base) and K_p du.
    bool lam_valid = false;
    int base_state = contact::Free;
    // Cycle control within the step: flips of the solve's set between Newton iterations
    // (in/out of contact, stick/slip), and the holds after kFreezeAfter (count_flips).
    int normal_flips = 0, tangent_flips = 0;
    bool hold_active = false;
    bool hold_inactive = false;  // a held active node that ended in tension, released (verify_held)
    int hold_tangent = 0;        // 0, or the held contact::Stick / contact::Slip
    int hold_revisions = 0;      // revisions of the tangential or facet hold by verify_held (at most 2)
    double hold_dir[3] = {0, 0, 0};  // the held slip's friction direction (unit, world frame)
    // Facet cycle control (node-to-segment): the facet, and whether the projection was inside
    // it, at the last solve; changes of them between solves; the facet held after
    // kFacetFreezeAfter changes (-1: none), extended past its ends (hold_facet_projection).
    int solve_facet = -1;
    bool solve_inside = true;
    int facet_flips = 0;
    int hold_facet = -1;         // -2: to be held on its closest facet at the next evaluation (a revision)
    bool hold_in_band = true;    // the held facet's projection within kHoldBand of the facet
    double lam_base[3] = {0, 0, 0}, kdu[3] = {0, 0, 0};
    // Held in some way by the cycle control (the log's and the failure report's "held").
    bool held() const { return hold_active || hold_inactive || hold_tangent != 0 || hold_facet != -1; }
  };


 private:
  struct Pair {
    ContactPairConfig cfg;
    bool persistence = true;
    std::unique_ptr<MasterSurface> master;  // null: rigid obstacle
    std::unique_ptr<SurfaceProjection> surface;  // the slave group's facets (every rank: the whole group)
    bool mortar = false;                         // cfg.discretization == "mortar"
    std::unique_ptr<MasterSurface> slave_faces;  // mortar: the slave group's oriented facets (surface positions)
    std::vector<std::vector<int>> node_faces;    // mortar: per slave node (nodes order), its slave facets
    std::vector<contact::MortarRows> mortar_out; // mortar: per slave node, the last evaluation
    std::vector<Slave> nodes;
    // "set update" = linearised: the bulk tangent rows of the slave nodes' dofs at the last
    // apply() with a tangent (CSR, row i * dim + c; columns in that tangent's column map).
    std::vector<std::size_t> krow_ptr;
    std::vector<la::LO> krow_col;
    std::vector<double> krow_val;
    std::vector<contact::NodeOutput> out;   // per slave node, last apply()
    int parts = 0;                          // connected parts of the slave surface (Slave::part)
    long excluded = 0;                      // slave nodes with every component prescribed (left out), global
    long partial = 0;                       // slave nodes with some prescribed components (kept), global
    bool active = true;                     // set_active_pairs()
    double last_normal_force = 0.0, last_dt = 0.0;  // normal_force_history()
  };
  void setup_slaves(std::size_t ip, const Config& cfg, const Mesh& mesh, const Assembler& assembler, const std::vector<GId>& master_set,
                    std::multimap<GId, int>& slave_of);
  void setup_master_maps(const Mesh& mesh, const std::vector<GId>& surface_set, const Assembler& assembler);
  int master_pos(GId g) const;  // index of node g in master_nodes_, or -1
  contact::Obstacle obstacle(const Pair& p, double t) const;
  // A rigid circle, sphere, cylinder or capsule: a pair with an obstacle diameter.
  static bool round_obstacle(const Pair& p) { return !p.master && p.cfg.obstacle != "plane"; }
  std::array<double, 3> translation(const Pair& p, double t) const;
  // Positions of the master nodes at u (3 per master node; imports u's master dofs).
  void update_master_positions(const la::Vector& u, std::vector<double>& xm) const;
  void locate(const Pair& p, Slave& nd, const double* x) const;
  bool keep_facet(const Pair& p, Slave& nd, const double* x) const;
  // A held facet (Slave::hold_facet) extended by up to kHoldReach of its parameter range
  // past each end: false (the hold dropped) when the node's projection leaves that.
  static constexpr double kHoldReach = 0.5;
  bool hold_facet_projection(const Pair& p, Slave& nd, const double* x) const;
  double facet_gap(const Pair& p, const Slave& nd, const double* x, double* n, double* rel) const;
  void node_input(const Pair& p, const Slave& nd, const double* x, contact::NodeInput& in) const;
  // The law's parameters of one slave node: its stiffness scale, release threshold and c_nu, c_tau.
  contact::LawParams node_params(const Pair& p, const Slave& nd, const contact::LawParams& lp) const;
  void initial_gap_rates(const la::Vector& u0, const la::Vector& v0, double dt0);
  void read_scales(const la::CrsMatrix& K);
  void capture_rows(const la::RCP<la::CrsMatrix>& K);  // Pair::krow_* of the linearised pairs
  // The part of v (a slave's force or slip) that friction sees: tangential, and on one
  // symmetry plane in 3D along the plane's one tangential direction (ContactHolds.cpp).
  double friction_part(const Slave& nd, const double* v, double* vt) const;
  // The force between the bodies at slave nd with normal n (contact::contact_force).
  void contact_force_of(const Slave& nd, const double* n, double* F) const;
  void count_flips(const Pair& p, Slave& nd) const;
  static double tangent_penalty(const Pair& p, const Slave& nd, double dt);
  bool linearised_ = false;                            // some pair decides its sets from the last solve
  double alpha_ = 1.0;                                 // set_step_length()
  la::RCP<const la::CrsMatrix> rows_of_;               // the tangent capture_rows() read (its column map)
  void evaluate_nodes(const la::Vector& u, la::Vector& r);
  void send_reactions(la::Vector& r);
  void rewrite_rigid_rows(la::CrsMatrix& K);
  la::RCP<la::CrsMatrix> coupled_tangent(const la::RCP<la::CrsMatrix>& K);
  std::array<long, 2> pattern_signature() const;
  bool refill(const la::CrsMatrix& K, const la::CrsMatrix& D);
  void update_changed();
  std::vector<double> slave_pressures(const Pair& p) const;
  // Mortar (ContactMortar.cpp).
  using FaceCoupling = contact::FaceCoupling;
  void setup_mortar(Pair& p);
  std::vector<std::vector<FaceCoupling>> couple_faces(const Pair& p, const std::vector<char>& needed) const;
  // Slave node i's mortar geometry at the current surface positions: gap d (the search
  // radius without a master), normal, relative displacement; with `law`, also its
  // conditions into p.mortar_out[i] (returns the state; Free without a master).
  int mortar_node(Pair& p, std::size_t i, const std::vector<std::vector<FaceCoupling>>& cpl, const contact::LawParams* law, double* d,
                  double* n, double* rel);
  void evaluate_mortar(Pair& p, const contact::LawParams& lp, double lf, const double* u, double* r);
  void mortar_geometry(Pair& p);  // gap, normal, rel of every slave node (initialize, accept)
  // Rows of Q - I and G (coupled_tangent) of active mortar node i: its own rows, its master nodes'.
  using Row = std::vector<std::pair<la::GO, double>>;
  void mortar_rows(const Pair& p, std::size_t i, std::vector<Row>& q, std::vector<Row>& g, std::map<la::GO, Row>& q_far,
                   std::map<la::GO, Row>& g_far) const;

  int dim_;
  bool axi_;  // Problem->kinematics = axisymmetric: tributary and projection areas of revolved facets
  double end_time_ = 1.0, t0_ = 0.0, t1_ = 0.0, dt_ = 1.0, dt_last_ = 0.0, gap_tol_ = 0.0, model_size_ = 0.0;
  bool changed_ = true;
  const Distribution& dist_;
  std::vector<Pair> pairs_;
  // Surface ghosting (rebuild_ghosts): the surface nodes (master nodes, and the slave
  // nodes of mortar pairs) near this rank's slave nodes are imported, not the whole surface.
  void rebuild_ghosts(const la::Vector& u);
  // Whether an owned slave or surface node moved more than a quarter of the margin since
  // the last rebuild_ghosts() (collective).
  bool ghosts_outrun(const la::Vector& u) const;
  // Master surfaces: the surface nodes' dofs present on this rank, imported each
  // evaluation; positions at the start of the step; Dirichlet flags of those dofs.
  bool has_master_ = false;
  bool mixed_analysis_ = false;  // static and dynamic stages: `auto` pairs switch (set_analysis)
  bool dynamic_ = true;          // the stage's analysis (set_analysis): the two-step mean is for dynamic steps
  std::vector<GId> master_nodes_;          // sorted
  std::vector<double> master_X_;           // reference coordinates, 3 per master node
  std::vector<double> master_area_;        // tributary reference area per master node
  std::vector<double> master_x_, master_xn_;  // current / start-of-step positions, 3 per master node
  std::vector<char> master_fixed_;         // per master dof (dim per node): prescribed (or a plane's constraint row)
  std::map<int, PlaneDirections> master_plane_;  // master nodes (master_pos) on `normal` planes
  void setup_master_planes(const Assembler& assembler);
  // v (dim values) less its components along the planes' normals of master node pos.
  void project_on_master_planes(int pos, double* v) const;
  std::vector<char> present_;              // per surface node: imported on this rank
  std::vector<int> ghost_pos_;             // the imported surface nodes (positions), master_map_ order
  std::vector<int> ghost_index_;           // per surface node: its index in ghost_pos_, or -1
  double ghost_margin_ = 0.0;              // 8 h (h: the largest reference facet extent of the surfaces)
  double ghost_box_[6] = {0, 0, 0, 0, 0, 0};  // this rank's slave nodes' box at the last rebuild
  std::vector<double> ghost_x_;            // owned surface nodes' positions at the last rebuild (3 each, by position)
  la::RCP<la::Vector> u_n_;                // the step's start (to import the start positions of new ghosts)
  la::RCP<const la::Map> master_map_;
  la::RCP<const la::Import> master_import_;
  la::RCP<const la::Export> master_export_;
  la::RCP<la::Vector> master_u_, master_r_;
  // The coupled tangent K' of the last evaluation and the signature of its graph.
  la::RCP<la::CrsMatrix> Kp_;
  std::array<long, 2> Kp_signature_{};
};

}  // namespace stentor
