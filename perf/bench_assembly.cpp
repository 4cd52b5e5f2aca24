// bench_assembly: throughput of the finite-strain assembly and cost split of one Newton solve.
//
//   bench_assembly DECK [--repeat N] [--csv FILE] [--size H] [--no-newton]
//                       [--newton-iterations N] [--fill-level K] [--tag TEXT]
//
// Sets up the deck's problem exactly as run_simulation does (mesh, Distribution, Assembler,
// LinearSolver), then measures
//   (a) residual-only assembly,
//   (b) residual + tangent assembly (including the export into the owned matrix),
// each N times at a smooth, non-trivial displacement field, reporting Gauss points per
// second and seconds per call; and
//   (c) one Newton solve of the deck's first load step with the deck's solver settings,
// split into assembly, preconditioner setup (LinearSolver::setup) and linear solve, with
// Newton and GMRES iteration counts. The Newton loop is the one of solver/Newton.cpp
// (backtracking line search included), instrumented.
//
// Times are wall clock per rank; the reported value is the maximum over ranks. A deck with
// a plastic material (e.g. perf/decks/cube_p2_plastic.xml) is timed from the virgin
// Gauss-point state at every call; the number of points that flow is printed.
// Output: a table on stdout and, with --csv, one row per measurement appended to FILE
// (columns: deck, ranks, threads, dofs, cells, gauss_points, what, seconds, rate, iterations).
#include <mpi.h>

#include <Tpetra_Core.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "assembly/Assembler.hpp"
#include "assembly/HyperelasticElement.hpp"
#include "bc/Loads.hpp"
#include "deck/Config.hpp"
#include "fem/Quadrature.hpp"
#include "material/Plasticity.hpp"
#include "mesh/MeshComm.hpp"
#include "parallel/Distribution.hpp"
#include "solver/LinearSolver.hpp"

using namespace stentor;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of this process (all its threads). On a shared machine it leaves out the time
// other processes take from us, which wall-clock time includes.
double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double max_over_ranks(const la::Comm& comm, double v) {
  double g = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &v, &g);
  return g;
}

struct Row {
  std::string what;
  double seconds = 0.0;  // max over ranks
  double rate = 0.0;     // Gauss points per second (assembly rows), 0 otherwise
  long iterations = 0;   // calls / iterations, see `what`
};

