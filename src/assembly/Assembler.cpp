#include "assembly/Assembler.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <sstream>
#include <set>
#include <unordered_set>

#include <Teuchos_CommHelpers.hpp>

#include "assembly/HyperelasticElement.hpp"
#include "assembly/PressureElement.hpp"
#include "material/SymEigen.hpp"

namespace stentor {
namespace {

using DeviceMatrix = la::CrsMatrix::local_matrix_device_type;

// Gathers a cell's reference coordinates and displacements from overlap-local arrays.
template <class Conn, class Coords, class UView>
KOKKOS_INLINE_FUNCTION void gather_cell(int c, int nn, int dim, const Conn& conn, const Coords& X, const UView& u,
                                        double (*Xe)[3], double (*Ue)[3], int* dofs) {
  for (int a = 0; a < nn; ++a) {
    const int l = conn(c, a);
    for (int d = 0; d < 3; ++d) {
      Xe[a][d] = X(l, d);
      Ue[a][d] = 0.0;
    }
    for (int d = 0; d < dim; ++d) {
      dofs[a * dim + d] = l * dim + d;
      Ue[a][d] = u(l * dim + d, 0);
    }
  }
}

// Sums an element vector/matrix into overlap storage, skipping constrained rows.
// Atomic: cells running at the same time may share nodes. Without it the caller
// guarantees they do not (cells of one colour, see Assembler::color_cells).
template <bool WithTangent, bool Atomic, class RView, class Flags>
KOKKOS_INLINE_FUNCTION void scatter(int nd, const int* dofs, const double* re, const double (*ke)[kMaxCellDofs],
                                    const RView& r, const DeviceMatrix& K, const Flags& flag) {
  for (int i = 0; i < nd; ++i) {
    if (Atomic)
      Kokkos::atomic_add(&r(dofs[i], 0), re[i]);
    else
      r(dofs[i], 0) += re[i];
    // Rows are sorted (checked in build_graph): binary search for each node's first dof,
    // its other dofs are the next entries (the search hint finds them at once).
    if (WithTangent && !flag(dofs[i])) K.sumIntoValues(dofs[i], dofs, nd, ke[i], true, Atomic);
  }
}

// The law of every deck material (material/MaterialRegistry.hpp).
std::vector<Material> deck_laws(const Config& cfg) {
  std::vector<Material> laws;
  for (const MaterialConfig& m : cfg.materials) laws.push_back(make_material(m));
  return laws;
}

// Committed history rows of a block of law Law, at the law's initial values.
template <class Law>
Assembler::HistoryView initial_history(std::size_t rows) {
  Assembler::HistoryView h("history_committed", rows, Law::kNumHist);
  Kokkos::parallel_for(
      "stentor::init_history", Kokkos::RangePolicy<la::ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const int i) { stentor::init_history<Law>(&h(i, 0)); });
  return h;
}

// The element technology of the body owning physical group `group`; f-bar is refused, naming
// the body's parameter, on cells other than hex8.
ElementTechnology block_technology(const Config& cfg, const std::string& group, CellType type) {
  for (const auto& body : cfg.bodies) {
    if (body.group != group || !body.fbar()) continue;
    if (type != CellType::Hex8)
      throw InputError(cfg.deck_path + ": 'Bodies->" + body.name + "->element technology' = f-bar needs hex8 cells; physical group '" +
                       group + "' has " + cell_name(type) + " cells (mesh it with 'Mesh->recombine' = true, order 1, or a " +
                       "structured .geo with Recombine; or use 'full')");
    return ElementTechnology::FBar;
  }
  return ElementTechnology::Full;
}

}  // namespace

Assembler::Assembler(const Mesh& mesh, const Distribution& dist, const Config& cfg, const Loads& loads,
                     const std::vector<int>& block_material)
    : Assembler(mesh, dist, cfg, loads, block_material, deck_laws(cfg)) {}

Assembler::Assembler(const Mesh& mesh, const Distribution& dist, const Config& cfg, const Loads& loads,
                     const std::vector<int>& block_material, const std::vector<Material>& laws)
    : dist_(dist), loads_(loads), dim_(dist.dim()),
      kin_(cfg.problem.axisymmetric() ? Kinematics::Axisymmetric : Kinematics::Cartesian) {
  if (kin_ == Kinematics::Axisymmetric && dim_ != 2)
    throw InputError(cfg.deck_path + ": 'Problem->kinematics' = axisymmetric needs a 2D mesh in the (r, z) half plane; the mesh is " +
                     std::to_string(dim_) + "D");
  if (laws.size() != cfg.materials.size())
    throw std::logic_error("Assembler: " + std::to_string(laws.size()) + " laws for " + std::to_string(cfg.materials.size()) +
                           " materials");
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b) {
    const MaterialConfig& m = cfg.materials[static_cast<std::size_t>(block_material[b])];
    block_law_.push_back(laws[static_cast<std::size_t>(block_material[b])]);
    block_density_.push_back(m.density);
    // Viscosity acts only in dynamics (it needs a time step); statics pays nothing for it.
    block_eta_.push_back(cfg.any_dynamic() ? m.viscosity : 0.0);
    quad_degree_.push_back(default_quadrature_degree(mesh.volumes[b].type));
    block_tech_.push_back(block_technology(cfg, mesh.volumes[b].name, mesh.volumes[b].type));
  }
  if (cfg.problem.assembly == "coloring") color_cells();
  exporter_ = Teuchos::rcp(new la::Export(dist.overlap_map(), dist.owned_map()));
  u_overlap_ = Teuchos::rcp(new la::Vector(dist.overlap_map()));
  u0_overlap_ = Teuchos::rcp(new la::Vector(dist.overlap_map()));
  r_overlap_ = Teuchos::rcp(new la::Vector(dist.overlap_map()));
  rext_overlap_ = Teuchos::rcp(new la::Vector(dist.overlap_map()));
  r_static_ = Teuchos::rcp(new la::Vector(dist.owned_map()));
  f_ext_ = Teuchos::rcp(new la::Vector(dist.owned_map()));
  work_ = Teuchos::rcp(new la::Vector(dist.owned_map()));
  failures_ = Kokkos::View<int*, la::ExecSpace>("failures", 3);
  bad_cell_ = Kokkos::View<int*, la::ExecSpace>("bad_cell", 1);
  for (const auto& v : mesh.volumes) block_names_.push_back(v.name);
  build_graph();
  init_history();

  // Dirichlet flags (all overlap dofs, so ghost rows are skipped too) and owned values.
  const la::LO nloc = dist.num_local_nodes();
  dirichlet_flag_ = Kokkos::View<int*, la::ExecSpace>("dirichlet", static_cast<std::size_t>(nloc) * dim_);
  auto fh = Kokkos::create_mirror_view(dirichlet_flag_);
  Kokkos::deep_copy(fh, 0);
  std::vector<int> owned_set(static_cast<std::size_t>(dist.num_owned_nodes()) * dim_, -1);
  // The set a constrained dof's reaction is reported for: the first set in deck order that
  // constrains this component of this node (a node shared by two sets counts once).
  std::vector<int> first_set(owned_set.size(), -1);
  std::vector<double> owned_val(owned_set.size(), 0.0);
  for (std::size_t s = 0; s < loads.dirichlet.size(); ++s) {
    const DirichletSet& d = loads.dirichlet[s];
    if (d.normal) continue;  // setup_planes
    for (GId g : d.nodes) {
      const la::LO l = dist.local_node(g);
      if (l < 0) continue;
      const std::array<double, 3> value = d.field ? d.field(mesh.coord(g)) : d.values;
      for (int c = 0; c < dim_; ++c) {
        if (!d.components[static_cast<std::size_t>(c)]) continue;
        fh(static_cast<std::size_t>(l) * dim_ + c) = 1;
        if (l < dist.num_owned_nodes()) {  // later sets override earlier ones on shared nodes
          owned_set[static_cast<std::size_t>(l) * dim_ + c] = static_cast<int>(s);
          int& first = first_set[static_cast<std::size_t>(l) * dim_ + c];
          if (first < 0) first = static_cast<int>(s);
          owned_val[static_cast<std::size_t>(l) * dim_ + c] = value[static_cast<std::size_t>(c)];
        }
      }
    }
  }
  Kokkos::deep_copy(dirichlet_flag_, fh);
  for (std::size_t i = 0; i < owned_set.size(); ++i)
    if (owned_set[i] >= 0) {
      owned_dirichlet_dofs_.push_back(static_cast<la::LO>(i));
      owned_dirichlet_value_.push_back(owned_val[i]);
      owned_dirichlet_set_.push_back(owned_set[i]);
      owned_reaction_set_.push_back(first_set[i]);
    }
  owned_dirichlet_flag_.assign(owned_set.size(), 0);
  for (la::LO i : owned_dirichlet_dofs_) owned_dirichlet_flag_[static_cast<std::size_t>(i)] = 1;
  owned_cartesian_flag_ = owned_dirichlet_flag_;
  reactions_.assign(loads.dirichlet.size(), {0.0, 0.0, 0.0});
  setup_planes();
  setup_loads(mesh);
}

