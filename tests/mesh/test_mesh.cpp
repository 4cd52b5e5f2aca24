// Mesh reading (gmsh .geo / .msh), checks, group queries and METIS partitioning.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <thread>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "fem/Geometry.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "mesh/GeoScreen.hpp"
#include "mesh/GmshReader.hpp"
#include "mesh/Progress.hpp"
#include "mesh/MeshCheck.hpp"
#include "mesh/MeshComm.hpp"
#include "mesh/MeshQuery.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

const double kPi = 3.14159265358979323846;

std::string input(const std::string& name) { return std::string(STENTOR_SOURCE_DIR) + "/inputs/" + name; }

MeshConfig config(const std::string& file, double size = 0.0, int order = 1, bool recombine = false) {
  MeshConfig c;
  c.file = file;
  c.size = size;
  c.order = order;
  c.recombine = recombine;
  return c;
}

// A scratch folder, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("stentor_mesh_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = (path / name).string();
    std::ofstream(p) << text;
    return p;
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

// Expects `f` to throw InputError whose message contains every string in `parts`.
template <class F>
std::string expect_input_error(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
    return msg;
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

// Measure (area/volume) of all volume cells: sum over quadrature points of |det J| w.
double measure(const Mesh& m) {
  double total = 0.0;
  for (const auto& b : m.volumes) {
    double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
    const int nq = quadrature(b.type, 4, xi, w);
    const int nn = b.nodes_per_cell;
    for (std::size_t c = 0; c < b.num_cells(); ++c) {
      double X[kMaxCellNodes][3], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
      for (int a = 0; a < nn; ++a)
        for (int d = 0; d < 3; ++d) X[a][d] = m.x[3 * b.conn[c * nn + a] + d];
      for (int q = 0; q < nq; ++q) {
        shape_functions(b.type, xi[q], nullptr, dN);
        total += std::abs(reference_gradients(m.dim, nn, X, dN, dNdX)) * w[q];
      }
    }
  }
  return total;
}

// Area enclosed by a closed boundary curve (2D): |sum over its cells of  x dy|.
double enclosed_area(const Mesh& m, const std::string& group) {
  double total = 0.0;
  for (const auto* b : boundary_blocks(m, group)) {
    double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
    const int nq = quadrature(b->type, 4, xi, w);
    const int nn = b->nodes_per_cell;
    for (std::size_t c = 0; c < b->num_cells(); ++c)
      for (int q = 0; q < nq; ++q) {
        double N[kMaxCellNodes], dN[kMaxCellNodes][3], x = 0, dy = 0;
        shape_functions(b->type, xi[q], N, dN);
        for (int a = 0; a < nn; ++a) {
          const stentor::GId n = b->conn[c * nn + a];
          x += N[a] * m.x[3 * n];
          dy += dN[a][0] * m.x[3 * n + 1];
        }
        total += x * dy * w[q];
      }
  }
  return std::abs(total);
}

std::set<std::string> as_set(const std::vector<std::string>& v) { return {v.begin(), v.end()}; }

std::set<CellType> volume_types(const Mesh& m) {
  std::set<CellType> t;
  for (const auto& b : m.volumes) t.insert(b.type);
  return t;
}

// Structural invariants every mesh from read_mesh satisfies.
void expect_consistent(const Mesh& m) {
  const std::size_t nn = m.num_nodes();
  ASSERT_GT(nn, 0u);
  std::vector<char> used(nn, 0);
  stentor::GId next = 0;
  for (const auto& b : m.volumes) {
    EXPECT_EQ(b.nodes_per_cell, cell_num_nodes(b.type));
    EXPECT_EQ(cell_dim(b.type), m.dim);
    EXPECT_EQ(b.conn.size() % b.nodes_per_cell, 0u);
    ASSERT_EQ(b.cell_id.size(), b.num_cells());
    for (stentor::GId id : b.cell_id) EXPECT_EQ(id, next++);
    for (stentor::GId n : b.conn) {
      ASSERT_GE(n, 0);
      ASSERT_LT(static_cast<std::size_t>(n), nn);
      used[n] = 1;
    }
  }
  EXPECT_EQ(static_cast<std::size_t>(next), m.num_volume_cells());
  for (const auto& b : m.boundaries) {
    EXPECT_LT(cell_dim(b.type), m.dim);
    EXPECT_EQ(b.nodes_per_cell, cell_num_nodes(b.type));
    for (stentor::GId n : b.conn) {
      ASSERT_LT(static_cast<std::size_t>(n), nn);
      used[n] = 1;
    }
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "unused nodes";
  if (m.dim == 2)
    for (std::size_t i = 0; i < nn; ++i) EXPECT_EQ(m.x[3 * i + 2], 0.0);
}

void expect_same_mesh(const Mesh& a, const Mesh& b, double tol = 0.0) {
  ASSERT_EQ(a.dim, b.dim);
  ASSERT_EQ(a.x.size(), b.x.size());
  for (std::size_t i = 0; i < a.x.size(); ++i) ASSERT_NEAR(a.x[i], b.x[i], tol) << i;
  for (auto pair : {std::make_pair(&a.volumes, &b.volumes), std::make_pair(&a.boundaries, &b.boundaries)}) {
    ASSERT_EQ(pair.first->size(), pair.second->size());
    for (std::size_t k = 0; k < pair.first->size(); ++k) {
      const auto &p = (*pair.first)[k], &q = (*pair.second)[k];
      EXPECT_EQ(p.name, q.name);
      EXPECT_EQ(p.physical_tag, q.physical_tag);
      EXPECT_EQ(p.type, q.type);
      EXPECT_EQ(p.conn, q.conn);
      EXPECT_EQ(p.cell_id, q.cell_id);
    }
  }
}

struct GeoCase {
  const char* file;
  int dim;
  const char* body;
  std::set<std::string> boundaries;
  double size_coarse, size_fine;
  double exact_measure;
};

const std::vector<GeoCase>& geo_cases() {
  static const std::vector<GeoCase> cases = {
      {"block2d.geo", 2, "block", {"left", "right", "bottom", "top"}, 0.25, 0.1, 1.0},
      {"block3d.geo", 3, "block", {"left", "right", "front", "back", "bottom", "top"}, 0.5, 0.25, 1.0},
      {"cook.geo", 2, "membrane", {"clamped", "tip"}, 8.0, 3.0, 1440.0},
      {"cylinder.geo", 2, "wall", {"inner", "outer", "xsym", "ysym"}, 0.3, 0.1, 0.75 * kPi},
      {"artery_ring.geo", 2, "artery", {"lumen", "outer"}, 2.5e-4, 1e-4, kPi * (4e-6 - 2.25e-6)},
  };
  return cases;
}

}  // namespace

// ---------------------------------------------------------------- .geo inputs

TEST(GmshReader, GeoInputsAtTwoSizesAndOrders) {
  for (const auto& gc : geo_cases()) {
    SCOPED_TRACE(gc.file);
    for (int order : {1, 2}) {
      SCOPED_TRACE("order " + std::to_string(order));
      const Mesh coarse = read_mesh(config(input(gc.file), gc.size_coarse, order));
      const Mesh fine = read_mesh(config(input(gc.file), gc.size_fine, order));
      for (const Mesh* m : {&coarse, &fine}) {
        expect_consistent(*m);
        EXPECT_EQ(m->dim, gc.dim);
        EXPECT_EQ(m->source, input(gc.file));
        EXPECT_EQ(m->volume_group_names(), std::vector<std::string>{gc.body});
        EXPECT_EQ(as_set(m->boundary_group_names()), gc.boundaries);
        const CellType want = gc.dim == 2 ? (order == 1 ? CellType::Tri3 : CellType::Tri6)
                                          : (order == 1 ? CellType::Tet4 : CellType::Tet10);
        EXPECT_EQ(volume_types(*m), std::set<CellType>{want});
        for (const auto& b : m->boundaries) {
          EXPECT_EQ(cell_dim(b.type), gc.dim - 1);
          EXPECT_EQ(cell_order(b.type), order);
        }
        EXPECT_NO_THROW(check_mesh(*m));
        EXPECT_EQ(count_inverted_cells(*m), 0u);
      }
      EXPECT_GT(fine.num_volume_cells(), 2 * coarse.num_volume_cells());
      EXPECT_GT(fine.num_nodes(), coarse.num_nodes());
    }
  }
}

TEST(GmshReader, DefaultSizeComesFromTheGeo) {
  // size 0: the .geo's own h (0.1 for the unit square) governs.
  const Mesh d = read_mesh(config(input("block2d.geo")));
  const Mesh c = read_mesh(config(input("block2d.geo"), 0.25));
  const Mesh f = read_mesh(config(input("block2d.geo"), 0.05));
  EXPECT_GT(d.num_volume_cells(), c.num_volume_cells());
  EXPECT_LT(d.num_volume_cells(), f.num_volume_cells());
  // A size larger than the .geo's h also applies (the points' h is ignored).
  const Mesh big = read_mesh(config(input("block2d.geo"), 0.5));
  EXPECT_LT(big.num_volume_cells(), c.num_volume_cells());
}

TEST(GmshReader, NumberingIsDeterministic) {
  for (const char* f : {"artery_ring.geo", "block3d.geo"}) {
    const Mesh a = read_mesh(config(input(f), 0, 2));
    const Mesh b = read_mesh(config(input(f), 0, 2));
    expect_same_mesh(a, b);
  }
}

TEST(GmshReader, RecombineGivesQuadsAndHexes) {
  const Mesh q = read_mesh(config(input("block2d.geo"), 0.1, 1, true));
  expect_consistent(q);
  EXPECT_TRUE(volume_types(q).count(CellType::Quad4));
  std::size_t nquad = 0;
  for (const auto& b : q.volumes)
    if (b.type == CellType::Quad4) nquad += b.num_cells();
  EXPECT_GT(nquad, 0.9 * q.num_volume_cells());
  EXPECT_NO_THROW(check_mesh(q));
  EXPECT_NEAR(measure(q), 1.0, 1e-12);

  const Mesh ring = read_mesh(config(input("artery_ring.geo"), 1e-4, 1, true));
  EXPECT_TRUE(volume_types(ring).count(CellType::Quad4));
  EXPECT_NO_THROW(check_mesh(ring));

  const Mesh h = read_mesh(config(input("block3d.geo"), 0.5, 1, true));
  expect_consistent(h);
  EXPECT_EQ(volume_types(h), std::set<CellType>{CellType::Hex8});
  for (const auto& b : h.boundaries) EXPECT_EQ(b.type, CellType::Quad4);
  EXPECT_NO_THROW(check_mesh(h));
  EXPECT_NEAR(measure(h), 1.0, 1e-12);

  expect_input_error([] { read_mesh(config(input("block2d.geo"), 0.1, 2, true)); },
                     {input("block2d.geo") + ": ", "recombine", "order 1"});
}

TEST(GmshReader, AreasAndVolumes) {
  for (int order : {1, 2}) {
    EXPECT_NEAR(measure(read_mesh(config(input("block2d.geo"), 0.2, order))), 1.0, 1e-12);
    EXPECT_NEAR(measure(read_mesh(config(input("block3d.geo"), 0.4, order))), 1.0, 1e-12);
    EXPECT_NEAR(measure(read_mesh(config(input("cook.geo"), 5.0, order))), 1440.0, 1e-9);
  }
  // Annulus: the polygonal P1 boundaries lose area Phi h^2/12 per arc of angle Phi whatever the
  // radius, so inner and outer chord errors cancel at O(h^2): the area is accurate for P1 and P2.
  const double ri = 1.5e-3, ro = 2.0e-3, exact = kPi * (ro * ro - ri * ri);
  const double h[2] = {2e-4, 1e-4};
  double err1[2], err2[2];  // relative errors of the area enclosed by "outer", P1 / P2
  for (int k = 0; k < 2; ++k) {
    const Mesh p1 = read_mesh(config(input("artery_ring.geo"), h[k], 1));
    const Mesh p2 = read_mesh(config(input("artery_ring.geo"), h[k], 2));
    EXPECT_NEAR(measure(p1), exact, 1e-5 * exact);
    EXPECT_NEAR(measure(p2), exact, 1e-6 * exact);
    err1[k] = std::abs(enclosed_area(p1, "outer") - kPi * ro * ro) / (kPi * ro * ro);
    err2[k] = std::abs(enclosed_area(p2, "outer") - kPi * ro * ro) / (kPi * ro * ro);
  }
  // P1: relative error h^2 / (6 r^2) (chords), O(h^2); P2 (mid-nodes on the circle): O(h^4).
  EXPECT_NEAR(err1[0], h[0] * h[0] / (6 * ro * ro), 0.3 * h[0] * h[0] / (6 * ro * ro));
  EXPECT_GT(err1[0] / err1[1], 3.0);
  EXPECT_LT(err1[0] / err1[1], 5.5);
  EXPECT_LT(err2[0], 0.01 * err1[0]);
  EXPECT_GT(err2[0] / err2[1], 10.0);
  // Quarter cylinder, P2.
  EXPECT_NEAR(measure(read_mesh(config(input("cylinder.geo"), 0.1, 2))), 0.75 * kPi, 1e-6);
}

TEST(GmshReader, BoundaryGroupsLieWhereTheySay) {
  const Mesh m = read_mesh(config(input("block3d.geo"), 0.25, 2));
  const struct {
    const char* name;
    int axis;
    double value;
  } faces[] = {{"left", 0, 0.0}, {"right", 0, 1.0}, {"front", 1, 0.0},
               {"back", 1, 1.0}, {"bottom", 2, 0.0}, {"top", 2, 1.0}};
  for (const auto& f : faces) {
    const auto nodes = boundary_nodes(m, f.name);
    ASSERT_FALSE(nodes.empty()) << f.name;
    EXPECT_TRUE(std::is_sorted(nodes.begin(), nodes.end()));
    EXPECT_EQ(std::adjacent_find(nodes.begin(), nodes.end()), nodes.end());
    for (stentor::GId n : nodes) EXPECT_NEAR(m.x[3 * n + f.axis], f.value, 1e-12) << f.name;
    for (const auto* b : boundary_blocks(m, f.name)) EXPECT_EQ(b->type, CellType::Tri6);
  }
  const Mesh c = read_mesh(config(input("cylinder.geo"), 0.2, 2));
  for (stentor::GId n : boundary_nodes(c, "inner"))
    EXPECT_NEAR(std::hypot(c.x[3 * n], c.x[3 * n + 1]), 1.0, 1e-9);
  for (stentor::GId n : boundary_nodes(c, "outer"))
    EXPECT_NEAR(std::hypot(c.x[3 * n], c.x[3 * n + 1]), 2.0, 1e-9);
  for (stentor::GId n : boundary_nodes(c, "xsym")) EXPECT_NEAR(c.x[3 * n + 1], 0.0, 1e-12);
  for (stentor::GId n : boundary_nodes(c, "ysym")) EXPECT_NEAR(c.x[3 * n], 0.0, 1e-12);
  const Mesh k = read_mesh(config(input("cook.geo"), 4.0));
  for (stentor::GId n : boundary_nodes(k, "clamped")) EXPECT_NEAR(k.x[3 * n], 0.0, 1e-12);
  for (stentor::GId n : boundary_nodes(k, "tip")) EXPECT_NEAR(k.x[3 * n], 48.0, 1e-12);
  const Mesh r = read_mesh(config(input("artery_ring.geo"), 2e-4));
  for (stentor::GId n : boundary_nodes(r, "lumen")) EXPECT_NEAR(std::hypot(r.x[3 * n], r.x[3 * n + 1]), 1.5e-3, 1e-12);
  EXPECT_EQ(volume_nodes(r, "artery").size(), r.num_nodes());
}

// ---------------------------------------------------------------- .msh files

TEST(GmshReader, MshRoundTrip) {
  TempDir tmp;
  for (const char* geo : {"artery_ring.geo", "block3d.geo"}) {
    for (int order : {1, 2}) {
      const double size = std::string(geo) == "block3d.geo" ? 0.3 : 2e-4;
      const Mesh ref = read_mesh(config(input(geo), size, order));
      // Mesh the same .geo through gmsh directly and write it in three formats.
      gmsh::initialize(0, nullptr, false);
      gmsh::option::setNumber("General.Terminal", 0);
      gmsh::open(input(geo));
      gmsh::option::setNumber("Mesh.MeshSizeMax", size);
      gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
      gmsh::option::setNumber("Mesh.ElementOrder", order);
      gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);
      gmsh::model::mesh::generate(ref.dim);
      const struct {
        const char* name;
        double version;
        int binary;
      } formats[] = {{"a41.msh", 4.1, 0}, {"b41.msh", 4.1, 1}, {"a22.msh", 2.2, 0}};
      for (const auto& f : formats) {
        gmsh::option::setNumber("Mesh.MshFileVersion", f.version);
        gmsh::option::setNumber("Mesh.Binary", f.binary);
        gmsh::write(tmp.file(f.name));
      }
      gmsh::finalize();
      for (const auto& f : formats) {
        SCOPED_TRACE(std::string(geo) + " order " + std::to_string(order) + " " + f.name);
        // .msh: size/order/recombine of the deck are ignored.
        const Mesh m = read_mesh(config(tmp.file(f.name), 123.0, 3 - order));
        EXPECT_EQ(m.source, tmp.file(f.name));
        expect_same_mesh(ref, m, f.binary ? 0.0 : 1e-15 * (std::string(geo) == "block3d.geo" ? 1.0 : 1e-3));
      }
    }
  }
}