void usage() {
  std::cerr << "usage: bench_assembly DECK [--repeat N] [--csv FILE] [--size H] [--no-newton]\n"
               "  --repeat N   assembly calls timed per measurement (default 5)\n"
               "  --csv FILE   append one row per measurement to FILE (header written if new)\n"
               "  --size H     override Mesh->size of the deck (e.g. 0.2 for a quick check)\n"
               "  --no-newton  skip the Newton solve\n"
               "  --newton-iterations N  cap Newton iterations (Newton->max iterations); a capped solve\n"
               "               is reported as 'newton_total(not converged)' with the cost of the iterations done\n"
               "  --fill-level K  override Linear Solver->fill level (RILUK level of fill)\n"
               "  --tag TEXT   appended to the deck name in the CSV, as cube_p1[TEXT]\n"
               "  --steps N    override Stepping->steps (the Newton solve is the first load step; more\n"
               "               steps make it milder)\n"
               "  --assembly atomic|coloring  override Problem->assembly (thread-safe sums)\n"
               "  --preconditioner schwarz|muelu|none  override Linear Solver->preconditioner\n";
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank();
  const int nranks = comm->getSize();

  std::string deck, csv, tag, assembly, preconditioner;
  int repeat = 5;
  double size = 0.0;
  bool newton = true;
  int newton_cap = 0, fill_level = -1, steps = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        if (rank == 0) usage();
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--repeat")
      repeat = std::max(1, std::stoi(next()));
    else if (a == "--csv")
      csv = next();
    else if (a == "--size")
      size = std::stod(next());
    else if (a == "--newton-iterations")
      newton_cap = std::stoi(next());
    else if (a == "--tag")
      tag = next();
    else if (a == "--fill-level")
      fill_level = std::stoi(next());
    else if (a == "--steps")
      steps = std::stoi(next());
    else if (a == "--assembly")
      assembly = next();
    else if (a == "--preconditioner")
      preconditioner = next();
    else if (a == "--no-newton")
      newton = false;
    else if (a == "-h" || a == "--help") {
      if (rank == 0) usage();
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      if (rank == 0) {
        std::cerr << "bench_assembly: unknown option '" << a << "'\n";
        usage();
      }
      return 2;
    } else
      deck = a;
  }
  if (deck.empty()) {
    if (rank == 0) usage();
    return 2;
  }

  try {
    Config cfg = read_deck(deck);
    if (size > 0.0) cfg.mesh.size = size;
    if (newton_cap > 0) cfg.newton.max_iterations = newton_cap;
    if (fill_level >= 0) cfg.linear.fill_level = fill_level;
    if (!assembly.empty()) cfg.problem.assembly = assembly;
    if (steps > 0) cfg.stepping.num_steps = steps;
    if (!preconditioner.empty()) cfg.linear.preconditioner = preconditioner;
    // CSV label: deck name plus the overrides, e.g. cube_p2[h=0.1][fill=0].
    std::ostringstream label_os;
    label_os << std::filesystem::path(deck).stem().string();
    if (size > 0.0) label_os << "[h=" << size << "]";
    if (fill_level >= 0) label_os << "[fill=" << fill_level << "]";
    if (steps > 0) label_os << "[steps=" << steps << "]";
    if (!assembly.empty()) label_os << "[" << assembly << "]";
    if (!preconditioner.empty()) label_os << "[" << preconditioner << "]";
    if (!tag.empty()) label_os << "[" << tag << "]";
    const std::string label = label_os.str();

    std::vector<Row> rows;
    auto t0 = Clock::now();
    Mesh mesh = read_mesh_on_root(cfg.mesh, MPI_COMM_WORLD, true, false);
    rows.push_back({"mesh", max_over_ranks(*comm, seconds_since(t0)), 0.0, 1});
    const std::vector<int> block_mat = block_materials(cfg, mesh);
    const Loads loads = resolve_loads(cfg, mesh);

    t0 = Clock::now();
    Distribution dist(mesh, comm);
    Assembler assembler(mesh, dist, cfg, loads, block_mat);
    rows.push_back({"setup", max_over_ranks(*comm, seconds_since(t0)), 0.0, 1});
    LinearSolver linear(cfg.linear, comm);
    const int dim = dist.dim();
    {
      // Node coordinates for MueLu's rigid-body null space (as run_simulation does).
      std::vector<double> xyz(3 * static_cast<std::size_t>(dist.num_owned_nodes()));
      for (la::LO n = 0; n < dist.num_owned_nodes(); ++n)
        for (int k = 0; k < 3; ++k) xyz[3 * static_cast<std::size_t>(n) + k] = mesh.x[3 * static_cast<std::size_t>(dist.global_node(n)) + k];
      linear.set_node_coordinates(dim, xyz);
    }

    const long dofs = static_cast<long>(dist.owned_map()->getGlobalNumElements());
    const long cells = static_cast<long>(mesh.num_volume_cells());
    long gauss_points = 0;
    std::string cell_types;
    for (const auto& b : mesh.volumes) {
      const QuadRule q = make_rule(b.type, stiffness_quadrature_degree(b.type));  // as Assembler::assemble
      gauss_points += static_cast<long>(b.num_cells()) * q.n;
      cell_types += (cell_types.empty() ? "" : ", ") + std::string(cell_name(b.type)) + " x " + std::to_string(q.n) + " pts";
    }
    const int threads = la::ExecSpace().concurrency();

    std::ostringstream null_stream;
    std::ostream& out = rank == 0 ? std::cout : null_stream;
    out << "bench_assembly: " << deck << "\n"
        << "  mesh     " << mesh.num_nodes() << " nodes, " << cells << " cells (" << cell_types << "), " << gauss_points
        << " Gauss points, " << dofs << " dofs\n"
        << "  matrix   " << assembler.matrix()->getGlobalNumEntries() << " nonzeros\n"
        << "  parallel " << nranks << " MPI rank(s) x " << threads << " " << la::ExecSpace::name() << " thread(s), " << cfg.problem.assembly
        << " assembly" << (assembler.num_colors() > 0 ? " (" + std::to_string(assembler.num_colors()) + " colours)" : std::string())
        << "\n"
        << "  solver   " << linear.description() << "\n"
        << "  repeat   " << repeat << "\n";
    if (rank == 0) {
      std::ifstream la_file("/proc/loadavg");
      std::string load;
      if (std::getline(la_file, load)) out << "  loadavg  " << load << " (machine load at start)\n";
    }

    // A smooth, non-trivial state: 20% stretch along x with lateral contraction, plus a
    // sine bump that vanishes on the cube's faces, so it agrees with the benchmark decks'
    // Dirichlet values at the end time (a jump there would invert P2 cells). det F > 0.7.
    la::Vector u(dist.owned_map()), r(dist.owned_map());
    {
      auto uh = u.getLocalViewHost(Tpetra::Access::ReadWrite);
      const double pi = 3.14159265358979323846;
      for (la::LO l = 0; l < dist.num_owned_nodes(); ++l) {
        const double* X = &mesh.x[3 * static_cast<std::size_t>(dist.global_node(l))];
        const double b = std::sin(pi * X[0]) * std::sin(pi * X[1]) * (dim == 3 ? std::sin(pi * X[2]) : 1.0);
        const double v[3] = {0.20 * X[0] + 0.03 * b, -0.05 * X[1] + 0.02 * b, -0.05 * X[2] - 0.02 * b};
        for (int d = 0; d < dim; ++d) uh(l * dim + d, 0) = v[d];
      }
    }
    const double T = cfg.stepping.end_time;
    assembler.apply_dirichlet(u, T, T);

    auto time_assembly = [&](bool tangent, const std::string& what) {
      const Assembler::Stats st = assembler.assemble(u, T, T, r, tangent);  // warm-up
      if (st.inverted > 0) throw std::runtime_error("benchmark state inverts " + std::to_string(st.inverted) + " cells");
      if (assembler.has_history() && !tangent) {
        // A plastic deck: every call starts from the virgin committed state (nothing is
        // committed here), so the points that flow are the same in every call.
        long flowing = 0, points = 0;
        for (std::size_t b = 0; b < mesh.volumes.size(); ++b) {
          const auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), assembler.trial_history(b));
          points += static_cast<long>(h.extent(0));
          for (std::size_t i = 0; i < h.extent(0); ++i) flowing += h(i, CiarletGeymonatPlasticity::kYielding) > 0.0;
        }
        out << "  plastic  " << flowing << " of " << points << " Gauss points flowing (rank 0)\n";
      }
      double local = 0.0, fastest = 1e300, cpu = 0.0;
      for (int k = 0; k < repeat; ++k) {
        comm->barrier();
        const auto s = Clock::now();
        const double c0 = cpu_seconds();
        assembler.assemble(u, T, T, r, tangent);
        Kokkos::fence();
        cpu += cpu_seconds() - c0;
        const double dt = seconds_since(s);
        local += dt;
        fastest = std::min(fastest, dt);
      }
      const double per_call = max_over_ranks(*comm, local) / repeat;
      const double min_call = max_over_ranks(*comm, fastest);
      const double cpu_call = max_over_ranks(*comm, cpu) / repeat / threads;
      rows.push_back({what, per_call, gauss_points / per_call, repeat});
      rows.push_back({what + "[min]", min_call, gauss_points / min_call, repeat});
      rows.push_back({what + "[cpu]", cpu_call, gauss_points / cpu_call, repeat});
    };
    time_assembly(false, "residual");
    time_assembly(true, "residual+tangent");

    // ---- One Newton solve: the deck's first load step from u = 0. As in run_simulation, the
    // step starts from u = 0 with the Dirichlet values of t1 imposed; if that state already
    // inverts cells, the step is halved (Stepping->max cutbacks) and the cut-backs counted.
    bool converged = false;
    if (newton) {
      const NewtonConfig& nc = cfg.newton;
      double t1 = T / cfg.stepping.num_steps;
      double t_asm = 0.0, t_setup = 0.0, t_solve = 0.0;
      long n_asm = 0, n_setup = 0, linear_its = 0;
      int newton_its = 0;
      auto evaluate = [&](const la::Vector& x, la::Vector& res) {
        const auto s = Clock::now();
        const Assembler::Stats st = assembler.assemble(x, t1, T, res, true);
        Kokkos::fence();
        t_asm += seconds_since(s);
        ++n_asm;
        return st.inverted == 0;
      };
      la::Vector du(u.getMap()), u_trial(u.getMap()), r_trial(u.getMap());
      comm->barrier();
      const auto s_total = Clock::now();
      std::string failure;
      int cutbacks = 0;
      for (;;) {
        u.putScalar(0.0);
        assembler.apply_dirichlet(u, t1, T);
        if (evaluate(u, r)) break;
        if (cutbacks >= cfg.stepping.max_cutbacks)
          throw std::runtime_error("first load step: inverted elements at the start even after " + std::to_string(cutbacks) +
                                   " halvings");
        ++cutbacks;
        t1 *= 0.5;
        out << "    load step: imposing the Dirichlet values inverts cells; halving the step to t = " << t1 << "\n";
      }
      out << "    load step 0 -> " << t1 << " (of end time " << T << ", " << cutbacks << " cut-back(s))\n";
      double rn = r.norm2();
      const double r0 = rn;
      const double target = std::max(nc.residual_tolerance * rn, nc.absolute_tolerance);
      converged = rn <= target;
      for (int it = 1; it <= nc.max_iterations && !converged; ++it) {
        auto s = Clock::now();
        linear.setup(assembler.matrix());
        const double ts = seconds_since(s);
        t_setup += ts;
        ++n_setup;
        r.scale(-1.0);
        s = Clock::now();
        const LinearSolver::Result lr = linear.solve(r, du);
        const double tl = seconds_since(s);
        t_solve += tl;
        r.scale(-1.0);
        linear_its += lr.iterations;
        if (!std::isfinite(du.norm2())) {
          failure = "non-finite increment";
          break;
        }
        double alpha = 1.0, rn_trial = 0.0;
        bool accepted = false;
        const int max_halvings = nc.line_search ? nc.line_search_max : 0;
        for (int ls = 0; ls <= max_halvings; ++ls) {
          u_trial.update(1.0, u, alpha, du, 0.0);
          if (evaluate(u_trial, r_trial)) {
            rn_trial = r_trial.norm2();
            if (std::isfinite(rn_trial) && (!nc.line_search || rn_trial <= (1.0 - 1e-4 * alpha) * rn)) {
              accepted = true;
              break;
            }
          }
          alpha *= 0.5;
        }
        if (!accepted) {
          alpha = 1.0;
          u_trial.update(1.0, u, alpha, du, 0.0);
          if (!evaluate(u_trial, r_trial)) {
            failure = "line search found no admissible step";
            break;
          }
          rn_trial = r_trial.norm2();
        }
        u.update(1.0, u_trial, 0.0);
        r.update(1.0, r_trial, 0.0);
        const double step = alpha * du.norm2();
        const double un = u.norm2();
        rn = rn_trial;
        newton_its = it;
        out << "    newton " << std::setw(2) << it << "  |r| " << std::scientific << std::setprecision(3) << rn << "  alpha "
            << std::defaultfloat << alpha << "  gmres " << lr.iterations << (lr.converged ? "" : " (not converged)") << "  setup " << std::fixed
            << std::setprecision(3) << ts << " s  solve " << tl << " s (rank 0)" << std::defaultfloat << "\n"
            << std::flush;
        if (rn <= target ||
            (step <= nc.increment_tolerance * std::max(un, 1e-300) && rn <= std::sqrt(nc.residual_tolerance) * r0))
          converged = true;
      }
      const double total = seconds_since(s_total);
      if (!converged)
        out << "  Newton stopped without convergence ("
            << (!failure.empty() ? failure : newton_cap > 0 ? "--newton-iterations cap" : "iteration limit") << "), |r|/|r0| = " << rn / r0
            << "\n";
      const bool capped = !converged && failure.empty() && newton_cap > 0;
      rows.push_back({converged ? "newton_total" : capped ? "newton_total(capped)" : "newton_total(not converged)",
                      max_over_ranks(*comm, total), 0.0, newton_its});
      if (capped) converged = true;  // requested: not an error
      rows.push_back({"newton_assembly", max_over_ranks(*comm, t_asm), 0.0, n_asm});
      rows.push_back({"newton_cutbacks", 0.0, 0.0, cutbacks});
      rows.push_back({"newton_prec_setup", max_over_ranks(*comm, t_setup), 0.0, n_setup});
      rows.push_back({"newton_linear_solve", max_over_ranks(*comm, t_solve), 0.0, linear_its});
    }

    out << "\n"
        << std::left << std::setw(28) << "what" << std::right << std::setw(12) << "seconds" << std::setw(16) << "GP/s"
        << std::setw(12) << "count" << "\n";
    for (const auto& row : rows) {
      out << std::left << std::setw(28) << row.what << std::right << std::setw(12) << std::fixed << std::setprecision(4)
          << row.seconds << std::setw(16) << std::scientific << std::setprecision(3);
      if (row.rate > 0)
        out << row.rate;
      else
        out << "-";
      out << std::setw(12) << row.iterations << std::defaultfloat << "\n";
    }
    out << "  (assembly rows: seconds per call, mean of the repeats ([min]: fastest repeat; [cpu]: process CPU time\n"
           "   per thread, i.e. without the time other processes took); newton rows: seconds in total,\n"
           "   count = Newton iterations / assembly calls / step halvings before the first solve / preconditioner setups /\n"
           "   GMRES iterations)\n";

    if (rank == 0 && !csv.empty()) {
      const bool fresh = !std::filesystem::exists(csv) || std::filesystem::file_size(csv) == 0;
      if (std::filesystem::path(csv).has_parent_path()) std::filesystem::create_directories(std::filesystem::path(csv).parent_path());
      std::ofstream f(csv, std::ios::app);
      if (!f) throw std::runtime_error("cannot write " + csv);
      if (fresh) f << "deck,ranks,threads,dofs,cells,gauss_points,what,seconds,rate,iterations\n";
      for (const auto& row : rows)
        f << label << "," << nranks << "," << threads << "," << dofs << "," << cells << "," << gauss_points << "," << row.what << ","
          << std::setprecision(6) << row.seconds << "," << std::setprecision(6) << row.rate << "," << row.iterations << "\n";
      out << "appended " << rows.size() << " rows to " << csv << "\n";
    }
    return newton && !converged ? 3 : 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_assembly (rank " << rank << "): " << e.what() << "\n";
    return 1;
  }
}
