// Stages (issue 10): a procedure written as "Stages" equals the same procedure written
// as one interval with ramp tables, where both can express it (to 1e-10): loads switched
// and held across stages (statics and dynamics), and a rigid balloon (a circle obstacle)
// inflated in one stage and partly deflated in the next.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include "CsvSeries.hpp"
#include "deck/Config.hpp"
#include "run/Simulation.hpp"

using namespace stentor;
using namespace stentor::testing;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::path(STENTOR_BINARY_DIR) / "system_tests" / "stages";
const std::string kGeo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block2d.geo";

std::string p(const std::string& name, const std::string& type, const std::string& value) {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>";
}

// A block (block2d.geo, 0.25 cells) made of rubber; `body` holds the rest of the deck.
std::string deck(bool dynamic, const std::string& body) {
  std::ostringstream os;
  os << "<ParameterList name=\"stentor\">\n"
     << "<ParameterList name=\"Problem\">" << p("analysis", "string", dynamic ? "dynamic" : "static") << "</ParameterList>\n"
     << "<ParameterList name=\"Mesh\">" << p("file", "string", kGeo) << p("size", "double", "0.25") << "</ParameterList>\n"
     << "<ParameterList name=\"Materials\"><ParameterList name=\"rubber\">" << p("C1", "double", "0.5e6") << p("D", "double", "0.35e6")
     << p("density", "double", "1000") << "</ParameterList></ParameterList>\n"
     << "<ParameterList name=\"Bodies\"><ParameterList name=\"block\">" << p("material", "string", "rubber")
     << "</ParameterList></ParameterList>\n"
     << "<ParameterList name=\"Linear Solver\">" << p("method", "string", "direct") << "</ParameterList>\n"
     << "<ParameterList name=\"Output\">" << p("fields", "bool", "false") << "</ParameterList>\n"
     << body << "</ParameterList>\n";
  return os.str();
}

struct Outcome {
  int status = -1;
  RunResult res;
  Series history;
  std::string log;
};

Outcome run(const std::string& xml, const std::string& tag) {
  fs::create_directories(kDir);
  const fs::path file = kDir / (tag + ".xml");
  std::ofstream(file) << xml;
  const Config cfg = read_deck(file.string());
  RunOptions opts;
  opts.output_dir = (kDir / tag).string();
  Outcome o;
  std::ostringstream capture;
  std::streambuf* old = std::cout.rdbuf(capture.rdbuf());
  try {
    o.status = run_simulation(cfg, opts, &o.res);
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  std::cout.rdbuf(old);
  o.log = capture.str();
  EXPECT_EQ(o.status, 0) << tag << "\n" << o.log;
  o.history = read_csv(kDir / tag / "stentor_history.csv");
  return o;
}

// Every column of `one` (and the final displacement) equals `staged`'s to `tol` relative
// to the largest value of the column or, for a vector's component (name ending _x, _y,
// _z), of the vector's components: a component that is zero up to round-off is compared
// with the force it is a component of.
void expect_same(const Outcome& staged, const Outcome& one, double tol) {
  ASSERT_EQ(staged.history.rows(), one.history.rows());
  auto stem = [](const std::string& n) {
    const auto k = n.size();
    return k > 2 && n[k - 2] == '_' && (n[k - 1] == 'x' || n[k - 1] == 'y' || n[k - 1] == 'z') ? n.substr(0, k - 2) : n;
  };
  std::map<std::string, double> scale_of;
  for (const auto& [name, v] : one.history.col)
    for (double x : v) scale_of[stem(name)] = std::max(scale_of[stem(name)], std::abs(x));
  for (const auto& [name, v] : one.history.col) {
    const auto& w = staged.history[name];
    const double scale = std::max(1e-300, scale_of[stem(name)]);
    double diff = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) diff = std::max(diff, std::abs(v[i] - w[i]));
    EXPECT_LE(diff, tol * scale) << "column " << name;
  }
  double scale = 1e-300, diff = 0.0;
  for (std::size_t i = 0; i < one.res.displacement.size(); ++i) {
    scale = std::max(scale, std::abs(one.res.displacement[i]));
    diff = std::max(diff, std::abs(one.res.displacement[i] - staged.res.displacement[i]));
  }
  EXPECT_LE(diff, tol * scale) << "final displacement";
  std::printf("[stages] %zu steps: max |u_staged - u_one| = %.2e (|u| %.2e)\n", one.history.rows(), diff, scale);
}