TEST(GmshReader, UnsupportedElementTypeInMsh) {
  TempDir tmp;
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(input("block2d.geo"));
  gmsh::option::setNumber("Mesh.RecombineAll", 1);
  gmsh::option::setNumber("Mesh.ElementOrder", 2);
  gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 0);  // quad9
  gmsh::model::mesh::generate(2);
  gmsh::write(tmp.file("q9.msh"));
  gmsh::finalize();
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(input("block2d.geo"));
  gmsh::option::setNumber("Mesh.RecombineAll", 1);
  gmsh::option::setNumber("Mesh.ElementOrder", 2);
  gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);  // quad8: not a body type
  gmsh::model::mesh::generate(2);
  gmsh::write(tmp.file("q8.msh"));
  gmsh::finalize();
  expect_input_error([&] { read_mesh(config(tmp.file("q9.msh"))); },
                     {tmp.file("q9.msh") + ": ", "'block'", "Quadrilateral 9"});
  expect_input_error([&] { read_mesh(config(tmp.file("q8.msh"))); },
                     {tmp.file("q8.msh") + ": ", "'block'", "quad8", "not supported"});
}

// ---------------------------------------------------------------- errors

TEST(GmshReader, Errors) {
  TempDir tmp;
  const std::string missing = tmp.file("nope.msh");
  expect_input_error([&] { read_mesh(config(missing)); }, {missing + ": ", "cannot open"});

  const std::string bad = tmp.write("bad.geo", "Point(1) = {0, 0, 0};\nLine(1) = {1, 2;\n");
  const std::string msg = expect_input_error([&] { read_mesh(config(bad)); }, {bad + ": ", "gmsh", "syntax error"});
  EXPECT_EQ(msg.rfind(bad, 0), 0u);

  const std::string garbage = tmp.write("garbage.msh", "this is not a mesh\n");
  expect_input_error([&] { read_mesh(config(garbage)); }, {garbage + ": ", "gmsh"});

  const std::string square = "Point(1) = {0,0,0,0.5}; Point(2) = {1,0,0,0.5}; Point(3) = {1,1,0,0.5};\n"
                             "Point(4) = {0,1,0,0.5};\nLine(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; "
                             "Line(4) = {4,1};\nCurve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};\n";
  const std::string nobody = tmp.write("nobody.geo", square + "Physical Curve(\"left\") = {4};\n");
  expect_input_error([&] { read_mesh(config(nobody)); },
                     {nobody + ": ", "mesh has no physical group of dimension 2",
                      "bodies must be physical surfaces"});
  const std::string nogroups = tmp.write("nogroups.geo", square);
  expect_input_error([&] { read_mesh(config(nogroups)); }, {nogroups + ": ", "no physical group of dimension 2"});

  const std::string lifted = tmp.write(
      "lifted.geo", "Point(1) = {0,0,1,0.5}; Point(2) = {1,0,1,0.5}; Point(3) = {1,1,1,0.5};\n"
                    "Point(4) = {0,1,1,0.5};\nLine(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; "
                    "Line(4) = {4,1};\nCurve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};\n"
                    "Physical Surface(\"s\") = {1};\n");
  expect_input_error([&] { read_mesh(config(lifted)); }, {lifted + ": ", "z = 0 plane"});

  const std::string overlap =
      tmp.write("overlap.geo", square + "Physical Surface(\"a\") = {1};\nPhysical Surface(\"b\") = {1};\n");
  expect_input_error([&] { read_mesh(config(overlap)); }, {overlap + ": ", "'a'", "'b'", "overlap"});

  MeshConfig c = config(input("block2d.geo"));
  c.dimension = 4;
  expect_input_error([&] { read_mesh(c); }, {"dimension"});
}