void Assembler::init_history() {
  // Views only for blocks whose law has history, and none at all without such a block.
  bool any = false;
  for (const auto& lb : dist_.blocks()) any = any || history_layout(block_law_[static_cast<std::size_t>(lb.volume_block)]).size > 0;
  if (!any) return;
  for (const auto& lb : dist_.blocks()) {
    BlockHistory bh;
    bh.ngp = make_rule(lb.type, stiffness_quadrature_degree(lb.type)).n;
    const std::size_t rows = lb.cell_ids.size() * static_cast<std::size_t>(bh.ngp);
    std::visit(
        [&](const auto& law) {
          using Law = std::decay_t<decltype(law)>;
          if constexpr (kHasHistory<Law>) {
            bh.committed = initial_history<Law>(rows);
            bh.trial = HistoryView("history_trial", rows, Law::kNumHist);
            Kokkos::deep_copy(bh.trial, bh.committed);
          }
        },
        block_law_[static_cast<std::size_t>(lb.volume_block)]);
    history_.push_back(bh);
  }
}

void Assembler::commit_history() {
  for (auto& bh : history_)
    if (bh.committed.extent(0) > 0) Kokkos::deep_copy(bh.committed, bh.trial);
}

void Assembler::rollback_history() {
  for (auto& bh : history_)
    if (bh.committed.extent(0) > 0) Kokkos::deep_copy(bh.trial, bh.committed);
}

Assembler::HistoryView Assembler::committed_history(std::size_t b) const {
  return b < history_.size() ? history_[b].committed : HistoryView();
}

Assembler::HistoryView Assembler::trial_history(std::size_t b) const {
  return b < history_.size() ? history_[b].trial : HistoryView();
}

void Assembler::build_graph() {
  // Node adjacency through cells, then one row per dof with all dofs of adjacent nodes.
  const la::LO nloc = dist_.num_local_nodes();
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(nloc));
  for (const auto& b : dist_.blocks()) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.conn);
    for (std::size_t c = 0; c < h.extent(0); ++c)
      for (int a = 0; a < b.nodes_per_cell; ++a)
        for (int bb = 0; bb < b.nodes_per_cell; ++bb) adj[static_cast<std::size_t>(h(c, a))].push_back(h(c, bb));
  }
  std::size_t maxrow = 0;
  for (auto& v : adj) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    maxrow = std::max(maxrow, v.size() * dim_);
  }
  // Overlap graph: column map = overlap map, so local column index = overlap dof index.
  auto overlap_graph = Teuchos::rcp(new Tpetra::CrsGraph<la::LO, la::GO, la::Node>(dist_.overlap_map(), dist_.overlap_map(), maxrow));
  std::vector<la::LO> cols;
  for (la::LO n = 0; n < nloc; ++n) {
    cols.clear();
    for (int m : adj[static_cast<std::size_t>(n)])
      for (int d = 0; d < dim_; ++d) cols.push_back(m * dim_ + d);
    for (int d = 0; d < dim_; ++d) overlap_graph->insertLocalIndices(n * dim_ + d, Teuchos::ArrayView<const la::LO>(cols));
  }
  overlap_graph->fillComplete(dist_.owned_map(), dist_.owned_map());
  if (!overlap_graph->isSorted())
    throw std::logic_error("Assembler: the overlap graph's rows are not sorted (the element scatter relies on it)");
  K_overlap_ = Teuchos::rcp(new la::CrsMatrix(overlap_graph));
  K_overlap_->fillComplete(dist_.owned_map(), dist_.owned_map());

  auto owned_graph = Teuchos::rcp(new Tpetra::CrsGraph<la::LO, la::GO, la::Node>(dist_.owned_map(), 0));
  owned_graph->doExport(*overlap_graph, *exporter_, Tpetra::INSERT);
  owned_graph->fillComplete(dist_.owned_map(), dist_.owned_map());
  K_ = Teuchos::rcp(new la::CrsMatrix(owned_graph));
  K_->fillComplete(dist_.owned_map(), dist_.owned_map());

  // Moving the summed overlap matrix into the owned one. Owned nodes come first in the
  // overlap numbering, so the overlap matrix's owned rows are its first rows and the
  // owned matrix has every one of their entries: for those, a precomputed position in the
  // owned matrix's value array (a threaded copy, no global index lookups). Only the ghost
  // rows (the tail of the value array) travel by a Tpetra export, from a matrix holding
  // just them. (Exporting the whole overlap matrix cost 14-35% of a residual+tangent call
  // even on one rank, see docs/performance.md.)
  {
    const la::LO n_owned_rows = static_cast<la::LO>(dist_.owned_map()->getNodeNumElements());
    auto ov = K_overlap_->getLocalMatrixHost();
    auto ow = K_->getLocalMatrixHost();
    const auto ocol = K_overlap_->getColMap(), wcol = K_->getColMap();
    const std::size_t n_owned_entries = ov.graph.row_map(n_owned_rows);
    owned_value_pos_ = Kokkos::View<std::size_t*, la::ExecSpace>("owned_value_pos", n_owned_entries);
    auto pos = Kokkos::create_mirror_view(owned_value_pos_);
    for (la::LO row = 0; row < n_owned_rows; ++row) {
      const std::size_t b = ow.graph.row_map(row), e = ow.graph.row_map(row + 1);
      for (std::size_t j = ov.graph.row_map(row); j < ov.graph.row_map(row + 1); ++j) {
        const la::LO c = wcol->getLocalElement(ocol->getGlobalElement(ov.graph.entries(j)));
        std::size_t k = b;
        while (k < e && ow.graph.entries(k) != c) ++k;
        if (c == Teuchos::OrdinalTraits<la::LO>::invalid() || k == e)
          throw std::logic_error("Assembler: an owned row of the overlap matrix has an entry the owned matrix lacks");
        pos(j) = k;
      }
    }
    Kokkos::deep_copy(owned_value_pos_, pos);

    // Ghost rows: a matrix on the ghost dofs only, same column map and column pattern as
    // the overlap matrix, so its value array is the overlap's value array past the owned rows.
    const std::size_t n_all_rows = dist_.overlap_map()->getNodeNumElements();
    std::vector<la::GO> ghost_gids;
    for (std::size_t row = static_cast<std::size_t>(n_owned_rows); row < n_all_rows; ++row)
      ghost_gids.push_back(dist_.overlap_map()->getGlobalElement(static_cast<la::LO>(row)));
    ghost_map_ = Teuchos::rcp(new la::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                          Teuchos::ArrayView<const la::GO>(ghost_gids), 0, dist_.comm()));
    const std::size_t n_ghost_rows = ghost_gids.size();
    Kokkos::View<std::size_t*, la::ExecSpace> rowptr("ghost_rowptr", n_ghost_rows + 1);
    Kokkos::View<la::LO*, la::ExecSpace> cols("ghost_cols", ov.graph.entries.extent(0) - n_owned_entries);
    Kokkos::View<double*, la::ExecSpace> vals("ghost_vals", cols.extent(0));
    {
      auto rh = Kokkos::create_mirror_view(rowptr);
      auto ch = Kokkos::create_mirror_view(cols);
      for (std::size_t r = 0; r <= n_ghost_rows; ++r) rh(r) = ov.graph.row_map(static_cast<std::size_t>(n_owned_rows) + r) - n_owned_entries;
      for (std::size_t j = 0; j < ch.extent(0); ++j) ch(j) = ov.graph.entries(n_owned_entries + j);
      Kokkos::deep_copy(rowptr, rh);
      Kokkos::deep_copy(cols, ch);
    }
    K_ghost_ = Teuchos::rcp(new la::CrsMatrix(ghost_map_, ocol, rowptr, cols, vals));
    K_ghost_->fillComplete(dist_.owned_map(), dist_.owned_map());
    ghost_exporter_ = Teuchos::rcp(new la::Export(ghost_map_, dist_.owned_map()));
  }
}