const char* kLoads =
    "<ParameterList name=\"Boundary Conditions\">"
    "<ParameterList name=\"clamp\"><Parameter name=\"type\" type=\"string\" value=\"Dirichlet\"/>"
    "<Parameter name=\"boundary\" type=\"string\" value=\"bottom\"/></ParameterList>"
    "<ParameterList name=\"pull\"><Parameter name=\"type\" type=\"string\" value=\"Dirichlet\"/>"
    "<Parameter name=\"boundary\" type=\"string\" value=\"top\"/><Parameter name=\"components\" type=\"string\" value=\"y\"/>"
    "<Parameter name=\"values\" type=\"Array(double)\" value=\"{0.2}\"/>%PULL%</ParameterList>"
    "<ParameterList name=\"squeeze\"><Parameter name=\"type\" type=\"string\" value=\"pressure\"/>"
    "<Parameter name=\"boundary\" type=\"string\" value=\"right\"/><Parameter name=\"pressure\" type=\"double\" value=\"5e4\"/>"
    "%SQUEEZE%</ParameterList></ParameterList>\n";

std::string loads(const std::string& pull, const std::string& squeeze) {
  std::string s = kLoads;
  s.replace(s.find("%PULL%"), 6, pull);
  s.replace(s.find("%SQUEEZE%"), 9, squeeze);
  return s;
}

std::string table(const std::string& prefix, const std::string& times, const std::string& factors) {
  return p(prefix, "string", "table") + p(prefix + " times", "Array(double)", times) + p(prefix + " factors", "Array(double)", factors);
}

// Stage 1 pulls the top (squeeze off), stage 2 holds the pull (not listed) and ramps the
// pressure up; the same as ramp tables over [0, 2 T].
void pull_then_squeeze(bool dynamic) {
  const std::string T = dynamic ? "0.1" : "1", T2 = dynamic ? "0.2" : "2";
  const std::string staged = deck(dynamic, loads("", "") +
      "<ParameterList name=\"Stages\">"
      "<ParameterList name=\"pull\">" + p("duration", "double", T) + p("steps", "int", "4") + p("loads", "string", "clamp, pull") +
      "</ParameterList><ParameterList name=\"squeeze\">" + p("end time", "double", T2) + p("step", "double", dynamic ? "0.025" : "0.25") +
      p("loads", "string", "clamp,squeeze") + "</ParameterList></ParameterList>\n");
  const std::string one = deck(dynamic, loads(table("ramp", "{0, " + T + "}", "{0, 1}"), table("ramp", "{0, " + T + ", " + T2 + "}", "{0, 0, 1}")) +
      "<ParameterList name=\"Stepping\">" + p("end time", "double", T2) + p("steps", "int", "8") + "</ParameterList>\n");
  const std::string tag = dynamic ? "dynamic" : "static";
  const Outcome a = run(staged, "pull_squeeze_staged_" + tag), b = run(one, "pull_squeeze_one_" + tag);
  EXPECT_NE(a.log.find("stage 2/2 'squeeze'"), std::string::npos) << a.log;
  // The progress lines name the stage and count its own time against its duration, then
  // the wall time and the estimate for the whole procedure.
  const std::string d = dynamic ? "0.1" : "1", first = dynamic ? "0.025" : "0.25";
  EXPECT_NE(a.log.find("[pull 1/2: " + first + " of " + d + " s; "), std::string::npos) << a.log;
  EXPECT_NE(a.log.find("[squeeze 2/2: " + first + " of " + d + " s; "), std::string::npos) << "stage-local time\n" << a.log;
  const auto last = a.log.find("[squeeze 2/2: " + d + " of " + d + " s; ");
  ASSERT_NE(last, std::string::npos) << a.log;
  const std::string tail = a.log.substr(last, a.log.find('\n', last) - last);
  EXPECT_NE(tail.find(" s, ~"), std::string::npos) << tail;
  EXPECT_NE(tail.find(" s left]"), std::string::npos) << tail;
  ASSERT_TRUE(a.history.has("stage"));
  EXPECT_EQ(a.history["stage"].front(), 1.0);
  EXPECT_EQ(a.history["stage"].back(), 2.0);
  expect_same(a, b, 1e-10);
}

}  // namespace