// A .geo is input, never a program: commands that run programs, write files, end the
// process or mesh by themselves are refused (file:line) before gmsh reads the file.
// screen_geo_text on `text` (as x.geo in `dir`) throws an InputError holding each fragment.
void expect_geo_refused(const std::string& dir, const std::string& text, std::initializer_list<std::string> fragments) {
  SCOPED_TRACE(text);
  expect_input_error([&] { screen_geo_text(text, "x.geo", dir); }, fragments);
}

TEST(GeoScreen, RefusesCommandsThatRunOrWrite) {
  TempDir tmp;
  const std::string dir = tmp.path.string();
  auto refused = [&](const std::string& text, const std::string& word, int line) {
    SCOPED_TRACE(text);
    expect_input_error([&] { screen_geo_text(text, "x.geo", dir); },
                       {"x.geo:" + std::to_string(line) + ": '" + word + "'", "remove it from the .geo"});
  };
  refused("Point(1) = {0,0,0};\nSystemCall \"touch PWNED\";\n", "SystemCall", 2);
  refused("System \"touch PWNED\";", "System", 1);
  refused("a = 1;\n\nPrintf(\"%g\", a) > \"/tmp/PWNED\";", "Printf", 3);
  refused("Printf(\"x\") >> \"log.txt\";", "Printf", 1);
  refused("Save \"out.msh\";", "Save", 1);
  refused("Print \"out.png\";", "Print", 1);
  refused("CreateDir \"d\";", "CreateDir", 1);
  refused("Exit;", "Exit", 1);
  refused("Sleep 1e9;", "Sleep", 1);
  refused("Mesh 3;", "Mesh", 1);
  refused("RefineMesh;", "RefineMesh", 1);
  refused("OnelabRun(\"c\", \"touch PWNED\");", "OnelabRun", 1);
  refused("General.OptionsFileName = \"/tmp/x\";", "General", 1);
  refused("Solver.Executable0 = \"/bin/sh\";", "Solver", 1);
  // Not commands: comments, strings, options, a Printf to the terminal.
  EXPECT_NO_THROW(screen_geo_text("// SystemCall \"x\";\n/* Exit; Save \"a\"; */\nPrintf(\"Exit; %g\", 1 > 0);\n"
                                  "Mesh.Algorithm = 6; Print.Width = 3; General.Terminal = 1;\n"
                                  "Physical Surface(\"Save\") = {1};\nCoherence Mesh;\n",
                                  "x.geo", dir));
  // Included files are screened too; a computed include name is refused.
  tmp.write("evil.geo", "\n\nSystemCall \"touch PWNED\";\n");
  expect_input_error([&] { screen_geo_text("Include \"evil.geo\";", "x.geo", dir); },
                     {"evil.geo:3: 'SystemCall'"});
  expect_input_error([&] { screen_geo_text("Include StrCat(\"ev\", \"il.geo\");", "x.geo", dir); },
                     {"x.geo:1: 'Include' needs a literal"});
  EXPECT_NO_THROW(screen_geo_file(input("artery_ring_pins.geo")));
  // Through read_mesh: refused before gmsh runs it, nothing is written.
  const std::string geo = tmp.write("sys.geo", "SystemCall \"touch " + tmp.file("PWNED") + "\";\n");
  expect_input_error([&] { read_mesh(config(geo)); }, {geo + ":1: 'SystemCall' runs a program"});
  EXPECT_FALSE(fs::exists(tmp.file("PWNED")));
}