void Assembler::color_cells() {
  // Greedy colouring of each block's cells so that no two cells of a colour share a node:
  // a cell takes the lowest colour none of its nodes has seen yet. Per node a bit set of
  // the colours already used there (kMaxColors bits). Colours are then stored as ranges
  // of a permutation of the block's cells, in the original order within each colour.
  constexpr int kWords = kMaxColors / 64;
  const auto nloc = static_cast<std::size_t>(dist_.num_local_nodes());
  colors_.clear();
  for (const auto& b : dist_.blocks()) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.conn);
    const std::size_t nc = h.extent(0);
    std::vector<std::uint64_t> used(nloc * kWords, 0);
    std::vector<int> color(nc, 0);
    int ncolors = 0;
    for (std::size_t c = 0; c < nc; ++c) {
      std::uint64_t forbidden[kWords] = {};
      for (int a = 0; a < b.nodes_per_cell; ++a)
        for (int w = 0; w < kWords; ++w) forbidden[w] |= used[static_cast<std::size_t>(h(c, a)) * kWords + w];
      int k = 0;
      while (k < kMaxColors && (forbidden[k / 64] >> (k % 64) & 1u)) ++k;
      if (k == kMaxColors)
        throw std::runtime_error("Problem->assembly = coloring: a cell needs more than " + std::to_string(kMaxColors) +
                                 " colours (nodes shared by very many cells); use assembly = atomic");
      color[c] = k;
      ncolors = std::max(ncolors, k + 1);
      for (int a = 0; a < b.nodes_per_cell; ++a) used[static_cast<std::size_t>(h(c, a)) * kWords + k / 64] |= std::uint64_t{1} << (k % 64);
    }
    BlockColors bc;
    bc.offsets.assign(static_cast<std::size_t>(ncolors) + 1, 0);
    for (std::size_t c = 0; c < nc; ++c) ++bc.offsets[static_cast<std::size_t>(color[c]) + 1];
    for (int k = 0; k < ncolors; ++k) bc.offsets[static_cast<std::size_t>(k) + 1] += bc.offsets[static_cast<std::size_t>(k)];
    bc.cells = Kokkos::View<int*, la::ExecSpace>("colored_cells", nc);
    auto ch = Kokkos::create_mirror_view(bc.cells);
    std::vector<std::size_t> next(bc.offsets.begin(), bc.offsets.end() - 1);
    for (std::size_t c = 0; c < nc; ++c) ch(next[static_cast<std::size_t>(color[c])]++) = static_cast<int>(c);
    Kokkos::deep_copy(bc.cells, ch);
    colors_.push_back(std::move(bc));
  }
}

int Assembler::num_colors() const {
  std::size_t n = 0;
  for (const auto& bc : colors_) n = std::max(n, bc.offsets.empty() ? 0 : bc.offsets.size() - 1);
  return static_cast<int>(n);
}

std::vector<int> Assembler::cell_colors(std::size_t b) const {
  if (b >= colors_.size()) return {};
  const BlockColors& bc = colors_[b];
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), bc.cells);
  std::vector<int> color(h.extent(0), -1);
  for (std::size_t k = 0; k + 1 < bc.offsets.size(); ++k)
    for (std::size_t i = bc.offsets[k]; i < bc.offsets[k + 1]; ++i) color[static_cast<std::size_t>(h(i))] = static_cast<int>(k);
  return color;
}