TEST(Stages, StaticPullThenSqueezeEqualsRampTables) { pull_then_squeeze(false); }
TEST(Stages, DynamicPullThenSqueezeEqualsRampTables) { pull_then_squeeze(true); }

// A rigid balloon (circle under the block, whose top is clamped) inflates in stage 1
// (deck ramp, linear in stage-local time) and deflates to half in stage 2 (a stage ramp
// table); then a stage with contact off and the balloon held. The first two stages equal
// one interval with a radius table.
TEST(Stages, RigidBalloonInflateDeflateEqualsRampTable) {
  auto body = [&](const std::string& radius_ramp) {
    return "<ParameterList name=\"Boundary Conditions\"><ParameterList name=\"hold\">" + p("type", "string", "Dirichlet") +
           p("boundary", "string", "top") + "</ParameterList></ParameterList>\n"
           "<ParameterList name=\"Contact\"><ParameterList name=\"balloon\">" + p("slave", "string", "bottom") +
           p("obstacle", "string", "circle") + p("point", "Array(double)", "{0.5, -0.5}") + p("radius", "double", "0.45") +
           p("radius change", "double", "0.15") + radius_ramp + "</ParameterList></ParameterList>\n";
  };
  const std::string stages =
      "<ParameterList name=\"Stages\">"
      "<ParameterList name=\"inflate\">" + p("duration", "double", "1") + p("steps", "int", "4") + "</ParameterList>"
      "<ParameterList name=\"deflate\">" + p("duration", "double", "0.5") + p("steps", "int", "2") +
      "<ParameterList name=\"Ramps\"><ParameterList name=\"balloon\">" + table("radius ramp", "{0, 0.5}", "{1, 0.5}") +
      "</ParameterList></ParameterList></ParameterList>";
  const Outcome a = run(deck(false, body("") + stages + "</ParameterList>\n"), "balloon_staged");
  const Outcome b = run(deck(false, body(table("radius ramp", "{0, 1, 1.5}", "{0, 1, 0.5}")) + "<ParameterList name=\"Stepping\">" +
                                        p("end time", "double", "1.5") + p("steps", "int", "6") + "</ParameterList>\n"),
                        "balloon_one");
  // The balloon pushes into the block: contact force at the end of inflation.
  const auto& fy = b.history["contact_balloon_force_y"];
  ASSERT_EQ(fy.size(), 6u);
  EXPECT_GT(std::abs(fy[3]), 0.0);
  expect_same(a, b, 1e-10);

  // Released: with the pair off in a third stage the block springs back to rest.
  const Outcome c = run(deck(false, body("") + stages +
                                        "<ParameterList name=\"release\">" + p("duration", "double", "0.5") + p("contact", "string", "none") +
                                        "</ParameterList></ParameterList>\n"),
                        "balloon_release");
  double umax = 0.0;
  for (double v : c.res.displacement) umax = std::max(umax, std::abs(v));
  EXPECT_LT(umax, 1e-8) << "the block did not return to rest once contact was off";
  EXPECT_EQ(c.history["contact_balloon_active"].back(), 0.0);
}