// Ways a command hid from the screen (found by the hostile-input corpus, issue 16; each
// ran `touch` through gmsh 4.8): gmsh's lexer takes '...' as a string too and has no
// escapes ("\" is a string holding a backslash); Include parses any file as .geo, and
// Merge/MergeWithBoundingBox parse any file that is not a mesh or CAD format; options may
// be written "General . X"; General.AbortOnError = 4 makes gmsh exit at an Error(); a
// Printf/Sprintf format is handed to sprintf with numbers (%s, %n crash or write memory).
TEST(GeoScreen, RefusesCommandsHiddenFromTheFirstScreen) {
  TempDir tmp;
  const std::string dir = tmp.path.string();
  auto refused = [&](const std::string& text, std::initializer_list<std::string> f) { expect_geo_refused(dir, text, f); };
  refused("Printf('\"');\nSystemCall 'touch PWNED';\nPrintf('\"');\n", {"x.geo:2: 'SystemCall'"});
  refused("Printf(\"\\\");\nSystemCall \"touch PWNED\";\nPrintf(\"\\\");\n", {"x.geo:2: 'SystemCall'"});
  tmp.write("cmds.txt", "\nSystemCall \"touch PWNED\";\n");
  tmp.write("cmds", "Exit;\n");
  tmp.write("inc.GEO", "Sleep 10;\n");
  refused("Include \"cmds.txt\";", {"cmds.txt:2: 'SystemCall'"});
  refused("Merge \"cmds.txt\";", {"cmds.txt:2: 'SystemCall'"});
  refused("MergeWithBoundingBox \"cmds.txt\";", {"cmds.txt:2: 'SystemCall'"});
  refused("Include \"cmds\";", {"cmds:1: 'Exit'"});
  refused("Include \"inc.GEO\";", {"inc.GEO:1: 'Sleep'"});
  refused("MergeWithBoundingBox StrCat(\"cm\", \"ds\");", {"x.geo:1: 'MergeWithBoundingBox' needs a literal"});
  refused("Include \"/dev/zero\";", {"x.geo:1: 'Include' names '/dev/zero', which is not a regular file"});
  refused("Include \"/\";", {"which is not a regular file"});
  refused("Merge \"nope.geo\";", {"x.geo:1: 'Merge' names", "nope.geo', which does not exist"});
  refused("General . OptionsFileName = \"/tmp/x\";", {"x.geo:1: 'General' sets an option that names a file"});
  refused("General.AbortOnError = 4;\nError(\"x\");", {"x.geo:1: 'General' sets General.AbortOnError"});
  refused("SendToServer \"x\";", {"x.geo:1: 'SendToServer' runs a program"});
  refused("Printf(\"%s %s\", 1, 2);", {"x.geo:1: 'Printf' has a format conversion other than a number's"});
  refused("x = 1;\nPrintf('%n');", {"x.geo:2: 'Printf' has a format conversion"});
  refused("s = Sprintf(\"%999999999g\", 1);", {"'Sprintf' has a format width or precision of more than 3 digits"});
  refused("Printf(StrCat(\"%\", \"n\"));", {"'Printf' needs a literal \"format\""});
  // A merged .msh goes through the .msh screen.
  tmp.write("bad.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n2 1 0 5\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n");
  refused("Merge \"bad.msh\";", {"bad.msh: $Nodes section"});
  // Still accepted: quotes of either kind holding the other, numeric formats, data files.
  tmp.write("part.step", "ISO-10303-21;\n");
  EXPECT_NO_THROW(screen_geo_text("Printf('say \"hi\" %g', 1);\nPrintf(\"it's %5.2f%%\", 2);\n"
                                  "s = Sprintf(\"%g * (%g + %e)\", 1, 2, 3);\nGeneral.Terminal = 1;\n"
                                  "Merge \"part.step\";\n",
                                  "x.geo", dir));
  for (const char* f : {"artery_ring.geo", "artery_ring_pins.geo", "necking_bar.geo", "s4_stent_artery.geo",
                        "s3_ring_foundation.geo", "ironing.geo", "hertz.geo"})
    EXPECT_NO_THROW(screen_geo_file(input(f))) << f;
}