void Assembler::setup_loads(const Mesh& mesh) {
  std::unordered_set<GId> local_cells;
  for (const auto& b : dist_.blocks()) local_cells.insert(b.cell_ids.begin(), b.cell_ids.end());
  const auto Xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dist_.coords());

  for (const FacetLoad& fl : loads_.facet_loads) {
    std::vector<std::size_t> mine;
    for (std::size_t f = 0; f < fl.num_facets(); ++f)
      if (local_cells.count(fl.adjacent_cell[f])) mine.push_back(f);
    const int nn = fl.nodes_per_facet;
    const QuadRule q = make_rule(fl.facet_type, 2 * cell_order(fl.facet_type) + 1);
    if (fl.type == LoadConfig::Type::Traction) {
      // Dead traction on the reference surface: f_a = int N_a t dA, assembled once.
      DeadLoad dl{fl.ramp, Teuchos::rcp(new la::Vector(dist_.overlap_map()))};
      auto f = dl.f->getLocalViewHost(Tpetra::Access::ReadWrite);
      for (std::size_t f_i : mine) {
        double X[kMaxCellNodes][3], N[kMaxCellNodes], dN[kMaxCellNodes][3], n[3];
        int l[kMaxCellNodes];
        for (int a = 0; a < nn; ++a) {
          l[a] = dist_.local_node(fl.conn[f_i * nn + a]);
          for (int d = 0; d < 3; ++d) X[a][d] = Xh(l[a], d);
        }
        for (int g = 0; g < q.n; ++g) {
          shape_functions(fl.facet_type, q.xi[g], N, dN);
          double dA = facet_measure_and_normal(dim_, nn, X, dN, n);
          dA = volume_weight(kin_, dA, reference_radius(kin_, nn, N, X));  // axisymmetric: the revolved area
          for (int a = 0; a < nn; ++a)
            for (int d = 0; d < dim_; ++d) f(l[a] * dim_ + d, 0) += q.w[g] * dA * N[a] * fl.traction[static_cast<std::size_t>(d)];
        }
      }
      dead_.push_back(dl);
    } else {
      PressureLoad pl;
      pl.ramp = fl.ramp;
      pl.pressure = fl.pressure;
      pl.cavity = fl.cavity;
      pl.type = fl.facet_type;
      pl.nn = nn;
      pl.conn = Kokkos::View<int**, Kokkos::LayoutRight, la::ExecSpace>("pconn", mine.size(), nn);
      pl.orientation = Kokkos::View<double*, la::ExecSpace>("porient", mine.size());
      auto ch = Kokkos::create_mirror_view(pl.conn);
      auto oh = Kokkos::create_mirror_view(pl.orientation);
      for (std::size_t i = 0; i < mine.size(); ++i) {
        for (int a = 0; a < nn; ++a) ch(i, a) = dist_.local_node(fl.conn[mine[i] * nn + a]);
        oh(i) = fl.orientation[mine[i]];
      }
      Kokkos::deep_copy(pl.conn, ch);
      Kokkos::deep_copy(pl.orientation, oh);
      pressures_.push_back(pl);
    }
  }
  for (const BodyForce& bf : loads_.body_forces) {
    DeadLoad dl{bf.ramp, Teuchos::rcp(new la::Vector(dist_.overlap_map()))};
    auto f = dl.f->getLocalViewHost(Tpetra::Access::ReadWrite);
    for (const auto& lb : dist_.blocks()) {
      if (std::find(bf.volume_blocks.begin(), bf.volume_blocks.end(), lb.volume_block) == bf.volume_blocks.end()) continue;
      const QuadRule q = make_rule(lb.type, quad_degree_[static_cast<std::size_t>(lb.volume_block)]);
      auto conn = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lb.conn);
      const int nn = lb.nodes_per_cell;
      for (std::size_t c = 0; c < conn.extent(0); ++c) {
        double X[kMaxCellNodes][3], N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
        for (int a = 0; a < nn; ++a)
          for (int d = 0; d < 3; ++d) X[a][d] = Xh(conn(c, a), d);
        for (int g = 0; g < q.n; ++g) {
          shape_functions(lb.type, q.xi[g], N, dN);
          const double detJ = volume_weight(kin_, reference_gradients(dim_, nn, X, dN, dNdX), reference_radius(kin_, nn, N, X));
          std::array<double, 3> force = bf.force;
          if (bf.field) {
            double xq[3] = {0, 0, 0};
            for (int a = 0; a < nn; ++a)
              for (int d = 0; d < 3; ++d) xq[d] += N[a] * X[a][d];
            force = bf.field(xq);
          }
          for (int a = 0; a < nn; ++a)
            for (int d = 0; d < dim_; ++d) f(conn(c, a) * dim_ + d, 0) += q.w[g] * detJ * N[a] * force[static_cast<std::size_t>(d)];
        }
      }
    }
    dead_.push_back(dl);
  }
  (void)mesh;
  for (const FluidCavitySpec& spec : loads_.cavities) cavities_.push_back(Cavity{spec});
  for (std::size_t k = 0; k < cavities_.size(); ++k) {
    cavities_[k].V0 = cavity_volume(k, true);
    if (!(cavities_[k].V0 > 0.0))
      throw InputError("'Boundary Conditions->" + cavities_[k].spec.name + "': the cavity enclosed by group '" + cavities_[k].spec.group +
                       "' about its axis has volume " + std::to_string(cavities_[k].V0) +
                       " in the mesh (expected > 0: is the axis inside the wall, and does the group bound the cavity?)");
  }
}

void Assembler::apply_dirichlet(la::Vector& u, double t, double end_time) const {
  {
    auto uh = u.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (std::size_t i = 0; i < owned_dirichlet_dofs_.size(); ++i) {
      const DirichletSet& d = loads_.dirichlet[static_cast<std::size_t>(owned_dirichlet_set_[i])];
      uh(owned_dirichlet_dofs_[i], 0) = owned_dirichlet_value_[i] * d.ramp(t, end_time);
    }
  }
  apply_planes(u, t, end_time);
}

double Assembler::support_work(const la::Vector& du) const {
  auto dh = du.getLocalViewHost(Tpetra::Access::ReadOnly);
  double loc = 0.0, glob = 0.0;
  for (std::size_t k = 0; k < dirichlet_r_.size(); ++k) loc += dirichlet_r_[k] * dh(owned_dirichlet_dofs_[k], 0);
  for (std::size_t k = 0; k < plane_r_.size(); ++k)
    for (int i = 0; i < planes_[k].m; ++i)
      for (int c = 0; c < dim_; ++c) loc += plane_r_[k][static_cast<std::size_t>(i)] * planes_[k].e[i][c] * dh(planes_[k].lid * dim_ + c, 0);
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &loc, &glob);
  return glob;
}

bool Assembler::is_dirichlet(la::LO owned_dof) const { return owned_dirichlet_flag_[static_cast<std::size_t>(owned_dof)] != 0; }

const la::RCP<la::CrsMatrix>& Assembler::mass() {
  if (!M_.is_null()) return M_;
  // Consistent mass, assembled once (overlap -> owned, like the tangent). All rows are
  // kept: inertia of constrained nodes enters their reactions.
  auto M_overlap = Teuchos::rcp(new la::CrsMatrix(K_overlap_->getCrsGraph()));
  M_overlap->fillComplete(dist_.owned_map(), dist_.owned_map());
  auto Ml = M_overlap->getLocalMatrixDevice();
  Kokkos::deep_copy(Ml.values, 0.0);
  const int dim = dim_;
  const Kinematics kin = kin_;
  auto X = dist_.coords();
  for (const auto& lb : dist_.blocks()) {
    const std::size_t nc = lb.cell_ids.size();
    const double rho = block_density_[static_cast<std::size_t>(lb.volume_block)];
    if (nc == 0 || rho == 0.0) continue;
    const QuadRule q = make_rule(lb.type, quad_degree_[static_cast<std::size_t>(lb.volume_block)]);
    const CellType type = lb.type;
    const int nn = lb.nodes_per_cell;
    auto conn = lb.conn;
    Kokkos::parallel_for(
        "stentor::mass", Kokkos::RangePolicy<la::ExecSpace>(0, nc), KOKKOS_LAMBDA(const int c) {
          double Xe[kMaxCellNodes][3], me[kMaxCellDofs][kMaxCellDofs];
          int dofs[kMaxCellDofs];
          for (int a = 0; a < nn; ++a) {
            const int l = conn(c, a);
            for (int d = 0; d < 3; ++d) Xe[a][d] = X(l, d);
            for (int d = 0; d < dim; ++d) dofs[a * dim + d] = l * dim + d;
          }
          mass_element(dim, kin, type, nn, Xe, rho, q, me);
          for (int i = 0; i < nn * dim; ++i) Ml.sumIntoValues(dofs[i], dofs, nn * dim, me[i], true, true);
        });
  }
  M_ = Teuchos::rcp(new la::CrsMatrix(K_->getCrsGraph()));
  M_->resumeFill();
  M_->setAllToScalar(0.0);
  M_->doExport(*M_overlap, *exporter_, Tpetra::ADD);
  M_->fillComplete(dist_.owned_map(), dist_.owned_map());
  return M_;
}

std::string Assembler::describe_failed(GId gid, std::size_t block, int cell) const {
  GId loc = gid, glob = 0;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MIN, 1, &loc, &glob);
  // The rank holding that cell sends its block and centre (a sum with zeros elsewhere).
  double v[4] = {0, 0, 0, 0}, w[4] = {0, 0, 0, 0};
  if (cell >= 0 && gid == glob) {
    const auto& lb = dist_.blocks()[block];
    auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dist_.coords());
    auto conn = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lb.conn);
    const int nn = lb.nodes_per_cell;
    for (int a = 0; a < nn; ++a)
      for (int d = 0; d < dim_; ++d) v[d] += X(conn(cell, a), d) / nn;
    v[3] = static_cast<double>(lb.volume_block) + 1.0;
  }
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 4, v, w);
  std::ostringstream os;
  os.precision(4);
  os << "cell " << glob;
  if (w[3] > 0.0) os << " of '" << block_names_[static_cast<std::size_t>(w[3]) - 1] << "'";
  os << " (reference centre " << w[0] << ", " << w[1];
  if (dim_ == 3) os << ", " << w[2];
  os << ")";
  return os.str();
}

// The solid cells of every local block: each cell's residual (and, with_tangent, its tangent
// into Kl) scattered into r_overlap_, one kernel launch per block compiled for the block's law;
// the sums of the strain energy, the viscous and the plastic dissipation; the failed cell of
// smallest global id (bad_local = -1: none).
Assembler::CellSums Assembler::assemble_cells(const StepInput& in, bool has_old, bool with_tangent, const DeviceMatrix& Kl) {
  const int dim = dim_;
  const Kinematics kin = kin_;
  auto flags = dirichlet_flag_;
  auto fails = failures_;
  auto bad = bad_cell_;
  auto X = dist_.coords();
  CellSums sums;
  auto uv = u_overlap_->getLocalViewDevice(Tpetra::Access::ReadOnly);
  auto u0v = u0_overlap_->getLocalViewDevice(Tpetra::Access::ReadOnly);
  auto rv = r_overlap_->getLocalViewDevice(Tpetra::Access::ReadWrite);
  for (std::size_t bi = 0; bi < dist_.blocks().size(); ++bi) {
    const auto& lb = dist_.blocks()[bi];
    const std::size_t nc = lb.cell_ids.size();
    if (nc == 0) continue;
    const QuadRule q = make_rule(lb.type, stiffness_quadrature_degree(lb.type));
    ElementTime et;
    et.eval = in.eval;
    et.dt = in.dt;
    // Viscosity needs a step (dt > 0): the initial-state assembly (dt = 0) has none (it was 0/0 = NaN).
    et.eta = in.dt > 0.0 ? block_eta_[static_cast<std::size_t>(lb.volume_block)] : 0.0;
    et.has_old = has_old && (in.eval != StressEval::EndPoint || et.eta > 0.0);
    const CellType type = lb.type;
    const ElementTechnology tech = block_tech_[static_cast<std::size_t>(lb.volume_block)];
    const int nn = lb.nodes_per_cell;
    auto conn = lb.conn;
    double e_block = 0.0;
    Kokkos::View<double*, la::ExecSpace> dsum("dissipation", 2);  // viscous, plastic
    // One launch per block, compiled for the block's law type; a block whose law has
    // Gauss-point history reads its committed rows and writes its trial rows (cell c:
    // rows c * ngp ...).
    auto launch = [&](const auto& law) {
      constexpr bool H = kHasHistory<std::decay_t<decltype(law)>>;
      HistoryView hn, h1;
      int ngp = 0, nh = 0;
      if (H) {
        hn = history_[bi].committed;
        h1 = history_[bi].trial;
        ngp = history_[bi].ngp;
        nh = static_cast<int>(hn.extent(1));
      }
      auto body = [=](const int c, double& e, auto tangent_tag, auto atomic_tag) {
        constexpr bool T = decltype(tangent_tag)::value;
        constexpr bool A = decltype(atomic_tag)::value;
        double Xe[kMaxCellNodes][3], Ue[kMaxCellNodes][3], U0e[kMaxCellNodes][3], re[kMaxCellDofs];
        double ke[T ? kMaxCellDofs : 1][kMaxCellDofs];
        int dofs[kMaxCellDofs];
        gather_cell(c, nn, dim, conn, X, uv, Xe, Ue, dofs);
        if (et.has_old)
          for (int a = 0; a < nn; ++a)
            for (int d = 0; d < 3; ++d) U0e[a][d] = d < dim ? u0v(dofs[a * dim] + d, 0) : 0.0;
        double ec = 0.0, dc = 0.0, pc = 0.0;
        int status;
        if constexpr (H)
          status = solid_element<T>(dim, kin, tech, type, nn, Xe, Ue, U0e, law, et, q, re, ke, ec, dc,
                                    CellHistory{&hn(c * ngp, 0), &h1(c * ngp, 0), nh}, &pc);
        else
          status = solid_element<T>(dim, kin, tech, type, nn, Xe, Ue, U0e, law, et, q, re, ke, ec, dc);
        if (status != kElementOk) {
          Kokkos::atomic_increment(&fails(status == kElementInverted ? 0 : status == kElementLocalFailure ? 2 : 1));
          Kokkos::atomic_fetch_min(&bad(0), c);
          return;
        }
        e += ec;
        if (dc != 0.0) Kokkos::atomic_add(&dsum(0), dc);
        if (H && pc != 0.0) Kokkos::atomic_add(&dsum(1), pc);
        scatter<T, A>(nn * dim, dofs, re, ke, rv, Kl, flags);
      };
      if (colors_.empty()) {
        // Atomic sums: all cells in one kernel.
        if (with_tangent)
          Kokkos::parallel_reduce(
              "stentor::solid_residual_tangent", Kokkos::RangePolicy<la::ExecSpace>(0, nc),
              KOKKOS_LAMBDA(const int c, double& e) { body(c, e, std::true_type{}, std::true_type{}); }, e_block);
        else
          Kokkos::parallel_reduce(
              "stentor::solid_residual", Kokkos::RangePolicy<la::ExecSpace>(0, nc),
              KOKKOS_LAMBDA(const int c, double& e) { body(c, e, std::false_type{}, std::true_type{}); }, e_block);
      } else {
        // One kernel per colour: its cells share no node, so plain sums are race-free.
        const BlockColors& bc = colors_[bi];
        auto cells = bc.cells;
        for (std::size_t k = 0; k + 1 < bc.offsets.size(); ++k) {
          double e_color = 0.0;
          const Kokkos::RangePolicy<la::ExecSpace> range(bc.offsets[k], bc.offsets[k + 1]);
          if (with_tangent)
            Kokkos::parallel_reduce(
                "stentor::solid_residual_tangent_colored", range,
                KOKKOS_LAMBDA(const int i, double& e) { body(cells(i), e, std::true_type{}, std::false_type{}); }, e_color);
          else
            Kokkos::parallel_reduce(
                "stentor::solid_residual_colored", range,
                KOKKOS_LAMBDA(const int i, double& e) { body(cells(i), e, std::false_type{}, std::false_type{}); }, e_color);
          e_block += e_color;
        }
      }
    };
    Kokkos::deep_copy(bad, std::numeric_limits<int>::max());
    std::visit(launch, block_law_[static_cast<std::size_t>(lb.volume_block)]);
    auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), bad);
    if (bh(0) != std::numeric_limits<int>::max() && lb.cell_ids[static_cast<std::size_t>(bh(0))] < sums.bad_gid) {
      sums.bad_gid = lb.cell_ids[static_cast<std::size_t>(bh(0))];
      sums.bad_block = bi;
      sums.bad_local = bh(0);
    }
    auto dh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dsum);
    sums.energy += e_block;
    sums.dissipation += dh(0);
    sums.plastic += dh(1);
  }
  return sums;
}