// The screen decides on what a statement does (docs/robustness.md, "Mesh scripts"): a
// Printf redirection whatever forms its target, any command but Include/Merge/Background
// Field, at any depth; ordinary geometry, loops, macros and options still pass.
TEST(GeoScreen, RefusesByMeaningNotSpelling) {
  TempDir tmp;
  const std::string dir = tmp.path.string();
  const std::pair<std::string, std::string> cases[] = {
      {"Printf(\"touch /tmp/x\") >> StrCat(\"/home/me/\", \".bashrc\");", "x.geo:1: 'Printf' writes a file"},
      {"f = Sprintf(\"/tmp/p%g\", 1);\nPrintf(\"x\") > f;", "x.geo:2: 'Printf' writes a file"},
      {"For i In {1:2}\n  If (i > 1)\n    Save StrCat(\"a\", \"b\");\n  EndIf\nEndFor", "x.geo:3: 'Save' writes files"},
      {"Macro M\nDeleteFile \"a\";\nReturn", "x.geo:2: 'DeleteFile' writes or deletes files"},
      {"Frobnicate \"a\";", "x.geo:1: 'Frobnicate' is a command Stentor does not know"},
      {"General.NumThreads = 100000;", "'General' sets General.NumThreads"},
      {"Field[1] = ExternalProcess;", "'Field' of type ExternalProcess runs a program"},
      {"a = 1; $b = 2;", "x.geo:1: the character '$'"},
  };
  for (const auto& [text, fragment] : cases) expect_geo_refused(dir, text, {fragment});
  tmp.write("x.geo", "Point(1) = {0, 0, 0};\n");
  tmp.write("x.geo.opt", "Exit;\n");
  expect_input_error([&] { screen_geo_file(tmp.file("x.geo")); }, {"x.geo.opt:1: 'Exit' ends the process"});
  EXPECT_NO_THROW(screen_geo_text("lc = 0.1; s[] = {1, 2};\nFor i In {0:#s[]-1}\n  x = s[i] + 1;\nEndFor\n"
                                  "Macro M\n  Point(newp) = {x, 0, 0, lc};\nReturn\nCall M;\n"
                                  "Field[1] = Box; Field[1].VIn = lc; Background Field = 1;\n"
                                  "Printf(\"x = %g\", x > 1);\nMesh.Algorithm = 6;\n",
                                  "x.geo", dir));
}