// Follower pressures p on the current surface (configuration u_n + theta (u - u_n);
// assembly/PressureElement.hpp) into rext_overlap_ (and Kl).
void Assembler::assemble_pressures(const StepInput& in, bool has_old, bool with_tangent, const DeviceMatrix& Kl) {
  const int dim = dim_;
  const Kinematics kin = kin_;
  auto flags = dirichlet_flag_;
  auto X = dist_.coords();
  auto uv = u_overlap_->getLocalViewDevice(Tpetra::Access::ReadOnly);
  auto u0v = u0_overlap_->getLocalViewDevice(Tpetra::Access::ReadOnly);
  auto rxv = rext_overlap_->getLocalViewDevice(Tpetra::Access::ReadWrite);
  const double theta = has_old ? in.pressure_theta : 1.0;
  for (const auto& pl : pressures_) {
    const double p = pl.cavity >= 0 ? cavities_[static_cast<std::size_t>(pl.cavity)].p : pl.pressure * pl.ramp(in.load_time, in.end_time);
    const std::size_t nf = pl.conn.extent(0);
    if (nf == 0 || p == 0.0) continue;
    const QuadRule q = make_rule(pl.type, 2 * cell_order(pl.type) + 1);
    const CellType type = pl.type;
    const int nn = pl.nn;
    auto conn = pl.conn;
    auto orient = pl.orientation;
    const bool T = with_tangent;
    Kokkos::parallel_for(
        "stentor::follower_pressure", Kokkos::RangePolicy<la::ExecSpace>(0, nf), KOKKOS_LAMBDA(const int f) {
          double Xe[kMaxCellNodes][3], Ue[kMaxCellNodes][3], re[kMaxCellDofs], ke[kMaxCellDofs][kMaxCellDofs];
          int dofs[kMaxCellDofs];
          gather_cell(f, nn, dim, conn, X, uv, Xe, Ue, dofs);
          if (theta != 1.0)
            for (int a = 0; a < nn; ++a)
              for (int d = 0; d < dim; ++d) Ue[a][d] = theta * Ue[a][d] + (1.0 - theta) * u0v(dofs[a * dim] + d, 0);
          const int nd = nn * dim;
          pressure_element(dim, kin, type, nn, Xe, Ue, p * orient(f), theta, q, re, ke);
          if (T)
            scatter<true, true>(nd, dofs, re, ke, rxv, Kl, flags);
          else
            scatter<false, true>(nd, dofs, re, ke, rxv, Kl, flags);
        });
  }
}

// The reactions of the Dirichlet sets from the owned residual r, then its constrained rows
// zeroed (and those of the planes projected).
void Assembler::constrain_residual(la::Vector& r) {
  std::vector<double> loc(3 * reactions_.size(), 0.0), glob(loc.size(), 0.0);
  {
    auto rh = r.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (std::size_t k = 0; k < owned_dirichlet_dofs_.size(); ++k) {
      const la::LO i = owned_dirichlet_dofs_[k];
      loc[3 * static_cast<std::size_t>(owned_reaction_set_[k]) + static_cast<std::size_t>(i % dim_)] += rh(i, 0);
    }
    dirichlet_r_.resize(owned_dirichlet_dofs_.size());
    for (std::size_t k = 0; k < owned_dirichlet_dofs_.size(); ++k) {
      dirichlet_r_[k] = rh(owned_dirichlet_dofs_[k], 0);
      rh(owned_dirichlet_dofs_[k], 0) = 0.0;
    }
  }
  project_plane_rows(r, loc);
  if (!loc.empty()) Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), glob.data());
  for (std::size_t s = 0; s < reactions_.size(); ++s) reactions_[s] = {glob[3 * s], glob[3 * s + 1], glob[3 * s + 2]};
}

// The owned tangent from Kl: identity rows for the owned constrained dofs, the overlap's
// owned rows moved into K_ and its ghost rows exported (ADD), s K + c M on the free rows, the
// planes' rows projected, the cavities' rank-one terms.
void Assembler::finish_tangent(const StepInput& in, const DeviceMatrix& Kl) {
  auto flags = dirichlet_flag_;
  // Identity on owned constrained rows (owned dofs are a prefix of the overlap dofs).
  const la::LO ndir = static_cast<la::LO>(owned_dirichlet_dofs_.size());
  Kokkos::View<la::LO*, la::ExecSpace> rows("dirichlet_rows", ndir);
  auto rh = Kokkos::create_mirror_view(rows);
  for (la::LO i = 0; i < ndir; ++i) rh(i) = owned_dirichlet_dofs_[static_cast<std::size_t>(i)];
  Kokkos::deep_copy(rows, rh);
  Kokkos::parallel_for(
      "stentor::dirichlet_rows", Kokkos::RangePolicy<la::ExecSpace>(0, ndir), KOKKOS_LAMBDA(const int i) {
        const la::LO row = rows(i);
        const double one = 1.0;
        Kl.replaceValues(row, &row, 1, &one, true, true);
      });
  K_->resumeFill();
  {
    // Owned rows: scatter the overlap values to their precomputed positions (all
    // distinct, so no atomics); ghost rows: copy the overlap value tail, export (ADD).
    auto Kw = K_->getLocalMatrixDevice();
    auto Kg = K_ghost_->getLocalMatrixDevice();
    auto posv = owned_value_pos_;
    Kokkos::deep_copy(Kw.values, 0.0);
    const std::size_t n_owned_entries = posv.extent(0);
    Kokkos::parallel_for(
        "stentor::owned_rows_to_owned_matrix", Kokkos::RangePolicy<la::ExecSpace>(0, n_owned_entries),
        KOKKOS_LAMBDA(const std::size_t j) { Kw.values(posv(j)) = Kl.values(j); });
    Kokkos::deep_copy(Kg.values, Kokkos::subview(Kl.values, Kokkos::make_pair(n_owned_entries, Kl.values.extent(0))));
    Kokkos::fence();
    K_->doExport(*K_ghost_, *ghost_exporter_, Tpetra::ADD);
  }
  if (in.scale != 1.0 || in.mass_coeff != 0.0) {
    // K = s K + c M on unconstrained rows (K and M share one graph, so their local
    // value arrays line up entry by entry).
    auto Kv = K_->getLocalMatrixDevice();
    const double s = in.scale, c = in.mass_coeff;
    DeviceMatrix Mv;
    if (c != 0.0) Mv = mass()->getLocalMatrixDevice();
    auto oflag = flags;  // owned dofs are the first rows of the overlap flags
    Kokkos::parallel_for(
        "stentor::tangent_plus_mass", Kokkos::RangePolicy<la::ExecSpace>(0, Kv.numRows()), KOKKOS_LAMBDA(const int row) {
          if (oflag(row)) return;
          for (auto j = Kv.graph.row_map(row); j < Kv.graph.row_map(row + 1); ++j)
            Kv.values(j) = s * Kv.values(j) + (c != 0.0 ? c * Mv.values(j) : 0.0);
        });
  }
  project_plane_matrix();
  K_->fillComplete(dist_.owned_map(), dist_.owned_map());
  update_cavity_gradients();
}