// Meshing is bounded: a size far too small for the geometry is refused before gmsh
// meshes (it used to run for minutes or die of std::bad_alloc); the limit can be raised.
TEST(GmshReader, CellEstimateBoundsMeshing) {
  for (double size : {1e-9, 4.9e-324}) {
    const std::string msg = expect_input_error([&] { read_mesh(config(input("block2d.geo"), size)); },
                                               {"block2d.geo: ", "'Mesh->max cells' = 5e+06", "raise 'Mesh->max cells'"});
    EXPECT_NE(msg.find("larger 'Mesh->size'"), std::string::npos) << msg;
  }
  MeshConfig c = config(input("block3d.geo"), 0.05);
  c.max_cells = 100;
  expect_input_error([&] { read_mesh(c); }, {"block3d.geo: ", "more than 'Mesh->max cells' = 100"});
  c.max_cells = 1e6;
  EXPECT_GT(read_mesh(c).num_volume_cells(), 100u);
  // The .geo's own sizes (Mesh->size = 0) are estimated from the curve mesh.
  TempDir tmp;
  const std::string fine = tmp.write(
      "fine.geo", "h = 1e-4;\nPoint(1) = {0,0,0,h}; Point(2) = {1,0,0,h}; Point(3) = {1,1,0,h}; Point(4) = {0,1,0,h};\n"
                  "Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};\n"
                  "Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1}; Physical Surface(\"s\") = {1};\n");
  expect_input_error([&] { read_mesh(config(fine)); }, {fine + ": ", "the .geo's own sizes", "'Mesh->max cells'"});
}