Assembler::Stats Assembler::assemble(const la::Vector& u, const StepInput& in, la::Vector& r, bool with_tangent) {
  u_overlap_->doImport(u, *dist_.importer(), Tpetra::INSERT);
  const bool has_old = in.u_old != nullptr;
  if (has_old) u0_overlap_->doImport(*in.u_old, *dist_.importer(), Tpetra::INSERT);
  r_overlap_->putScalar(0.0);
  rext_overlap_->putScalar(0.0);
  Kokkos::deep_copy(failures_, 0);
  update_cavities(in);
  DeviceMatrix Kl;
  if (with_tangent) {
    Kl = K_overlap_->getLocalMatrixDevice();
    Kokkos::deep_copy(Kl.values, 0.0);
  }
  const CellSums sums = assemble_cells(in, has_old, with_tangent, Kl);
  assemble_pressures(in, has_old, with_tangent, Kl);
  // Dead loads: -f_ext contribution = -ramp(t) f.
  for (const auto& dl : dead_) rext_overlap_->update(-dl.ramp(in.load_time, in.end_time), *dl.f, 1.0);
  r_overlap_->update(1.0, *rext_overlap_, 1.0);

  auto fh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), failures_);
  long local_fail[3] = {fh(0), fh(1), fh(2)}, global_fail[3] = {0, 0, 0};
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 3, local_fail, global_fail);
  if (global_fail[1] > 0)
    throw std::runtime_error(std::to_string(global_fail[1]) + " cells have a non-positive reference Jacobian (mesh check missed them)");
  Stats st;
  double loc3[3] = {sums.energy, sums.dissipation, sums.plastic}, glob3[3] = {0, 0, 0};
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 3, loc3, glob3);
  st.energy = glob3[0];
  st.dissipation = glob3[1];
  st.plastic_dissipation = glob3[2];
  st.inverted = global_fail[0] + global_fail[2];  // a failed return map is inadmissible like an inverted cell
  if (st.inverted > 0) {
    st.first_failed = describe_failed(sums.bad_gid, sums.bad_block, sums.bad_local);
    return st;
  }

  r_static_->putScalar(0.0);
  r_static_->doExport(*r_overlap_, *exporter_, Tpetra::ADD);
  f_ext_->putScalar(0.0);
  f_ext_->doExport(*rext_overlap_, *exporter_, Tpetra::ADD);
  f_ext_->scale(-1.0);
  r.update(in.scale, *r_static_, 0.0);
  if (in.mass_coeff != 0.0) {
    // Inertia c M (u - u_tilde).
    work_->update(1.0, u, -1.0, *in.u_tilde, 0.0);
    mass()->apply(*work_, r, Teuchos::NO_TRANS, in.mass_coeff, 1.0);
  }
  if (in.extra) r.update(1.0, *in.extra, 1.0);
  constrain_residual(r);
  if (with_tangent) finish_tangent(in, Kl);
  return st;
}

Assembler::DofReactions Assembler::dof_reactions() const {
  DofReactions d;
  for (std::size_t k = 0; k < owned_dirichlet_dofs_.size() && k < dirichlet_r_.size(); ++k) {
    const la::LO i = owned_dirichlet_dofs_[k];
    d.nodes.push_back(dist_.global_node(i / dim_));
    d.components.push_back(static_cast<int>(i % dim_));
    d.values.push_back(dirichlet_r_[k]);
  }
  for (std::size_t k = 0; k < planes_.size() && k < plane_r_.size(); ++k) {
    const PlaneNode& p = planes_[k];
    for (int c = 0; c < dim_; ++c) {
      if (is_dirichlet(p.lid * dim_ + c) && std::find(p.j, p.j + p.m, c) == p.j + p.m) continue;  // Cartesian: listed above
      double v = 0.0;
      for (int i = 0; i < p.m; ++i) v += plane_r_[k][static_cast<std::size_t>(i)] * p.e[i][c];
      d.nodes.push_back(dist_.global_node(p.lid));
      d.components.push_back(c);
      d.values.push_back(v);
    }
  }
  return d;
}

namespace {

// Columns of the cell_fields kernel's result: stress (6), von Mises, J, volume, the history
// averages (nx), then the requested strains and principal stresses.
struct CellColumns {
  int extra = 9, green_lagrange = -1, log_strain = -1, principal = -1, total = 9;
  CellColumns(int nx, const Assembler::CellFieldRequest& req) {
    total = extra + nx;
    if (req.green_lagrange) green_lagrange = total, total += 6;
    if (req.log_strain) log_strain = total, total += 6;
    if (req.principal) principal = total, total += 3;
  }
};

template <class Row>
KOKKOS_INLINE_FUNCTION void put_sym(const Row& res, int c, int col, const Mat3& m) {
  res(c, col) = m(0, 0), res(c, col + 1) = m(1, 1), res(c, col + 2) = m(2, 2);
  res(c, col + 3) = m(0, 1), res(c, col + 4) = m(1, 2), res(c, col + 5) = m(0, 2);
}

// The kernel's rows (host copy) appended to `out`, field by field.
template <class Rows>
void append_cell_rows(const Rows& h, std::size_t nc, const CellColumns& col, int nx, Assembler::CellFields& out) {
  auto take = [&](std::vector<double>& v, std::size_t c, int at, int n) {
    for (int k = 0; at >= 0 && k < n; ++k) v.push_back(h(c, at + k));
  };
  for (std::size_t c = 0; c < nc; ++c) {
    take(out.stress, c, 0, 6);
    take(out.von_mises, c, 6, 1);
    take(out.J, c, 7, 1);
    take(out.volume, c, 8, 1);
    take(out.extra, c, col.extra, nx);
    take(out.green_lagrange, c, col.green_lagrange, 6);
    take(out.log_strain, c, col.log_strain, 6);
    take(out.principal, c, col.principal, 3);
  }
}

}  // namespace