// Long meshing prints progress (Progress, used around gmsh's generate with a 10 s
// interval; here 50 ms): nothing for work shorter than one interval, else a line per
// interval with the detail, and a closing line with the total time.
TEST(Progress, LinesOnlyForLongWork) {
  std::ostringstream quick, slow;
  { const stentor::Progress p(quick, "meshing  a.geo", " (about 10 cells)", 10.0); }
  EXPECT_EQ(quick.str(), "");
  {
    const stentor::Progress p(slow, "meshing  b.geo", " (about 1e+06 cells)", 0.05);
    std::this_thread::sleep_for(std::chrono::milliseconds(230));
  }
  const std::string out = slow.str();
  std::size_t lines = 0;
  for (std::size_t at = out.find("so far (about 1e+06 cells)\n"); at != std::string::npos; at = out.find("so far", at + 1)) ++lines;
  EXPECT_GE(lines, 2u) << out;
  EXPECT_LE(lines, 5u) << out;
  EXPECT_EQ(out.rfind("  meshing  b.geo: ", 0), 0u) << out;
  EXPECT_NE(out.find("  meshing  b.geo: done in 0 s\n"), std::string::npos) << out;
}

TEST(GmshReader, UnnamedGroupsAndPointSets) {
  TempDir tmp;
  const std::string f = tmp.write(
      "unnamed.geo", "Point(1) = {0,0,0,0.25}; Point(2) = {2,0,0,0.25}; Point(3) = {2,1,0,0.25};\n"
                     "Point(4) = {0,1,0,0.25};\nLine(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; "
                     "Line(4) = {4,1};\nCurve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};\n"
                     "Physical Surface(7) = {1};\nPhysical Curve(3) = {4};\nPhysical Point(\"corner\") = {3};\n");
  const Mesh m = read_mesh(config(f, 0, 2));
  expect_consistent(m);
  EXPECT_EQ(m.volume_group_names(), std::vector<std::string>{"tag7"});
  EXPECT_EQ(as_set(m.boundary_group_names()), (std::set<std::string>{"tag3", "corner"}));
  EXPECT_EQ(volume_blocks(m, "tag7").front()->physical_tag, 7);
  const auto corner = boundary_blocks(m, "corner");
  ASSERT_EQ(corner.size(), 1u);
  EXPECT_EQ(corner[0]->type, CellType::Point1);
  const auto cn = boundary_nodes(m, "corner");
  ASSERT_EQ(cn.size(), 1u);
  EXPECT_EQ(m.x[3 * cn[0]], 2.0);
  EXPECT_EQ(m.x[3 * cn[0] + 1], 1.0);
  EXPECT_NEAR(measure(m), 2.0, 1e-12);
}

TEST(GmshReader, ClockwiseSurfaceIsReportedNotFlipped) {
  TempDir tmp;
  const std::string f = tmp.write(
      "cw.geo", "Point(1) = {0,0,0,0.25}; Point(2) = {1,0,0,0.25}; Point(3) = {1,1,0,0.25};\n"
                "Point(4) = {0,1,0,0.25};\nLine(1) = {1,4}; Line(2) = {4,3}; Line(3) = {3,2}; "
                "Line(4) = {2,1};\nCurve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};\n"
                "Physical Surface(\"ring\") = {1};\n");
  const Mesh m = read_mesh(config(f));
  // gmsh meshes a clockwise curve loop clockwise; Stentor keeps that orientation.
  EXPECT_EQ(count_inverted_cells(m), m.num_volume_cells());
  expect_input_error([&] { check_mesh(m); },
                     {f + ": ", "inverted or degenerate elements (det J <= 0) in group 'ring'", "clockwise"});
}

// ---------------------------------------------------------------- check_mesh