namespace {

// What the cell_fields kernel of one block reads besides the law.
template <class UView>
struct CellFieldBlock {
  int dim, nn, ngp, nx;
  Kinematics kin;
  ElementTechnology tech;
  CellType type;
  QuadRule q;
  Kokkos::View<int**, Kokkos::LayoutRight, la::ExecSpace> conn;
  Kokkos::View<double* [3], Kokkos::LayoutRight, la::ExecSpace> X;
  UView uv;
  Assembler::HistoryView hist;                  // committed rows (laws with history)
  Kokkos::View<int*, la::ExecSpace> xcol;       // per output column: the law's history index, -1 if it has none
  CellColumns col;
};

// Cell fields of one block, compiled for its law: the stress of the committed state (the
// law's frozen_potential at the committed row when it has history), strains, J, volume
// and the Gauss-point average of the law's output history variables.
template <class Law, class UView>
Kokkos::View<double**, Kokkos::LayoutRight, la::ExecSpace> cell_fields_of_block(const Law& law, const CellFieldBlock<UView>& a,
                                                                                std::size_t nc) {
  constexpr bool H = kHasHistory<Law>;
  Kokkos::View<double**, Kokkos::LayoutRight, la::ExecSpace> res("cell_fields", nc, a.col.total);
  Kokkos::parallel_for(
      "stentor::cell_fields", Kokkos::RangePolicy<la::ExecSpace>(0, nc), KOKKOS_LAMBDA(const int c) {
        double Xe[kMaxCellNodes][3], Ue[kMaxCellNodes][3], N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
        int dofs[kMaxCellDofs];
        gather_cell(c, a.nn, a.dim, a.conn, a.X, a.uv, Xe, Ue, dofs);
        Mat3 sig = Mat3::zero(), E = Mat3::zero(), L = Mat3::zero();
        double Jm = 0.0, vol = 0.0, acc[kMaxHistoryColumns > 0 ? kMaxHistoryColumns : 1] = {};
        // F-bar: the stress is the law's at Fb = (J0/J)^(1/3) F (strains and J stay those of F).
        FBarCentre fb;
        const bool fbar = a.tech == ElementTechnology::FBar && fbar_centre(a.dim, a.type, a.nn, Xe, Ue, fb);
        for (int g = 0; g < a.q.n; ++g) {
          shape_functions(a.type, a.q.xi[g], N, dN);
          const double detJ = reference_gradients(a.dim, a.nn, Xe, dN, dNdX);
          const double R = reference_radius(a.kin, a.nn, N, Xe);
          const double w = volume_weight(a.kin, a.q.w[g] * detJ, R);
          const Mat3 F = point_deformation_gradient(a.dim, a.kin, a.nn, N, R, Ue, dNdX);
          const double J = det(F);
          vol += w;
          Jm += w * J;
          if constexpr (H)
            for (int k = 0; k < a.nx; ++k)
              if (a.xcol(k) >= 0) acc[k] += w * a.hist(c * a.ngp + g, a.xcol(k));
          if (J > 0.0) {
            const Mat3 Fs = fbar ? fbar_scale(fb.J0, F) * F : F;
            Mat3 S;
            if constexpr (H)
              S = law.frozen_potential(&a.hist(c * a.ngp + g, 0)).stress(tmul(Fs, Fs));
            else
              S = law_at_point(law, a.nn, N, Xe).stress(tmul(Fs, Fs));
            sig = sig + w * cauchy_stress(Fs, matmul(Fs, S));
          }
          if (J > 0.0 && a.col.green_lagrange >= 0) E = E + (0.5 * w) * (tmul(F, F) - Mat3::identity());
          if (J > 0.0 && a.col.log_strain >= 0) L = L + w * half_log_spd(matmul(F, transpose(F)));
        }
        sig = (1.0 / vol) * sig;
        for (int k = 0; k < a.nx; ++k) res(c, a.col.extra + k) = acc[k] / vol;
        put_sym(res, c, 0, sig);
        res(c, 6) = von_mises(sig);
        res(c, 7) = Jm / vol;
        res(c, 8) = vol;
        if (a.col.green_lagrange >= 0) put_sym(res, c, a.col.green_lagrange, (1.0 / vol) * E);
        if (a.col.log_strain >= 0) put_sym(res, c, a.col.log_strain, (1.0 / vol) * L);
        if (a.col.principal >= 0) {
          double lam[3];
          principal_values(sig, lam);
          for (int k = 0; k < 3; ++k) res(c, a.col.principal + k) = lam[k];
        }
      });
  return res;
}

// Per output column (names), the index of that history variable in `layout` or -1.
Kokkos::View<int*, la::ExecSpace> history_columns(const std::vector<std::string>& names, const HistoryLayout& layout) {
  Kokkos::View<int*, la::ExecSpace> xcol("extra_columns", names.size());
  auto xh = Kokkos::create_mirror_view(xcol);
  for (std::size_t k = 0; k < names.size(); ++k) {
    xh(k) = -1;
    for (int i = 0; i < layout.size; ++i)
      if (layout.vars[i].output && names[k] == layout.vars[i].name) xh(k) = i;
  }
  Kokkos::deep_copy(xcol, xh);
  return xcol;
}

}  // namespace

Assembler::CellFields Assembler::cell_fields(const la::Vector& u, const CellFieldRequest& req) {
  u_overlap_->doImport(u, *dist_.importer(), Tpetra::INSERT);
  CellFields out;
  if (has_history())  // every rank lists every block: the same names on every rank
    for (const auto& lb : dist_.blocks()) {
      const HistoryLayout h = history_layout(block_law_[static_cast<std::size_t>(lb.volume_block)]);
      for (int i = 0; i < h.size; ++i)
        if (h.vars[i].output && std::find(out.extra_names.begin(), out.extra_names.end(), h.vars[i].name) == out.extra_names.end())
          out.extra_names.push_back(h.vars[i].name);
    }
  const int nx = static_cast<int>(out.extra_names.size());
  const CellColumns col(nx, req);
  auto uv = u_overlap_->getLocalViewDevice(Tpetra::Access::ReadOnly);
  for (std::size_t bi = 0; bi < dist_.blocks().size(); ++bi) {
    const auto& lb = dist_.blocks()[bi];
    const std::size_t nc = lb.cell_ids.size();
    out.cell_ids.insert(out.cell_ids.end(), lb.cell_ids.begin(), lb.cell_ids.end());
    if (nc == 0) continue;
    const Material& law = block_law_[static_cast<std::size_t>(lb.volume_block)];
    // With history: the kernels' Gauss points (the stiffness rule), where the rows live.
    const bool has_hist = history_layout(law).size > 0;
    const ElementTechnology tech = block_tech_[static_cast<std::size_t>(lb.volume_block)];
    // With history or F-bar: the kernels' Gauss points (the stiffness rule).
    const bool kernel_points = has_hist || tech == ElementTechnology::FBar;
    CellFieldBlock<decltype(uv)> a{dim_, lb.nodes_per_cell, has_hist ? history_[bi].ngp : 0, nx, kin_, tech, lb.type,
                                   make_rule(lb.type, kernel_points ? stiffness_quadrature_degree(lb.type)
                                                               : quad_degree_[static_cast<std::size_t>(lb.volume_block)]),
                                   lb.conn, dist_.coords(), uv, has_hist ? history_[bi].committed : HistoryView(),
                                   history_columns(out.extra_names, history_layout(law)), col};
    const auto res = std::visit([&](const auto& l) { return cell_fields_of_block(l, a, nc); }, law);
    append_cell_rows(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), res), nc, col, nx, out);
  }
  return out;
}

}  // namespace stentor