TEST(MeshCheck, FlagsInvertedAndDegenerateTriangles) {
  Mesh m;
  m.dim = 2;
  m.source = "hand.msh";
  // nodes: unit square corners + a point on the diagonal
  m.x = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 0};
  CellBlock b;
  b.name = "ring";
  b.physical_tag = 1;
  b.type = CellType::Tri3;
  b.nodes_per_cell = 3;
  b.conn = {0, 1, 2, 0, 2, 3};
  b.cell_id = {0, 1};
  m.volumes.push_back(b);
  EXPECT_NO_THROW(check_mesh(m));

  m.volumes[0].conn = {0, 1, 2, 0, 3, 2};  // second one clockwise
  EXPECT_EQ(count_inverted_cells(m), 1u);
  const std::string msg =
      expect_input_error([&] { check_mesh(m); },
                         {"hand.msh: 1 inverted or degenerate element (det J <= 0) in group 'ring'", "cell 1",
                          "(0.333333, 0.666667, 0)"});
  EXPECT_EQ(msg.find("clockwise"), std::string::npos);

  m.volumes[0].conn = {0, 1, 2, 0, 4, 2};  // second one degenerate (collinear)
  expect_input_error([&] { check_mesh(m); }, {"1 inverted or degenerate element", "cell 1"});

  m.volumes[0].conn = {0, 2, 1, 0, 3, 2};  // both clockwise
  expect_input_error([&] { check_mesh(m); }, {"2 inverted or degenerate elements", "cell 0", "clockwise"});

  // A boundary node that no body cell holds.
  m.volumes[0].conn = {0, 1, 2, 0, 2, 3};
  CellBlock pt;
  pt.name = "stray";
  pt.type = CellType::Point1;
  pt.nodes_per_cell = 1;
  pt.conn = {4};
  pt.cell_id = {0};
  m.boundaries.push_back(pt);
  expect_input_error([&] { check_mesh(m); }, {"hand.msh: ", "'stray'", "belong to no body"});
}

TEST(MeshCheck, FlagsInvertedTet10) {
  Mesh m = read_mesh(config(input("block3d.geo"), 0.5, 2));
  EXPECT_NO_THROW(check_mesh(m));
  // Swap two vertices of cell 0 (and the matching mid-edge nodes stay put: also distorted).
  auto& b = m.volumes[0];
  std::swap(b.conn[1], b.conn[2]);
  EXPECT_GE(count_inverted_cells(m), 1u);
  expect_input_error([&] { check_mesh(m); }, {"in group 'block'", "cell 0"});
}

// ---------------------------------------------------------------- queries

TEST(MeshQuery, MissingGroupsListWhatExists) {
  const Mesh m = read_mesh(config(input("block2d.geo"), 0.25));
  const std::string msg = expect_input_error(
      [&] { boundary_nodes(m, "lefft"); },
      {"physical group 'lefft' not found in mesh " + input("block2d.geo"), "available boundary groups: ", "left",
       "right", "bottom", "top"});
  EXPECT_EQ(msg.find("block"), msg.find("block2d.geo"));  // only in the file name
  expect_input_error([&] { volume_blocks(m, "ring"); }, {"physical group 'ring' not found", "available volume groups: block"});
  expect_input_error([&] { boundary_blocks(m, "block"); }, {"'block' is a body (volume) group"});
  expect_input_error([&] { volume_blocks(m, "left"); }, {"'left' is a boundary group"});
  EXPECT_TRUE(has_boundary_group(m, "top"));
  EXPECT_FALSE(has_boundary_group(m, "block"));
  EXPECT_TRUE(has_volume_group(m, "block"));
  // left edge of a 0.25 mesh of the unit square: 5 nodes at x = 0.
  const auto left = boundary_nodes(m, "left");
  EXPECT_EQ(left.size(), 5u);
}

// ---------------------------------------------------------------- partitioning

TEST(MeshComm, PartitionIsBalancedAndDeterministic) {
  for (const auto& [geo, size, order] :
       {std::make_tuple("artery_ring.geo", 1e-4, 1), std::make_tuple("block3d.geo", 0.2, 2),
        std::make_tuple("cook.geo", 2.0, 1)}) {
    SCOPED_TRACE(geo);
    const Mesh m = read_mesh(config(input(geo), size, order));
    const std::size_t nc = m.num_volume_cells();
    EXPECT_EQ(partition_cells(m, 1), std::vector<int>(nc, 0));
    for (int np : {2, 4}) {
      const auto part = partition_cells(m, np);
      ASSERT_EQ(part.size(), nc);
      std::vector<std::size_t> count(np, 0);
      for (int p : part) {
        ASSERT_GE(p, 0);
        ASSERT_LT(p, np);
        ++count[p];
      }
      const double avg = double(nc) / np;
      for (int p = 0; p < np; ++p) {
        EXPECT_GT(count[p], 0u);
        EXPECT_LE(count[p], 1.1 * avg + 1) << "part " << p;
      }
      EXPECT_EQ(partition_cells(m, np), part);  // deterministic

      const auto owner = node_owners(m, part);
      ASSERT_EQ(owner.size(), m.num_nodes());
      std::vector<int> expect(m.num_nodes(), np);
      for (const auto& b : m.volumes)
        for (std::size_t c = 0; c < b.num_cells(); ++c)
          for (int a = 0; a < b.nodes_per_cell; ++a) {
            int& e = expect[b.conn[c * b.nodes_per_cell + a]];
            e = std::min(e, part[b.cell_id[c]]);
          }
      EXPECT_EQ(owner, expect);
    }
  }
  const Mesh tiny = read_mesh(config(input("block2d.geo"), 2.0));
  expect_input_error([&] { partition_cells(tiny, int(tiny.num_volume_cells()) + 1); }, {"cannot split"});
}
