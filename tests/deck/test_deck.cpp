// Input deck reader: parsing, defaults, every kind of validation error, ramps, and
// the agreement of docs/deck.md with the schema.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "deck/Config.hpp"
#include "deck/Schema.hpp"

namespace fs = std::filesystem;
using namespace stentor;

namespace {

// A complete deck using (almost) every feature.
const char* kFullDeck = R"XML(<?xml version="1.0"?>
<!-- full test deck -->
<ParameterList name="stentor">
  <ParameterList name="Problem">
    <Parameter name="title" type="string" value="ring test"/>
  </ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value="mesh/ring.msh"/>
    <Parameter name="dimension" type="int" value="2"/>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="steel">
      <Parameter name="model" type="string" value="ciarlet-geymonat"/>
      <Parameter name="C1" type="double" value="200e6"/>
      <Parameter name="C2" type="int" value="2000000"/>
      <Parameter name="D" type="double" value="140e6"/>
      <Parameter name="density" type="double" value="7800"/>
    </ParameterList>
    <ParameterList name="artery">
      <Parameter name="C1" type="double" value="0.5e6"/>
      <Parameter name="D" type="double" value="0.35e6"/>
      <Parameter name="viscosity" type="double" value="10"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="stent">
      <Parameter name="material" type="string" value="steel"/>
      <Parameter name="physical group" type="string" value="stent_surface"/>
    </ParameterList>
    <ParameterList name="vessel">
      <Parameter name="material" type="string" value="artery"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="clamp">
      <Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="base"/>
      <Parameter name="components" type="string" value="all"/>
    </ParameterList>
    <ParameterList name="pull">
      <Parameter name="type" type="string" value="dirichlet"/>
      <Parameter name="boundary" type="string" value="top"/>
      <Parameter name="components" type="string" value="y, x"/>
      <Parameter name="values" type="Array(double)" value="{0.1, -0.2}"/>
      <Parameter name="ramp" type="string" value="table"/>
      <Parameter name="ramp times" type="Array(double)" value="{0, 0.5, 1}"/>
      <Parameter name="ramp factors" type="Array(double)" value="{0, 1, 0.5}"/>
    </ParameterList>
    <ParameterList name="push">
      <Parameter name="type" type="string" value="traction"/>
      <Parameter name="boundary" type="string" value="right"/>
      <Parameter name="traction" type="Array(double)" value="{1e3, 0}"/>
      <Parameter name="ramp" type="string" value="Constant"/>
    </ParameterList>
    <ParameterList name="blow">
      <Parameter name="type" type="string" value="Pressure"/>
      <Parameter name="boundary" type="string" value="inner"/>
      <Parameter name="pressure" type="double" value="1.5e4"/>
    </ParameterList>
    <ParameterList name="gravity">
      <Parameter name="type" type="string" value="Body Force"/>
      <Parameter name="body" type="string" value="stent"/>
      <Parameter name="force" type="Array(double)" value="{0, -9.81e3}"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Stepping">
    <Parameter name="end time" type="double" value="2"/>
    <Parameter name="steps" type="int" value="10"/>
  </ParameterList>
  <ParameterList name="Newton">
    <Parameter name="max iterations" type="int" value="30"/>
    <Parameter name="line search" type="bool" value="false"/>
  </ParameterList>
  <ParameterList name="Linear Solver">
    <Parameter name="preconditioner" type="string" value="None"/>
    <Parameter name="subdomain solver" type="string" value="riluk"/>
    <Parameter name="tolerance" type="double" value="1e-8"/>
    <ParameterList name="Belos">
      <Parameter name="Num Blocks" type="int" value="50"/>
      <Parameter name="Any Belos Option" type="string" value="kept as is"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="directory" type="string" value="out"/>
    <Parameter name="every" type="int" value="2"/>
    <ParameterList name="Probes">
      <ParameterList name="tip">
        <Parameter name="point" type="Array(double)" value="{1, 2}"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
)XML";

// The smallest valid deck.
const char* kMinimalDeck = R"XML(<ParameterList name="anything">
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value="mesh/ring.msh"/>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="steel">
      <Parameter name="C1" type="double" value="1"/>
      <Parameter name="D" type="double" value="2"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="stent">
      <Parameter name="material" type="string" value="steel"/>
    </ParameterList>
  </ParameterList>
</ParameterList>
)XML";

class Deck : public ::testing::Test {
 protected:
  fs::path dir;
  void SetUp() override {
    static int counter = 0;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() /
          ("stentor_test_deck_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" + info->name());
    fs::create_directories(dir / "mesh");
    std::ofstream(dir / "mesh" / "ring.msh") << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string write(const std::string& xml, const std::string& name = "deck.xml") {
    const auto p = dir / name;
    std::ofstream(p) << xml;
    return p.string();
  }
  // Reads `xml` expecting an InputError that starts with the deck file name and
  // contains every needle.
  std::string expect_error(const std::string& xml, const std::vector<std::string>& needles) {
    const std::string path = write(xml);
    try {
      read_deck(path);
    } catch (const InputError& e) {
      const std::string msg = e.what();
      if (std::getenv("STENTOR_DECK_SHOW_ERRORS")) std::cout << "  " << msg << "\n";  // to review the wording
      EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << "message does not start with the deck file: " << msg;
      for (const auto& n : needles) EXPECT_NE(msg.find(n), std::string::npos) << "missing '" << n << "' in: " << msg;
      return msg;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
      return "";
    }
    ADD_FAILURE() << "expected InputError containing '" << needles.front() << "', but the deck was accepted";
    return "";
  }
};

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  if (pos == std::string::npos) throw std::logic_error("test bug: '" + from + "' not in deck");
  return s.replace(pos, from.size(), to);
}

}  // namespace

// ---------------------------------------------------------------------------
// Valid decks.

TEST_F(Deck, FullDeckParses) {
  const std::string path = write(kFullDeck);
  const Config c = read_deck(path);
  EXPECT_EQ(c.deck_path, fs::path(path).lexically_normal().string());
  EXPECT_EQ(c.problem.title, "ring test");
  EXPECT_EQ(c.problem.analysis, "static");
  EXPECT_EQ(c.mesh.file, (dir / "mesh" / "ring.msh").lexically_normal().string());
  EXPECT_EQ(c.mesh.dimension, 2);
  EXPECT_EQ(c.mesh.order, 1);

  ASSERT_EQ(c.materials.size(), 2u);
  EXPECT_EQ(c.materials[0].name, "steel");
  EXPECT_EQ(c.materials[0].model, "Ciarlet-Geymonat");
  EXPECT_DOUBLE_EQ(c.materials[0].C1, 200e6);
  EXPECT_DOUBLE_EQ(c.materials[0].C2, 2e6);  // an int is fine for a double
  EXPECT_DOUBLE_EQ(c.materials[0].D, 140e6);
  EXPECT_DOUBLE_EQ(c.materials[0].density, 7800);
  EXPECT_DOUBLE_EQ(c.materials[0].viscosity, 0);
  EXPECT_EQ(c.materials[1].name, "artery");
  EXPECT_DOUBLE_EQ(c.materials[1].C2, 0);
  EXPECT_DOUBLE_EQ(c.materials[1].viscosity, 10);
  EXPECT_EQ(&c.material("artery"), &c.materials[1]);
  EXPECT_THROW(c.material("bone"), InputError);

  ASSERT_EQ(c.bodies.size(), 2u);
  EXPECT_EQ(c.bodies[0].name, "stent");
  EXPECT_EQ(c.bodies[0].group, "stent_surface");
  EXPECT_EQ(c.bodies[0].material, "steel");
  EXPECT_EQ(c.bodies[1].group, "vessel");  // default: the sublist name

  ASSERT_EQ(c.loads.size(), 5u);
  const auto& clamp = c.loads[0];
  EXPECT_EQ(clamp.name, "clamp");
  EXPECT_EQ(clamp.type, LoadConfig::Type::Dirichlet);
  EXPECT_EQ(clamp.group, "base");
  EXPECT_TRUE(clamp.all_components);
  EXPECT_TRUE(clamp.components[0] && clamp.components[1] && !clamp.components[2]);  // 2D: no z
  EXPECT_EQ(clamp.vector, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(clamp.ramp.kind, Ramp::Kind::Linear);
  const auto& pull = c.loads[1];
  EXPECT_EQ(pull.type, LoadConfig::Type::Dirichlet);
  EXPECT_FALSE(pull.all_components);
  EXPECT_TRUE(pull.components[0] && pull.components[1] && !pull.components[2]);
  EXPECT_DOUBLE_EQ(pull.vector[1], 0.1);  // "y, x" with {0.1, -0.2}
  EXPECT_DOUBLE_EQ(pull.vector[0], -0.2);
  EXPECT_EQ(pull.ramp.kind, Ramp::Kind::Table);
  EXPECT_EQ(pull.ramp.times, (std::vector<double>{0, 0.5, 1}));
  EXPECT_EQ(pull.ramp.factors, (std::vector<double>{0, 1, 0.5}));
  EXPECT_EQ(c.loads[2].type, LoadConfig::Type::Traction);
  EXPECT_EQ(c.loads[2].group, "right");
  EXPECT_DOUBLE_EQ(c.loads[2].vector[0], 1e3);
  EXPECT_EQ(c.loads[2].ramp.kind, Ramp::Kind::Constant);
  EXPECT_EQ(c.loads[3].type, LoadConfig::Type::Pressure);
  EXPECT_DOUBLE_EQ(c.loads[3].value, 1.5e4);
  EXPECT_EQ(c.loads[4].type, LoadConfig::Type::BodyForce);
  EXPECT_EQ(c.loads[4].group, "stent_surface");  // the body's physical group
  EXPECT_DOUBLE_EQ(c.loads[4].vector[1], -9.81e3);

  EXPECT_DOUBLE_EQ(c.stepping.end_time, 2);
  EXPECT_EQ(c.stepping.num_steps, 10);
  EXPECT_EQ(c.stepping.max_cutbacks, 6);
  EXPECT_EQ(c.newton.max_iterations, 30);
  EXPECT_FALSE(c.newton.line_search);
  EXPECT_DOUBLE_EQ(c.newton.residual_tolerance, 1e-10);
  EXPECT_EQ(c.linear.method, "gmres");
  EXPECT_EQ(c.linear.preconditioner, "none");
  EXPECT_EQ(c.linear.subdomain_solver, "RILUK");
  EXPECT_DOUBLE_EQ(c.linear.tolerance, 1e-8);
  EXPECT_NE(c.linear.belos_xml.find("Num Blocks"), std::string::npos);
  EXPECT_NE(c.linear.belos_xml.find("kept as is"), std::string::npos);
  EXPECT_TRUE(c.linear.ifpack2_xml.empty());
  EXPECT_EQ(c.output.directory, "out");
  EXPECT_EQ(c.output.basename, "stentor");
  EXPECT_EQ(c.output.every, 2);
  ASSERT_EQ(c.output.probes.size(), 1u);
  EXPECT_EQ(c.output.probes[0].name, "tip");
  EXPECT_EQ(c.output.probes[0].point, (std::array<double, 3>{1, 2, 0}));
}

TEST_F(Deck, MinimalDeckGetsTheStructDefaults) {
  const Config c = read_deck(write(kMinimalDeck));
  const Config d;
  EXPECT_EQ(c.problem.title, d.problem.title);
  EXPECT_EQ(c.problem.analysis, d.problem.analysis);
  EXPECT_EQ(c.mesh.size, d.mesh.size);
  EXPECT_EQ(c.mesh.order, d.mesh.order);
  EXPECT_EQ(c.mesh.recombine, d.mesh.recombine);
  EXPECT_EQ(c.mesh.dimension, d.mesh.dimension);
  EXPECT_EQ(c.materials.at(0).model, MaterialConfig{}.model);
  EXPECT_EQ(c.materials.at(0).C2, 0.0);
  EXPECT_TRUE(c.loads.empty());
  EXPECT_EQ(c.stepping.end_time, d.stepping.end_time);
  EXPECT_EQ(c.stepping.num_steps, d.stepping.num_steps);
  EXPECT_EQ(c.stepping.max_cutbacks, d.stepping.max_cutbacks);
  EXPECT_EQ(c.newton.max_iterations, d.newton.max_iterations);
  EXPECT_EQ(c.newton.residual_tolerance, d.newton.residual_tolerance);
  EXPECT_EQ(c.newton.absolute_tolerance, d.newton.absolute_tolerance);
  EXPECT_EQ(c.newton.increment_tolerance, d.newton.increment_tolerance);
  EXPECT_EQ(c.newton.line_search, d.newton.line_search);
  EXPECT_EQ(c.newton.line_search_max, d.newton.line_search_max);
  EXPECT_EQ(c.linear.method, d.linear.method);
  EXPECT_EQ(c.linear.preconditioner, d.linear.preconditioner);
  EXPECT_EQ(c.linear.tolerance, d.linear.tolerance);
  EXPECT_EQ(c.linear.max_iterations, d.linear.max_iterations);
  EXPECT_EQ(c.linear.restart, d.linear.restart);
  EXPECT_EQ(c.linear.overlap, d.linear.overlap);
  EXPECT_EQ(c.linear.subdomain_solver, d.linear.subdomain_solver);
  EXPECT_EQ(c.linear.fill_level, d.linear.fill_level);
  EXPECT_EQ(d.output.directory, "results/{deck}");  // per deck: {deck} is the deck's file name stem
  EXPECT_EQ(c.output.directory, "results/" + std::filesystem::path(c.deck_path).stem().string());
  EXPECT_EQ(c.output.basename, d.output.basename);
  EXPECT_EQ(c.output.every, d.output.every);
  EXPECT_EQ(c.output.fields, d.output.fields);
}

// A deck without a Newton / Linear Solver / Stepping sublist gets the structs' defaults,
// one with the sublists empty the schema's: the two must agree (they once did not for
// Newton->forcing, so decks without a Newton list solved with another forcing term).
TEST_F(Deck, EmptySublistsGetTheSameDefaultsAsAbsentOnes) {
  const Config a = read_deck(write(kMinimalDeck));
  const Config e = read_deck(write(replace(kMinimalDeck, "</ParameterList>\n</ParameterList>", R"(</ParameterList>
  <ParameterList name="Stepping"/>
  <ParameterList name="Newton"/>
  <ParameterList name="Linear Solver"/>
</ParameterList>)")));
  EXPECT_EQ(a.stepping.predictor, e.stepping.predictor);
  EXPECT_EQ(a.stepping.growth, e.stepping.growth);
  EXPECT_EQ(a.stepping.max_cutbacks, e.stepping.max_cutbacks);
  EXPECT_EQ(a.newton.max_iterations, e.newton.max_iterations);
  EXPECT_EQ(a.newton.residual_tolerance, e.newton.residual_tolerance);
  EXPECT_EQ(a.newton.absolute_tolerance, e.newton.absolute_tolerance);
  EXPECT_EQ(a.newton.increment_tolerance, e.newton.increment_tolerance);
  EXPECT_EQ(a.newton.line_search, e.newton.line_search);
  EXPECT_EQ(a.newton.line_search_max, e.newton.line_search_max);
  EXPECT_EQ(a.newton.line_search_watchdog, e.newton.line_search_watchdog);
  EXPECT_EQ(a.newton.forcing, e.newton.forcing);
  EXPECT_EQ(a.newton.forcing_max, e.newton.forcing_max);
  EXPECT_EQ(a.newton.max_increment, e.newton.max_increment);
  EXPECT_EQ(a.linear.method, e.linear.method);
  EXPECT_EQ(a.linear.preconditioner, e.linear.preconditioner);
  EXPECT_EQ(a.linear.tolerance, e.linear.tolerance);
  EXPECT_EQ(a.linear.max_iterations, e.linear.max_iterations);
  EXPECT_EQ(a.linear.restart, e.linear.restart);
  EXPECT_EQ(a.linear.overlap, e.linear.overlap);
  EXPECT_EQ(a.linear.subdomain_solver, e.linear.subdomain_solver);
  EXPECT_EQ(a.linear.fill_level, e.linear.fill_level);
  EXPECT_EQ(a.linear.preconditioner_reuse, e.linear.preconditioner_reuse);
}

TEST_F(Deck, DirichletAllWithoutDimensionKeepsZ) {
  const std::string xml = replace(kMinimalDeck, "</ParameterList>\n</ParameterList>", R"(</ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="fix">
      <Parameter name="type" type="string" value="DIRICHLET"/>
      <Parameter name="boundary" type="string" value="base"/>
    </ParameterList>
  </ParameterList>
</ParameterList>)");
  const Config c = read_deck(write(xml));
  ASSERT_EQ(c.loads.size(), 1u);
  EXPECT_TRUE(c.loads[0].all_components);  // default "all"
  EXPECT_TRUE(c.loads[0].components[0] && c.loads[0].components[1] && c.loads[0].components[2]);
}

TEST_F(Deck, DocExampleParses) {
  std::ifstream f(std::string(STENTOR_SOURCE_DIR) + "/docs/deck.md");
  ASSERT_TRUE(f) << "docs/deck.md not found";
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string md = ss.str();
  const auto b = md.find("```xml\n");
  ASSERT_NE(b, std::string::npos);
  const auto e = md.find("```", b + 7);
  ASSERT_NE(e, std::string::npos);
  std::ofstream(dir / "block2d.geo") << "// placeholder\n";
  const Config c = read_deck(write(md.substr(b + 7, e - b - 7)));
  EXPECT_EQ(c.loads.size(), 4u);
  EXPECT_EQ(c.mesh.order, 2);
  EXPECT_EQ(c.output.probes.size(), 1u);
}

TEST(ShippedDecks, AllInputDecksValidate) {
  const fs::path inputs = fs::path(STENTOR_SOURCE_DIR) / "inputs";
  if (!fs::is_directory(inputs)) GTEST_SKIP() << "no inputs/ folder";
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(inputs)) {
    if (e.path().extension() != ".xml") continue;
    ++n;
    try {
      read_deck(e.path().string());
    } catch (const std::exception& ex) {
      ADD_FAILURE() << ex.what();
    }
  }
  std::cout << "  validated " << n << " deck(s) in inputs/\n";
}

// ---------------------------------------------------------------------------
// Errors.

TEST_F(Deck, MissingDeckFile) {
  const std::string path = (dir / "nope.xml").string();
  try {
    read_deck(path);
    ADD_FAILURE() << "accepted a missing deck";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

TEST_F(Deck, MalformedXml) {
  const std::string msg = expect_error(replace(kMinimalDeck, "value=\"1\"/>", "value=\"1\""),
                                       {"malformed XML at line 8"});
  EXPECT_EQ(msg.find("Throw number"), std::string::npos) << msg;
  expect_error(replace(kMinimalDeck, "</ParameterList>\n</ParameterList>", "</ParameterList>\n</ParameterLst>"),
               {"malformed XML at line", "ParameterLst"});
  expect_error("", {"malformed XML"});
  expect_error("<Stentor name=\"x\"/>", {"root element", "<Stentor>"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"C1\"", "<Param name=\"C1\""),
               {"unexpected element <Param> in 'Materials->steel'"});
}

TEST_F(Deck, UnknownParameterSuggestsNearest) {
  const std::string msg = expect_error(replace(kMinimalDeck, "name=\"C1\"", "name=\"C11\""),
                                       {"unknown parameter 'Materials->steel->C11'; did you mean 'C1'?"});
  expect_error(replace(kMinimalDeck, "name=\"file\" type=\"string\" value=\"mesh/ring.msh\"/>",
                       "name=\"file\" type=\"string\" value=\"mesh/ring.msh\"/>\n"
                       "<Parameter name=\"Dimension\" type=\"int\" value=\"2\"/>"),
               {"unknown parameter 'Mesh->Dimension'; did you mean 'dimension'?"});
  // No close name: the valid ones are listed.
  expect_error(replace(kMinimalDeck, "name=\"C1\"", "name=\"stiffness\""),
               {"unknown parameter 'Materials->steel->stiffness'", "valid parameters of 'Materials->steel': model, C1"});
}

TEST_F(Deck, UnknownSublist) {
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"Bodies\">",
                       "<ParameterList name=\"Steping\"/>\n<ParameterList name=\"Bodies\">"),
               {"unknown sublist 'Steping'; did you mean 'Stepping'?"});
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"Bodies\">",
                       "<ParameterList name=\"Contacts\"/>\n<ParameterList name=\"Bodies\">"),
               {"unknown sublist 'Contacts'; did you mean 'Contact'?"});
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"Bodies\">",
                       "<ParameterList name=\"Plasticity\"/>\n<ParameterList name=\"Bodies\">"),
               {"unknown sublist 'Plasticity'", "valid sublists of the root list: Problem, Mesh"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"C1\" type=\"double\" value=\"1\"/>",
                       "<ParameterList name=\"C1\"/>"),
               {"'Materials->steel->C1' must be a parameter (double), not a sublist"});
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"steel\">",
                       "<Parameter name=\"C1\" type=\"double\" value=\"1\"/>\n<ParameterList name=\"steel\">"),
               {"'Materials->C1' is a parameter", "one per material"});
}

TEST_F(Deck, WrongType) {
  expect_error(replace(kMinimalDeck, "name=\"C1\" type=\"double\" value=\"1\"", "name=\"C1\" type=\"string\" value=\"abc\""),
               {"wrong type for 'Materials->steel->C1': expected double, got string 'abc'"});
  // Teuchos would silently read "abc" as 0 for a double.
  expect_error(replace(kMinimalDeck, "name=\"C1\" type=\"double\" value=\"1\"", "name=\"C1\" type=\"double\" value=\"abc\""),
               {"'Materials->steel->C1'", "needs a number", "'abc'"});
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"Bodies\">",
                       "<ParameterList name=\"Stepping\"><Parameter name=\"steps\" type=\"double\" value=\"2.5\"/>"
                       "</ParameterList>\n<ParameterList name=\"Bodies\">"),
               {"wrong type for 'Stepping->steps': expected int, got double 2.5"});
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"Bodies\">",
                       "<ParameterList name=\"Stepping\"><Parameter name=\"steps\" type=\"int\" value=\"2.5\"/>"
                       "</ParameterList>\n<ParameterList name=\"Bodies\">"),
               {"'Stepping->steps'", "needs an integer", "'2.5'"});
  expect_error(replace(kMinimalDeck, "name=\"C1\" type=\"double\"", "name=\"C1\" type=\"doubel\""),
               {"'Materials->steel->C1' has unknown type 'doubel'", "did you mean 'double'?"});
  expect_error(replace(kMinimalDeck, "name=\"C1\" type=\"double\" value=\"1\"",
                       "name=\"C1\" type=\"Array(double)\" value=\"{1, 2}\""),
               {"wrong type for 'Materials->steel->C1': expected double, got Array(double) {1, 2}"});
}

// Every real number goes through one strict reader: NaN, Inf, hex floats, overflow,
// underflow to 0 (found by the corpus) and malformed numbers are refused naming the parameter (Teuchos read array entries such
// as {nan} or {1e999} as 0, and strtod accepted them all).
TEST_F(Deck, NonFiniteAndUnparsableNumbers) {
  const std::string traction = "name=\"traction\" type=\"Array(double)\" value=\"{1e3, 0}\"";
  for (const std::string bad : {"nan", "NaN", "inf", "-inf", "Infinity", "0x1p-2", "1e999", "-1e400", "1e", "1.2.3", "--1", ".",
                                "1e-400", "-2.5e-999"}) {
    SCOPED_TRACE(bad);
    expect_error(replace(kFullDeck, traction, "name=\"traction\" type=\"Array(double)\" value=\"{" + bad + ", 0}\""),
                 {"'Boundary Conditions->push->traction'", "needs an array {a, b, ...} of double values", "'" + bad + "'"});
    expect_error(replace(kMinimalDeck, "name=\"C1\" type=\"double\" value=\"1\"",
                         "name=\"C1\" type=\"double\" value=\"" + bad + "\""),
                 {"'Materials->steel->C1'", "needs a number (finite and decimal", "'" + bad + "'"});
  }
  // In pass-through lists too.
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"Bodies\">",
                       "<ParameterList name=\"Linear Solver\"><ParameterList name=\"Belos\">"
                       "<Parameter name=\"Convergence Tolerance\" type=\"double\" value=\"nan\"/></ParameterList>"
                       "</ParameterList>\n<ParameterList name=\"Bodies\">"),
               {"'Linear Solver->Belos->Convergence Tolerance'", "needs a number"});
  // Decimal forms are read exactly as written, by the same reader.
  const Config c = read_deck(write(replace(kFullDeck, traction, "name=\"traction\" type=\"Array(double)\" value=\"{ .5 , -2.E-3 }\"")));
  bool found = false;
  for (const auto& l : c.loads)
    if (l.name == "push") {
      found = true;
      EXPECT_EQ(l.vector[0], 0.5);
      EXPECT_EQ(l.vector[1], -2e-3);
    }
  EXPECT_TRUE(found);
  // A denormal stays what it is; only a non-zero value that underflows to 0 is refused
  // (1e-400 read as 0 changed the meaning: 'Mesh->size' 0 is the .geo's own size).
  const Config d = read_deck(write(replace(kFullDeck, traction, "name=\"traction\" type=\"Array(double)\" value=\"{0e-999, 1e-310}\"")));
  for (const auto& l : d.loads)
    if (l.name == "push") {
      EXPECT_EQ(l.vector[0], 0.0);
      EXPECT_EQ(l.vector[1], 1e-310);
    }
}

// A direction must have a positive, finite length: (1e308, 1e308) used to pass the
// "not zero" test and be normalised to (0, 0).
TEST_F(Deck, DirectionsOfZeroOrOverflowingLength) {
  auto plane = [&](const std::string& normal) {
    return replace(kMinimalDeck, "<ParameterList name=\"Bodies\">",
                   "<ParameterList name=\"Contact\"><ParameterList name=\"floor\">"
                   "<Parameter name=\"slave\" type=\"string\" value=\"bottom\"/>"
                   "<Parameter name=\"obstacle\" type=\"string\" value=\"plane\"/>"
                   "<Parameter name=\"point\" type=\"Array(double)\" value=\"{0, 0}\"/>"
                   "<Parameter name=\"normal\" type=\"Array(double)\" value=\"" + normal + "\"/>"
                   "</ParameterList></ParameterList>\n<ParameterList name=\"Bodies\">");
  };
  expect_error(plane("{1e308, 1e308}"), {"'Contact->floor->normal' must be a direction of nonzero, finite length", "overflows"});
  expect_error(plane("{0, 0}"), {"'Contact->floor->normal' must be a direction of nonzero, finite length", "is 0"});
  expect_error(plane("{1e-200, 0}"), {"'Contact->floor->normal'", "is 0"});
  const Config c = read_deck(write(plane("{0, 2}")));
  ASSERT_EQ(c.contact.size(), 1u);
  EXPECT_EQ(c.contact[0].normal[1], 1.0);
}

TEST_F(Deck, DuplicateName) {
  expect_error(replace(kMinimalDeck, "<Parameter name=\"D\" type=\"double\" value=\"2\"/>",
                       "<Parameter name=\"D\" type=\"double\" value=\"2\"/><Parameter name=\"D\" type=\"double\" value=\"3\"/>"),
               {"'Materials->steel->D' is given twice"});
}

TEST_F(Deck, MaterialRanges) {
  expect_error(replace(kMinimalDeck, "name=\"C1\" type=\"double\" value=\"1\"", "name=\"C1\" type=\"double\" value=\"0\""),
               {"'Materials->steel->C1' must be > 0, got 0"});
  expect_error(replace(kMinimalDeck, "name=\"C1\" type=\"double\" value=\"1\"", "name=\"C1\" type=\"double\" value=\"-3\""),
               {"'Materials->steel->C1' must be > 0, got -3"});
  expect_error(replace(kMinimalDeck, "name=\"D\" type=\"double\" value=\"2\"", "name=\"D\" type=\"double\" value=\"-1\""),
               {"'Materials->steel->D' must be > 0, got -1"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"D\"",
                       "<Parameter name=\"C2\" type=\"double\" value=\"-0.5\"/><Parameter name=\"D\""),
               {"'Materials->steel->C2' must be >= 0, got -0.5"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"D\"",
                       "<Parameter name=\"density\" type=\"double\" value=\"-1\"/><Parameter name=\"D\""),
               {"'Materials->steel->density' must be >= 0, got -1"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"D\"",
                       "<Parameter name=\"model\" type=\"string\" value=\"neo-hooke\"/><Parameter name=\"D\""),
               {"'Materials->steel->model' must be one of Ciarlet-Geymonat, Ciarlet-Geymonat plasticity, neo-Hookean, "
                "neo-Hookean plasticity, neo-Hookean damage, Mooney-Rivlin, Holzapfel-Gasser-Ogden; got 'neo-hooke'; did you "
                "mean 'neo-Hookean'?"});
}

// Elastic constants: exactly one of C1 + D (+ C2), E + nu, mu + lambda (material/ElasticConstants.hpp).
TEST_F(Deck, ElasticConstantSets) {
  const std::string cg = "<Parameter name=\"C1\" type=\"double\" value=\"1\"/>\n      <Parameter name=\"D\" type=\"double\" value=\"2\"/>";
  auto p = [](const char* n, const char* v) {
    return std::string("<Parameter name=\"") + n + "\" type=\"double\" value=\"" + v + "\"/>";
  };
  {  // E = 2.6, nu = 0.3: mu = 1, lambda = 1.5; C2 = 0 -> C1 = 0.5, D = 0.375.
    const Config c = read_deck(write(replace(kMinimalDeck, cg, p("E", "2.6") + p("nu", "0.3"))));
    EXPECT_NEAR(c.materials[0].mu, 1.0, 1e-15);
    EXPECT_NEAR(c.materials[0].lambda, 1.5, 1e-15);
    EXPECT_NEAR(c.materials[0].C1, 0.5, 1e-15);
    EXPECT_EQ(c.materials[0].C2, 0.0);
    EXPECT_NEAR(c.materials[0].D, 0.375, 1e-15);
  }
  {  // mu/lambda with a given C2: C1 = mu/2 - C2, D = lambda/4 - C2.
    const Config c = read_deck(write(replace(kMinimalDeck, cg, p("mu", "4") + p("lambda", "8") + p("C2", "0.5"))));
    EXPECT_DOUBLE_EQ(c.materials[0].C1, 1.5);
    EXPECT_DOUBLE_EQ(c.materials[0].C2, 0.5);
    EXPECT_DOUBLE_EQ(c.materials[0].D, 1.5);
  }
  {  // C1/D: mu, lambda reported from the law's small-strain match.
    const Config c = read_deck(write(kMinimalDeck));
    EXPECT_DOUBLE_EQ(c.materials[0].mu, 2.0);
    EXPECT_DOUBLE_EQ(c.materials[0].lambda, 8.0);
  }
  expect_error(replace(kMinimalDeck, cg, p("E", "1")), {"missing required parameter 'Materials->steel->nu'", "'E' and 'nu'"});
  expect_error(replace(kMinimalDeck, cg, p("lambda", "1")), {"missing required parameter 'Materials->steel->mu'"});
  expect_error(replace(kMinimalDeck, cg, p("D", "1")), {"missing required parameter 'Materials->steel->C1'"});
  expect_error(replace(kMinimalDeck, cg, cg + p("E", "1") + p("nu", "0.2")),
               {"'Materials->steel'", "exactly one set", "got both C1/D and E/nu"});
  expect_error(replace(kMinimalDeck, cg, p("E", "1") + p("nu", "0.2") + p("mu", "1") + p("lambda", "1")),
               {"got both E/nu and mu/lambda"});
  expect_error(replace(kMinimalDeck, cg, p("C2", "1")), {"'Materials->steel' needs one set of elastic constants", "E + nu"});
  expect_error(replace(kMinimalDeck, cg, p("E", "1") + p("nu", "0")), {"D = lambda/4 - C2 = 0", "needs D > 0"});
  expect_error(replace(kMinimalDeck, cg, p("E", "1") + p("nu", "0.5")), {"'Materials->steel->nu' must be in [0, 0.5), got 0.5"});
  expect_error(replace(kMinimalDeck, cg, p("mu", "1") + p("lambda", "4") + p("C2", "0.5")), {"C1 = mu/2 - C2 = 0", "needs C1 > 0"});
  // neo-Hookean and Mooney-Rivlin: E/nu or mu/lambda only; Mooney-Rivlin splits mu with C2.
  auto model = [&](const char* m) { return std::string("<Parameter name=\"model\" type=\"string\" value=\"") + m + "\"/>"; };
  {
    const Config c = read_deck(write(replace(kMinimalDeck, cg, model("Mooney-Rivlin") + p("mu", "4") + p("lambda", "8") + p("C2", "0.5"))));
    EXPECT_EQ(c.materials[0].model, "Mooney-Rivlin");
    EXPECT_DOUBLE_EQ(c.materials[0].C1, 1.5);
    EXPECT_DOUBLE_EQ(c.materials[0].C2, 0.5);
    EXPECT_DOUBLE_EQ(c.materials[0].lambda, 8.0);
    const Config n = read_deck(write(replace(kMinimalDeck, cg, model("neo-hookean") + p("E", "2.6") + p("nu", "0.3"))));
    EXPECT_EQ(n.materials[0].model, "neo-Hookean");
    EXPECT_NEAR(n.materials[0].mu, 1.0, 1e-15);
  }
  expect_error(replace(kMinimalDeck, cg, model("neo-Hookean") + cg),
               {"'Materials->steel->C1' is a Ciarlet-Geymonat parameter", "neo-Hookean takes E + nu or mu + lambda"});
  expect_error(replace(kMinimalDeck, cg, model("neo-Hookean") + p("E", "1") + p("nu", "0.3") + p("C2", "0.1")),
               {"'Materials->steel->C2' needs 'model' = Ciarlet-Geymonat or Mooney-Rivlin"});
  expect_error(replace(kMinimalDeck, cg, model("neo-Hookean")), {"'Materials->steel' needs one set", "E + nu or mu + lambda"});
  expect_error(replace(kMinimalDeck, cg, model("Mooney-Rivlin") + p("mu", "4") + p("lambda", "1") + p("C2", "0.5")),
               {"lambda - 4 C2 = -1", "Mooney-Rivlin needs it >= 0"});
  // Holzapfel-Gasser-Ogden: k1, k2, fibre angle required; the frame defaults to the z axis through the origin.
  const std::string hgo = model("Holzapfel-Gasser-Ogden") + p("mu", "3") + p("lambda", "300");
  {
    const Config c = read_deck(write(replace(kMinimalDeck, cg, hgo + p("k1", "2.4") + p("k2", "0.8") + p("fibre angle", "29") +
                                                                 "<Parameter name=\"axis\" type=\"Array(double)\" value=\"{0, 2, 0}\"/>")));
    EXPECT_EQ(c.materials[0].k1, 2.4);
    EXPECT_EQ(c.materials[0].k2, 0.8);
    EXPECT_EQ(c.materials[0].fibre_angle, 29.0);
    EXPECT_EQ(c.materials[0].axis[1], 1.0);  // normalised
    EXPECT_EQ(c.materials[0].axis_point[0], 0.0);
  }
  expect_error(replace(kMinimalDeck, cg, hgo + p("k1", "2.4") + p("fibre angle", "29")),
               {"missing required parameter 'Materials->steel->k2' (double, > 0) for model = Holzapfel-Gasser-Ogden"});
  expect_error(replace(kMinimalDeck, cg, hgo + p("k1", "2.4") + p("k2", "1") + p("fibre angle", "100")),
               {"'Materials->steel->fibre angle' must be in [0, 90], got 100"});
  expect_error(replace(kMinimalDeck, cg, cg + p("k1", "2.4")), {"'Materials->steel->k1' needs 'model' = Holzapfel-Gasser-Ogden"});
  // 'e' (lower case) is not a parameter; the suggestion is E, no longer D.
  const std::string msg = expect_error(replace(kMinimalDeck, cg, p("e", "1") + p("nu", "0.3")),
                                       {"unknown parameter 'Materials->steel->e'", "did you mean 'E'"});
  EXPECT_EQ(msg.find("did you mean 'D'"), std::string::npos) << msg;
}

TEST_F(Deck, PlasticityParameters) {
  const std::string d = "<Parameter name=\"D\"";
  const std::string plastic = "<Parameter name=\"model\" type=\"string\" value=\"Ciarlet-Geymonat plasticity\"/>";
  const std::string Y = "<Parameter name=\"yield stress\" type=\"double\" value=\"0.5\"/>";
  const std::string H = "<Parameter name=\"hardening\" type=\"double\" value=\"2\"/>";
  const Config c = read_deck(write(replace(kMinimalDeck, d, plastic + Y + H + d)));
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_TRUE(c.materials[0].plastic());
  EXPECT_EQ(c.materials[0].yield_stress, 0.5);
  EXPECT_EQ(c.materials[0].hardening, 2.0);
  expect_error(replace(kMinimalDeck, d, plastic + d),
               {"missing required parameter 'Materials->steel->yield stress'", "Ciarlet-Geymonat plasticity"});
  expect_error(replace(kMinimalDeck, d, plastic + "<Parameter name=\"yield stress\" type=\"double\" value=\"0\"/>" + d),
               {"'Materials->steel->yield stress' must be > 0, got 0"});
  expect_error(replace(kMinimalDeck, d, plastic + Y + "<Parameter name=\"hardening\" type=\"double\" value=\"-1\"/>" + d),
               {"'Materials->steel->hardening' must be >= 0, got -1"});
  expect_error(replace(kMinimalDeck, d, Y + d), {"'Materials->steel->yield stress' needs 'model' = Ciarlet-Geymonat plasticity"});
  // The dynamic step: the incremental potential by default, `mean value` or `lagged` on request.
  EXPECT_EQ(c.materials[0].plastic_dynamic_step, "incremental potential");
  const std::string step = "<Parameter name=\"plastic dynamic step\" type=\"string\" value=\"";
  for (const char* v : {"incremental potential", "mean value", "lagged"})
    EXPECT_EQ(read_deck(write(replace(kMinimalDeck, d, plastic + Y + step + v + "\"/>" + d))).materials[0].plastic_dynamic_step,
              v);
  expect_error(replace(kMinimalDeck, d, plastic + Y + step + "frozen\"/>" + d),
               {"'Materials->steel->plastic dynamic step' must be one of"});
  expect_error(replace(kMinimalDeck, d, step + "lagged\"/>" + d),
               {"'Materials->steel->plastic dynamic step' needs 'model' = Ciarlet-Geymonat plasticity"});
  const std::string dyn = "<ParameterList name=\"Problem\"><Parameter name=\"analysis\" type=\"string\" value=\"dynamic\"/>"
                          "</ParameterList><ParameterList name=\"Time Integration\"><Parameter name=\"scheme\" "
                          "type=\"string\" value=\"midpoint\"/></ParameterList><ParameterList name=\"Mesh\">";
  const std::string rho = "<Parameter name=\"density\" type=\"double\" value=\"1\"/>";
  expect_error(replace(replace(kMinimalDeck, d, plastic + Y + rho + d), "<ParameterList name=\"Mesh\">", dyn),
               {"plasticity needs 'Time Integration->scheme' = gonzalez"});
}

namespace {
// kMinimalDeck with the material's C1/D replaced by `params` and, when `dynamic`, a
// dynamic analysis with `scheme` (density 1).
std::string material_deck(const std::string& params, bool dynamic = false, const std::string& scheme = "gonzalez") {
  const std::string cg = "<Parameter name=\"C1\" type=\"double\" value=\"1\"/>\n      <Parameter name=\"D\" type=\"double\" value=\"2\"/>";
  std::string deck = replace(kMinimalDeck, cg, params + (dynamic ? "<Parameter name=\"density\" type=\"double\" value=\"1\"/>" : ""));
  if (dynamic)
    deck = replace(deck, "<ParameterList name=\"Mesh\">",
                   "<ParameterList name=\"Problem\"><Parameter name=\"analysis\" type=\"string\" value=\"dynamic\"/></ParameterList>"
                   "<ParameterList name=\"Time Integration\"><Parameter name=\"scheme\" type=\"string\" value=\"" + scheme +
                       "\"/></ParameterList><ParameterList name=\"Mesh\">");
  return deck;
}
std::string dparam(const char* n, const char* v) { return std::string("<Parameter name=\"") + n + "\" type=\"double\" value=\"" + v + "\"/>"; }
std::string model_param(const char* m) { return std::string("<Parameter name=\"model\" type=\"string\" value=\"") + m + "\"/>"; }
}  // namespace

// neo-Hookean plasticity: the neo-Hookean constants (E + nu or mu + lambda) and the
// plasticity's yield stress and hardening, with the rules of Ciarlet-Geymonat plasticity.
TEST_F(Deck, NeoHookeanPlasticityParameters) {
  const std::string nh = model_param("neo-hookean Plasticity") + dparam("E", "2.6") + dparam("nu", "0.3");
  const Config c = read_deck(write(material_deck(nh + dparam("yield stress", "0.01") + dparam("hardening", "0.1"))));
  const MaterialConfig& m = c.materials[0];
  EXPECT_EQ(m.model, "neo-Hookean plasticity");
  EXPECT_TRUE(m.plastic());
  EXPECT_TRUE(m.has_history());
  EXPECT_FALSE(m.damage());
  EXPECT_FALSE(m.ciarlet_geymonat());
  EXPECT_NEAR(m.mu, 1.0, 1e-15);
  EXPECT_NEAR(m.lambda, 1.5, 1e-15);
  EXPECT_EQ(m.yield_stress, 0.01);
  EXPECT_EQ(m.hardening, 0.1);
  // The plastic fields are in the default output set, the damage ones are not there.
  EXPECT_TRUE(c.output.wants("equivalent_plastic_strain"));
  EXPECT_FALSE(c.output.wants("damage"));
  const Config g = read_deck(write(material_deck(nh + dparam("yield stress", "1"), true)));
  EXPECT_EQ(g.materials[0].hardening, 0.0);
  expect_error(material_deck(nh), {"missing required parameter 'Materials->steel->yield stress' (double, > 0) for model = "
                                   "neo-Hookean plasticity"});
  expect_error(material_deck(nh + dparam("yield stress", "0")), {"'Materials->steel->yield stress' must be > 0, got 0"});
  expect_error(material_deck(nh + dparam("yield stress", "1") + dparam("hardening", "-1")),
               {"'Materials->steel->hardening' must be >= 0, got -1"});
  expect_error(material_deck(model_param("neo-Hookean plasticity") + dparam("C1", "1") + dparam("D", "2") + dparam("yield stress", "1")),
               {"'Materials->steel->C1' is a Ciarlet-Geymonat parameter", "neo-Hookean plasticity takes E + nu or mu + lambda"});
  expect_error(material_deck(nh + dparam("C2", "0.1") + dparam("yield stress", "1")),
               {"'Materials->steel->C2' needs 'model' = Ciarlet-Geymonat or Mooney-Rivlin"});
  expect_error(material_deck(nh + dparam("yield stress", "1") + dparam("saturation damage", "0.5")),
               {"'Materials->steel->saturation damage' needs 'model' = neo-Hookean damage"});
  expect_error(material_deck(nh + dparam("yield stress", "1"), true, "midpoint"),
               {"'Materials->steel->model' = neo-Hookean plasticity needs 'Time Integration->scheme' = gonzalez", "not midpoint"});
  expect_error(material_deck(model_param("neo-Hookean") + dparam("E", "1") + dparam("nu", "0.3") + dparam("hardening", "1")),
               {"'Materials->steel->hardening' needs 'model' = Ciarlet-Geymonat plasticity or neo-Hookean plasticity"});
}

// The hardening laws of the plasticity models (material/IsotropicHardening.hpp): linear (the
// default), Voce (saturation stress >= yield stress, saturation rate > 0, both required) and a
// table (2 to 32 strains from 0, strictly increasing, as many non-decreasing stresses; the first
// stress is the yield stress, so `yield stress` and `hardening` are refused with it).
TEST_F(Deck, HardeningLawParameters) {
  const auto aparam = [](const char* n, const std::string& v) {
    return std::string("<Parameter name=\"") + n + "\" type=\"Array(double)\" value=\"{" + v + "}\"/>";
  };
  const auto sparam = [](const char* n, const char* v) {
    return std::string("<Parameter name=\"") + n + "\" type=\"string\" value=\"" + v + "\"/>";
  };
  const std::string cg = model_param("Ciarlet-Geymonat plasticity") + dparam("C1", "1") + dparam("D", "2");
  const std::string nh = model_param("neo-Hookean plasticity") + dparam("E", "2.6") + dparam("nu", "0.3");
  const std::string y = dparam("yield stress", "0.2");
  EXPECT_EQ(read_deck(write(material_deck(cg + y))).materials[0].hardening_law, "linear");
  const Config v = read_deck(write(material_deck(cg + y + sparam("hardening law", "voce") + dparam("hardening", "0.1") +
                                                 dparam("saturation stress", "0.5") + dparam("saturation rate", "12"))));
  EXPECT_EQ(v.materials[0].hardening_law, "Voce");
  EXPECT_EQ(v.materials[0].yield_stress, 0.2);
  EXPECT_EQ(v.materials[0].hardening, 0.1);
  EXPECT_EQ(v.materials[0].saturation_stress, 0.5);
  EXPECT_EQ(v.materials[0].saturation_rate, 12.0);
  const std::string tab = sparam("hardening law", "table");
  const Config t = read_deck(write(material_deck(nh + tab + aparam("hardening table strains", "0, 0.1, 0.3") +
                                                 aparam("hardening table stresses", "0.2, 0.3, 0.3"), true)));
  EXPECT_EQ(t.materials[0].hardening_law, "table");
  EXPECT_EQ(t.materials[0].yield_stress, 0.2);
  EXPECT_EQ(t.materials[0].hardening, 0.0);
  EXPECT_EQ(t.materials[0].table_strains, (std::vector<double>{0.0, 0.1, 0.3}));
  EXPECT_EQ(t.materials[0].table_stresses, (std::vector<double>{0.2, 0.3, 0.3}));
  const std::string voce = sparam("hardening law", "Voce");
  expect_error(material_deck(cg + y + voce + dparam("saturation rate", "1")),
               {"missing required parameter 'Materials->steel->saturation stress' (> 0) for 'hardening law' = Voce"});
  expect_error(material_deck(cg + y + voce + dparam("saturation stress", "1")),
               {"missing required parameter 'Materials->steel->saturation rate' (> 0) for 'hardening law' = Voce"});
  expect_error(material_deck(cg + y + voce + dparam("saturation stress", "0.1") + dparam("saturation rate", "1")),
               {"'Materials->steel->saturation stress' = 0.1 is below 'Materials->steel->yield stress' = 0.2",
                "softening is not supported"});
  expect_error(material_deck(cg + y + voce + dparam("saturation stress", "1") + dparam("saturation rate", "0")),
               {"'Materials->steel->saturation rate' must be > 0, got 0"});
  expect_error(material_deck(cg + y + dparam("saturation stress", "1")),
               {"'Materials->steel->saturation stress' needs 'hardening law' = Voce, got linear"});
  expect_error(material_deck(cg + y + aparam("hardening table strains", "0, 1")),
               {"'Materials->steel->hardening table strains' needs 'hardening law' = table, got linear"});
  expect_error(material_deck(cg + sparam("hardening law", "Swift") + y), {"'Materials->steel->hardening law'", "Swift"});
  const std::string strains = aparam("hardening table strains", "0, 0.1, 0.3");
  const std::string stresses = aparam("hardening table stresses", "0.2, 0.3, 0.35");
  expect_error(material_deck(cg + tab + strains),
               {"missing required parameter 'Materials->steel->hardening table stresses'", "for 'hardening law' = table"});
  expect_error(material_deck(cg + tab + y + strains + stresses),
               {"'Materials->steel->yield stress' is not allowed with 'hardening law' = table",
                "'Materials->steel->hardening table stresses' is the initial yield stress"});
  expect_error(material_deck(cg + tab + dparam("hardening", "1") + strains + stresses),
               {"'Materials->steel->hardening' needs 'hardening law' = linear or Voce, got table"});
  expect_error(material_deck(cg + tab + strains + aparam("hardening table stresses", "0.2, 0.3")),
               {"'Materials->steel->hardening table stresses' has 2 values and 'Materials->steel->hardening table strains' 3"});
  expect_error(material_deck(cg + tab + aparam("hardening table strains", "0.01, 0.1, 0.3") + stresses),
               {"'Materials->steel->hardening table strains' must start at 0, got 0.01"});
  expect_error(material_deck(cg + tab + aparam("hardening table strains", "0, 0.1, 0.1") + stresses),
               {"'Materials->steel->hardening table strains' must be strictly increasing, got 0.1 after 0.1"});
  expect_error(material_deck(cg + tab + strains + aparam("hardening table stresses", "0.2, 0.3, 0.25")),
               {"'Materials->steel->hardening table stresses' must be non-decreasing (softening is not supported), got "
                "0.25 after 0.3 at strain 0.3"});
  std::string many_e = "0", many_s = "1";
  for (int i = 1; i <= 32; ++i) many_e += ", " + std::to_string(i), many_s += ", 1";
  expect_error(material_deck(cg + tab + aparam("hardening table strains", many_e) + aparam("hardening table stresses", many_s)),
               {"'Materials->steel->hardening table strains'", "33"});
  expect_error(material_deck(model_param("neo-Hookean") + dparam("E", "1") + dparam("nu", "0.3") + voce),
               {"'Materials->steel->hardening law' needs 'model' = Ciarlet-Geymonat plasticity or neo-Hookean plasticity"});
}

// neo-Hookean damage (material/Damage.hpp): saturation damage d_inf in [0, 1) and damage
// energy scale beta > 0, both required; refused with the midpoint scheme (as plasticity).
TEST_F(Deck, NeoHookeanDamageParameters) {
  const std::string nh = model_param("neo-Hookean damage") + dparam("mu", "1") + dparam("lambda", "2");
  const std::string both = nh + dparam("saturation damage", "0.6") + dparam("damage energy scale", "0.05");
  const Config c = read_deck(write(material_deck(both)));
  const MaterialConfig& m = c.materials[0];
  EXPECT_EQ(m.model, "neo-Hookean damage");
  EXPECT_TRUE(m.damage());
  EXPECT_TRUE(m.has_history());
  EXPECT_FALSE(m.plastic());
  EXPECT_EQ(m.mu, 1.0);
  EXPECT_EQ(m.lambda, 2.0);
  EXPECT_EQ(m.saturation_damage, 0.6);
  EXPECT_EQ(m.damage_energy_scale, 0.05);
  EXPECT_TRUE(c.output.wants("damage"));
  EXPECT_TRUE(c.output.wants("max_virgin_energy"));
  EXPECT_TRUE(c.output.wants("damage_dissipation"));
  EXPECT_FALSE(c.output.wants("equivalent_plastic_strain"));
  EXPECT_EQ(read_deck(write(material_deck(nh + dparam("saturation damage", "0") + dparam("damage energy scale", "1"))))
                .materials[0].saturation_damage, 0.0);
  EXPECT_EQ(read_deck(write(material_deck(both, true, "newmark"))).time.scheme, "newmark");
  expect_error(material_deck(nh + dparam("damage energy scale", "1")),
               {"missing required parameter 'Materials->steel->saturation damage' (double, in [0, 1)) for model = neo-Hookean damage"});
  expect_error(material_deck(nh + dparam("saturation damage", "0.5")),
               {"missing required parameter 'Materials->steel->damage energy scale' (double, > 0) for model = neo-Hookean damage"});
  expect_error(material_deck(nh + dparam("saturation damage", "1") + dparam("damage energy scale", "1")),
               {"'Materials->steel->saturation damage' must be in [0, 1), got 1"});
  expect_error(material_deck(nh + dparam("saturation damage", "-0.1") + dparam("damage energy scale", "1")),
               {"'Materials->steel->saturation damage' must be in [0, 1), got -0.1"});
  expect_error(material_deck(nh + dparam("saturation damage", "0.5") + dparam("damage energy scale", "0")),
               {"'Materials->steel->damage energy scale' must be > 0, got 0"});
  expect_error(material_deck(both + dparam("yield stress", "1")),
               {"'Materials->steel->yield stress' needs 'model' = Ciarlet-Geymonat plasticity or neo-Hookean plasticity"});
  expect_error(material_deck(model_param("neo-Hookean damage") + dparam("C1", "1") + dparam("D", "2")),
               {"'Materials->steel->C1' is a Ciarlet-Geymonat parameter", "neo-Hookean damage takes E + nu or mu + lambda"});
  expect_error(material_deck(model_param("neo-Hookean") + dparam("mu", "1") + dparam("lambda", "2") + dparam("damage energy scale", "1")),
               {"'Materials->steel->damage energy scale' needs 'model' = neo-Hookean damage"});
  expect_error(material_deck(both, true, "midpoint"),
               {"'Materials->steel->model' = neo-Hookean damage needs 'Time Integration->scheme' = gonzalez", "not midpoint"});
  // The history fields of a law the deck does not have are refused by name.
  expect_error(replace(material_deck(model_param("neo-Hookean") + dparam("mu", "1") + dparam("lambda", "2")),
                       "  <ParameterList name=\"Bodies\">",
                       "  <ParameterList name=\"Output\"><Parameter name=\"field list\" type=\"string\" value=\"damage\"/>"
                       "</ParameterList>\n  <ParameterList name=\"Bodies\">"),
               {"'Output->field list'", "'damage' needs a body of model 'neo-Hookean damage'"});
  expect_error(replace(material_deck(both), "  <ParameterList name=\"Bodies\">",
                       "  <ParameterList name=\"Output\"><Parameter name=\"field list\" type=\"string\" value=\"yielding\"/>"
                       "</ParameterList>\n  <ParameterList name=\"Bodies\">"),
               {"'Output->field list'", "'yielding' needs a body of model 'Ciarlet-Geymonat plasticity' or 'neo-Hookean plasticity'"});
}

// docs/deck.md's example of the two models (a plastic strut, one with a hardening table, a
// damaging intima) reads.
TEST_F(Deck, DocsInelasticMaterialExampleParses) {
  std::ifstream f(std::string(STENTOR_SOURCE_DIR) + "/docs/deck.md");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string md = ss.str();
  const auto b = md.find("<ParameterList name=\"strut\">");
  ASSERT_NE(b, std::string::npos);
  const std::string example = md.substr(b, md.find("```", b) - b);
  const std::string steel = kMinimalDeck;
  const auto m0 = steel.find("    <ParameterList name=\"steel\">"), m1 = steel.find("  </ParameterList>\n  <ParameterList name=\"Bodies\">");
  const Config c = read_deck(write(replace(steel.substr(0, m0) + example + steel.substr(m1), "value=\"steel\"", "value=\"strut\"")));
  ASSERT_EQ(c.materials.size(), 3u);
  EXPECT_EQ(c.materials[0].model, "neo-Hookean plasticity");
  EXPECT_EQ(c.materials[0].yield_stress, 300.0);
  EXPECT_EQ(c.materials[1].hardening_law, "table");
  EXPECT_EQ(c.materials[1].yield_stress, 500.0);
  EXPECT_EQ(c.materials[1].table_stresses.size(), 4u);
  EXPECT_EQ(c.materials[2].model, "neo-Hookean damage");
  EXPECT_EQ(c.materials[2].damage_energy_scale, 0.02);
}

TEST_F(Deck, OtherRangesAndChoices) {
  const std::string newton = "<ParameterList name=\"Bodies\">";
  expect_error(replace(kMinimalDeck, newton,
                       "<ParameterList name=\"Stepping\"><Parameter name=\"end time\" type=\"double\" value=\"0\"/>"
                       "</ParameterList>\n" + newton),
               {"'Stepping->end time' must be > 0, got 0"});
  expect_error(replace(kMinimalDeck, newton,
                       "<ParameterList name=\"Stepping\"><Parameter name=\"target iterations\" type=\"int\" value=\"2\"/>"
                       "</ParameterList>\n" + newton),
               {"'Stepping->target iterations' = 2: must be 0 (off) or at least 4"});
  expect_error(replace(kMinimalDeck, newton,
                       "<ParameterList name=\"Linear Solver\"><Parameter name=\"method\" type=\"string\" value=\"gmrs\"/>"
                       "</ParameterList>\n" + newton),
               {"'Linear Solver->method' must be one of gmres, direct; got 'gmrs'; did you mean 'gmres'?"});
  expect_error(replace(kMinimalDeck, newton,
                       "<ParameterList name=\"Linear Solver\"><Parameter name=\"Belos\" type=\"int\" value=\"1\"/>"
                       "</ParameterList>\n" + newton),
               {"'Linear Solver->Belos' must be a sublist"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"file\"",
                       "<Parameter name=\"order\" type=\"int\" value=\"3\"/><Parameter name=\"file\""),
               {"'Mesh->order' must be one of 1, 2; got 3"});
}

// Problem->units: a label for plots only, default SI, case-insensitive like every choice.
TEST_F(Deck, UnitSystem) {
  EXPECT_EQ(read_deck(write(kMinimalDeck)).problem.units, "SI");
  const std::string problem = "<ParameterList name=\"Problem\"><Parameter name=\"units\" type=\"string\" value=\"";
  const std::string mesh = "<ParameterList name=\"Mesh\">";
  const Config c = read_deck(write(replace(kMinimalDeck, mesh, problem + "mm-n-s\"/></ParameterList>\n" + mesh)));
  EXPECT_EQ(c.problem.units, "mm-N-s");
  expect_error(replace(kMinimalDeck, mesh, problem + "mks\"/></ParameterList>\n" + mesh),
               {"'Problem->units' must be one of SI, mm-N-s, mm-g-ms, none; got 'mks'"});
}

TEST_F(Deck, MissingMeshFile) {
  expect_error(replace(kMinimalDeck, "mesh/ring.msh", "mesh/tube.msh"),
               {"'Mesh->file'", (dir / "mesh" / "tube.msh").string(), "does not exist"});
  expect_error(replace(kMinimalDeck, "mesh/ring.msh", "mesh/ring.stl"), {"'Mesh->file' must be a gmsh .msh or .geo file"});
}

TEST_F(Deck, UndefinedMaterial) {
  expect_error(replace(kFullDeck, "value=\"artery\"/>\n    </ParameterList>\n  </ParameterList>\n  <ParameterList name=\"Boundary",
                       "value=\"arterie\"/>\n    </ParameterList>\n  </ParameterList>\n  <ParameterList name=\"Boundary"),
               {"'Bodies->vessel->material' names undefined material 'arterie'", "defined materials: steel, artery",
                "did you mean 'artery'?"});
}

TEST_F(Deck, BadComponents) {
  expect_error(replace(kFullDeck, "value=\"y, x\"", "value=\"x w\""),
               {"'Boundary Conditions->pull->components' must list components x, y, z", "'x w'"});
  expect_error(replace(kFullDeck, "value=\"y, x\"", "value=\"x, x\""),
               {"'Boundary Conditions->pull->components' lists 'x' twice"});
  expect_error(replace(kFullDeck, "value=\"y, x\"", "value=\"x z\""),
               {"'Boundary Conditions->pull->components': 'z' is not a component of a 2D problem"});
  expect_error(replace(kFullDeck, "value=\"{0.1, -0.2}\"", "value=\"{0.1}\""),
               {"'Boundary Conditions->pull->values' must have one value per listed component (2"});
}

TEST_F(Deck, TableRamp) {
  expect_error(replace(kFullDeck, "value=\"{0, 1, 0.5}\"", "value=\"{0, 1}\""),
               {"'Boundary Conditions->pull->ramp factors' must have as many values as 'ramp times' (3), got 2"});
  expect_error(replace(kFullDeck, "value=\"{0, 0.5, 1}\"", "value=\"{0, 0.5, 0.5}\""),
               {"'Boundary Conditions->pull->ramp times' must be strictly increasing", "0.5 then 0.5"});
  expect_error(replace(kFullDeck, "value=\"{0, 0.5, 1}\"", "value=\"{0}\""),
               {"'Boundary Conditions->pull->ramp times' must have at least 2 values, got 1"});
  expect_error(replace(kFullDeck, "<Parameter name=\"ramp times\" type=\"Array(double)\" value=\"{0, 0.5, 1}\"/>", ""),
               {"missing required parameter 'Boundary Conditions->pull->ramp times'"});
  expect_error(replace(kFullDeck, "value=\"table\"", "value=\"linear\""),
               {"'Boundary Conditions->pull->ramp times' is only used with \"ramp\" = table"});
}

// Vector lengths against the mesh's dimension (issue 12: a 2-value initial velocity in a
// 3D deck ran as (vx, vy, 0)). Without Mesh->dimension the deck alone cannot tell, so it
// records every dimension-dependent vector it read; check_vector_dimensions checks them
// once the mesh is read (Model, so a run and --check alike), naming the first mismatch
// with the expected and the given number of values.
TEST_F(Deck, VectorLengthsCheckedAgainstTheMeshDimension) {
  std::string full = replace(kMinimalDeck, "<Parameter name=\"material\" type=\"string\" value=\"steel\"/>",
                             R"XML(<Parameter name="material" type="string" value="steel"/>
      <Parameter name="initial velocity" type="Array(double)" value="{5, 6, 7}"/>)XML");
  full = replace(full, "<Parameter name=\"D\" type=\"double\" value=\"2\"/>",
                 "<Parameter name=\"D\" type=\"double\" value=\"2\"/><Parameter name=\"density\" type=\"double\" value=\"1\"/>");
  full = full.substr(0, full.rfind("</ParameterList>")) + R"XML(  <ParameterList name="Problem">
    <Parameter name="analysis" type="string" value="dynamic"/>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="clamp">
      <Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="base"/>
      <Parameter name="values" type="Array(double)" value="{0, 0, 1}"/>
    </ParameterList>
    <ParameterList name="push">
      <Parameter name="type" type="string" value="traction"/>
      <Parameter name="boundary" type="string" value="right"/>
      <Parameter name="traction" type="Array(double)" value="{1, 0, 0}"/>
    </ParameterList>
    <ParameterList name="gravity">
      <Parameter name="type" type="string" value="body force"/>
      <Parameter name="force" type="Array(double)" value="{0, 0, -1}"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Initial Conditions">
    <Parameter name="displacement" type="Array(double)" value="{0, 0, 0}"/>
    <Parameter name="velocity" type="Array(double)" value="{0, 0, 2}"/>
    <Parameter name="angular velocity" type="Array(double)" value="{0, 0, 3}"/>
    <Parameter name="center" type="Array(double)" value="{0, 0, 0}"/>
  </ParameterList>
  <ParameterList name="Contact">
    <ParameterList name="floor">
      <Parameter name="slave" type="string" value="bottom"/>
      <Parameter name="obstacle" type="string" value="plane"/>
      <Parameter name="point" type="Array(double)" value="{0, 0, -5}"/>
      <Parameter name="normal" type="Array(double)" value="{0, 1, 1}"/>
      <Parameter name="translation" type="Array(double)" value="{0, 0, 4}"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Output">
    <ParameterList name="Probes">
      <ParameterList name="tip">
        <Parameter name="point" type="Array(double)" value="{1, 2, 3}"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
)XML";
  const Config c = read_deck(write(full));
  std::vector<std::string> paths;
  for (const auto& v : c.dim_vectors) paths.push_back(v.path);
  EXPECT_EQ(paths, (std::vector<std::string>{
                       "Bodies->stent->initial velocity", "Boundary Conditions->clamp->values", "Boundary Conditions->push->traction",
                       "Boundary Conditions->gravity->force", "Initial Conditions->displacement", "Initial Conditions->velocity",
                       "Initial Conditions->angular velocity", "Initial Conditions->center", "Output->Probes->tip->point",
                       "Contact->floor->point", "Contact->floor->normal", "Contact->floor->translation"}));
  EXPECT_NO_THROW(check_vector_dimensions(c, 3));
  auto expect_mismatch = [](const Config& cfg, int dim, const std::string& needle) {
    try {
      check_vector_dimensions(cfg, dim);
      ADD_FAILURE() << "accepted in " << dim << "D; expected: " << needle;
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(cfg.deck_path + ": ", 0), 0u) << msg;
      EXPECT_NE(msg.find(needle), std::string::npos) << msg;
    }
  };
  // In 2D the first vector is named (2D takes 2 values, 1 angular velocity).
  expect_mismatch(c, 2, "'Bodies->stent->initial velocity' must have 2 values (the mesh is 2D), got 3");
  // One short vector in a deck whose mesh is 3D, each kind in turn (the issue's case first).
  for (const auto& [from, to, needle] : std::vector<std::array<std::string, 3>>{
           {"{5, 6, 7}", "{5, 6}", "'Bodies->stent->initial velocity' must have 3 values (the mesh is 3D), got 2"},
           {"{0, 0, 1}\"/>\n    </ParameterList>\n    <ParameterList name=\"push\"", "{0, 1}\"/>\n    </ParameterList>\n    <ParameterList name=\"push\"",
            "'Boundary Conditions->clamp->values' must have 3 values (the mesh is 3D), got 2"},
           {"{1, 0, 0}", "{1, 0}", "'Boundary Conditions->push->traction' must have 3 values (the mesh is 3D), got 2"},
           {"{0, 0, -1}", "{0, -1}", "'Boundary Conditions->gravity->force' must have 3 values (the mesh is 3D), got 2"},
           {"{0, 0, 2}", "{0, 2}", "'Initial Conditions->velocity' must have 3 values (the mesh is 3D), got 2"},
           {"{0, 0, 3}", "{3}", "'Initial Conditions->angular velocity' must have 3 values (the mesh is 3D), got 1"},
           {"{0, 0, -5}\"/>\n      <Parameter name=\"normal\" type=\"Array(double)\" value=\"{0, 1, 1}\"/>\n      "
            "<Parameter name=\"translation\" type=\"Array(double)\" value=\"{0, 0, 4}",
            "{0, -5}\"/>\n      <Parameter name=\"normal\" type=\"Array(double)\" value=\"{1, 1}\"/>\n      "
            "<Parameter name=\"translation\" type=\"Array(double)\" value=\"{0, 4}",
            "'Contact->floor->point' must have 3 values (the mesh is 3D), got 2"},
           {"{1, 2, 3}", "{1, 2}", "'Output->Probes->tip->point' must have 3 values (the mesh is 3D), got 2"}})
    expect_mismatch(read_deck(write(replace(full, from, to), "short.xml")), 3, needle);
  // With Mesh->dimension the deck reader checks at once (same rule, its own wording).
  expect_error(replace(full, "value=\"mesh/ring.msh\"/>", "value=\"mesh/ring.msh\"/><Parameter name=\"dimension\" type=\"int\" value=\"2\"/>"),
               {"'Bodies->stent->initial velocity' must have 2 values ('Mesh->dimension' = 2), got 3"});
}

TEST_F(Deck, LoadTypes) {
  expect_error(replace(kFullDeck, "value=\"traction\"", "value=\"tracton\""),
               {"'Boundary Conditions->push->type' must be one of Dirichlet, traction, pressure, body force",
                "did you mean 'traction'?"});
  expect_error(replace(kFullDeck, "<Parameter name=\"pressure\" type=\"double\"", "<Parameter name=\"traction\" type=\"double\""),
               {"unknown parameter 'Boundary Conditions->blow->traction' for a load of type 'pressure'"});
  expect_error(replace(kFullDeck, "value=\"{1e3, 0}\"", "value=\"{1e3, 0, 0}\""),
               {"'Boundary Conditions->push->traction' must have 2 values ('Mesh->dimension' = 2), got 3"});
  expect_error(replace(kFullDeck, "<Parameter name=\"body\" type=\"string\" value=\"stent\"/>",
                       "<Parameter name=\"body\" type=\"string\" value=\"stnt\"/>"),
               {"'Boundary Conditions->gravity->body' names undefined body 'stnt'", "did you mean 'stent'?"});
}

TEST_F(Deck, MissingRequired) {
  expect_error(replace(kMinimalDeck, "<Parameter name=\"C1\" type=\"double\" value=\"1\"/>", ""),
               {"missing required parameter 'Materials->steel->C1' (double, > 0)"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"file\" type=\"string\" value=\"mesh/ring.msh\"/>", ""),
               {"missing required parameter 'Mesh->file'"});
  expect_error(replace(kMinimalDeck, "<Parameter name=\"material\" type=\"string\" value=\"steel\"/>", ""),
               {"missing required parameter 'Bodies->stent->material'"});
  expect_error(replace(kFullDeck, "<Parameter name=\"boundary\" type=\"string\" value=\"inner\"/>", ""),
               {"missing required parameter 'Boundary Conditions->blow->boundary'"});
  expect_error(replace(kFullDeck, "<Parameter name=\"type\" type=\"string\" value=\"Pressure\"/>", ""),
               {"missing required parameter 'Boundary Conditions->blow->type'"});
  std::string no_mesh = kMinimalDeck;
  no_mesh = replace(no_mesh, "<ParameterList name=\"Mesh\">\n    <Parameter name=\"file\" type=\"string\" value=\"mesh/ring.msh\"/>\n  </ParameterList>", "");
  expect_error(no_mesh, {"missing required sublist 'Mesh'"});
  expect_error(replace(kMinimalDeck, "<ParameterList name=\"stent\">\n      <Parameter name=\"material\" type=\"string\" value=\"steel\"/>\n    </ParameterList>", ""),
               {"'Bodies' defines no body"});
}

// ---------------------------------------------------------------------------
// Ramps.

TEST(Ramp, LinearAndConstant) {
  Ramp r;
  EXPECT_DOUBLE_EQ(r(0.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(r(0.5, 2.0), 0.25);
  EXPECT_DOUBLE_EQ(r(2.0, 2.0), 1.0);
  r.kind = Ramp::Kind::Constant;
  EXPECT_DOUBLE_EQ(r(0.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(r(1.3, 2.0), 1.0);
}

TEST(Ramp, TableInterpolatesAndClamps) {
  Ramp r;
  r.kind = Ramp::Kind::Table;
  r.times = {0.5, 1.0, 2.0};
  r.factors = {1.0, 3.0, -1.0};
  EXPECT_DOUBLE_EQ(r(0.0, 10.0), 1.0);    // before the first time
  EXPECT_DOUBLE_EQ(r(0.5, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(r(0.75, 10.0), 2.0);
  EXPECT_DOUBLE_EQ(r(1.0, 10.0), 3.0);
  EXPECT_DOUBLE_EQ(r(1.5, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(r(2.0, 10.0), -1.0);
  EXPECT_DOUBLE_EQ(r(5.0, 10.0), -1.0);   // after the last time
}

// ---------------------------------------------------------------------------
// Schema and docs.

TEST(Schema, NearestName) {
  EXPECT_EQ(nearest_name("C11", {"model", "C1", "C2", "D"}), "C1");
  EXPECT_EQ(nearest_name("STEPPING", {"Stepping", "Newton"}), "Stepping");
  EXPECT_EQ(nearest_name("tolerance", {"relative residual tolerance", "max iterations"}), "relative residual tolerance");
  EXPECT_EQ(nearest_name("qwertyuiop", {"C1", "D"}), "");
  EXPECT_EQ(nearest_name("stiffness", {"C1", "E", "nu", "D"}), "");  // one-letter names are no abbreviation
  EXPECT_EQ(edit_distance_ci("kitten", "SITTING"), 3);
}

TEST(Schema, EveryDefaultSatisfiesItsOwnRange) {
  for (const auto& l : deck_schema())
    for (const auto& p : l.params) {
      if (p.required) continue;
      // A documented default other than a value ("none", "from E/nu or mu/lambda") is not a number to check.
      if ((p.type == ParamType::Int || p.type == ParamType::Double) && p.default_doc.empty()) {
        EXPECT_TRUE(p.in_range(p.num)) << l.title << "->" << p.name;
      }
      if (!p.choices.empty()) {
        const std::string d = p.type == ParamType::Int ? std::to_string(static_cast<int>(p.num)) : p.str;
        EXPECT_NE(std::find(p.choices.begin(), p.choices.end(), d), p.choices.end()) << l.title << "->" << p.name;
      }
      EXPECT_FALSE(p.doc.empty()) << l.title << "->" << p.name;
    }
}

TEST(Schema, DocsContainTheGeneratedTables) {
  const std::string md = deck_schema_markdown();
  std::ifstream f(std::string(STENTOR_SOURCE_DIR) + "/docs/deck.md");
  EXPECT_TRUE(f) << "docs/deck.md not found";
  std::stringstream ss;
  ss << f.rdbuf();
  const bool found = f && ss.str().find(md) != std::string::npos;
  if (!found) {
    const std::string out = std::string(STENTOR_BINARY_DIR) + "/deck_schema.md";
    std::ofstream(out) << md;
    ADD_FAILURE() << "docs/deck.md does not contain the current schema tables; paste " << out
                  << " into docs/deck.md (replacing the BEGIN/END block)";
  }
}

// docs/deck.md's structure table lists every top-level sublist of the schema, in the
// schema's order, and no other.
TEST(Schema, DocsStructureTableListsEveryTopLevelSublist) {
  std::ifstream f(std::string(STENTOR_SOURCE_DIR) + "/docs/deck.md");
  ASSERT_TRUE(f) << "docs/deck.md not found";
  std::string line;
  std::vector<std::string> listed;
  bool in_table = false;
  while (std::getline(f, line)) {
    if (line.rfind("| Sublist |", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    if (line.rfind("|---", 0) == 0) continue;
    if (line.rfind("| `", 0) != 0) break;
    const auto e = line.find('`', 3);
    listed.push_back(line.substr(3, e - 3));
  }
  EXPECT_EQ(listed, deck_list_spec("").sublists);
}

// ---------------------------------------------------------------------------
// Output->field list and Output->times (docs/deck.md, "Outputs").

namespace {
std::string with_output(const std::string& params, const std::string& more = "") {
  return replace(kMinimalDeck, "  <ParameterList name=\"Bodies\">",
                 "  <ParameterList name=\"Output\">" + params + "</ParameterList>\n" + more + "  <ParameterList name=\"Bodies\">");
}
}  // namespace

TEST_F(Deck, OutputFieldListDefaultsAndSelections) {
  {
    const Config c = read_deck(write(kMinimalDeck));
    EXPECT_EQ(c.output.field_list, "default");
    EXPECT_EQ(c.output.field_names, (std::vector<std::string>{"displacement", "cauchy_stress", "von_mises", "J", "mpi_rank"}));
    EXPECT_TRUE(c.output.times.empty());
    EXPECT_TRUE(c.output.wants("von_mises"));
    EXPECT_FALSE(c.output.wants("log_strain"));
  }
  {
    const Config c = read_deck(write(with_output(
        R"XML(<Parameter name="field list" type="string" value="Log_Strain,displacement  reaction_force"/>
        <Parameter name="times" type="Array(double)" value="{0.1, 0.5, 1}"/>)XML")));
    EXPECT_EQ(c.output.field_names, (std::vector<std::string>{"displacement", "reaction_force", "log_strain"}));
    EXPECT_EQ(c.output.times, (std::vector<double>{0.1, 0.5, 1.0}));
  }
  {
    const Config c = read_deck(write(with_output(R"XML(<Parameter name="field list" type="string" value="default, principal_stress"/>)XML")));
    EXPECT_EQ(c.output.field_names.size(), 6u);
    EXPECT_TRUE(c.output.wants("principal_stress"));
    // all: every field of a static deck without contact or plasticity
    const Config a = read_deck(write(with_output(R"XML(<Parameter name="field list" type="string" value="all"/>)XML")));
    EXPECT_EQ(a.output.field_names.size(), 11u);
    EXPECT_FALSE(a.output.wants("velocity"));
    EXPECT_FALSE(a.output.wants("contact_gap"));
  }
  {  // fields off: nothing wanted
    const Config c = read_deck(write(with_output(R"XML(<Parameter name="fields" type="bool" value="false"/>)XML")));
    EXPECT_TRUE(c.output.field_names.empty());
    EXPECT_FALSE(c.output.wants("displacement"));
  }
}

TEST_F(Deck, OutputFieldListAndTimesErrors) {
  expect_error(with_output(R"XML(<Parameter name="field list" type="string" value="displacement, log_stran"/>)XML"),
                                       {"'Output->field list'", "'log_stran' is not a field", "did you mean 'log_strain'",
                                        "valid names: default, all, displacement", "green_lagrange_strain"});
  expect_error(with_output(R"XML(<Parameter name="field list" type="string" value="velocity"/>)XML"),
               {"'Output->field list'", "'velocity' needs 'Problem->analysis' = dynamic"});
  expect_error(with_output(R"XML(<Parameter name="field list" type="string" value="contact_gap"/>)XML"),
               {"'Output->field list'", "'contact_gap' needs a 'Contact' sublist"});
  expect_error(with_output(R"XML(<Parameter name="field list" type="string" value="J, j"/>)XML"), {"lists 'j' twice"});
  expect_error(with_output(R"XML(<Parameter name="field list" type="string" value=" , "/>)XML"), {"names no field"});
  expect_error(with_output(R"XML(<Parameter name="fields" type="bool" value="false"/>
      <Parameter name="field list" type="string" value="J"/>)XML"),
               {"'Output->field list' is given but 'Output->fields' is false"});
  expect_error(with_output(R"XML(<Parameter name="times" type="Array(double)" value="{0.5, 0.5}"/>)XML"),
               {"'Output->times' must be strictly increasing, got 0.5 then 0.5 at positions 1, 2"});
  expect_error(with_output(R"XML(<Parameter name="times" type="Array(double)" value="{0.5, 1.5}"/>)XML"),
               {"'Output->times' must lie in (0, end time = 1], got 1.5 at position 2"});
  expect_error(with_output(R"XML(<Parameter name="times" type="Array(double)" value="{0}"/>)XML"), {"'Output->times' must lie in (0"});
  expect_error(with_output(R"XML(<Parameter name="interval" type="double" value="1e-6"/>)XML"),
               {"'Output->interval' = 1e-06 would write 1000000 field outputs", "at most 100,000"});
  expect_error(with_output(R"XML(<Parameter name="fields" type="bool" value="false"/>
      <Parameter name="interval" type="double" value="0.1"/>)XML"),
               {"'Output->interval' is given but 'Output->fields' is false"});
}

// Output->interval: its multiples up to the end time merged with Output->times, one output
// per time (0.5 given in both is written once; 0.1 kept; the last multiple is the end time).
TEST_F(Deck, OutputIntervalMergesWithTimes) {
  const Config c = read_deck(write(with_output(R"XML(<Parameter name="interval" type="double" value="0.25"/>
      <Parameter name="times" type="Array(double)" value="{0.1, 0.5}"/>)XML")));
  EXPECT_EQ(c.output.times, (std::vector<double>{0.1, 0.25, 0.5, 0.75, 1.0}));
  const Config third = read_deck(write(with_output(R"XML(<Parameter name="interval" type="double" value="0.3333333333333333"/>)XML")));
  ASSERT_EQ(third.output.times.size(), 3u);  // 1/3, 2/3, and 3 x (1/3) within round-off of the end: the end time
  EXPECT_DOUBLE_EQ(third.output.times[2], 1.0);
}

namespace {
// kMinimalDeck with `more` (sublists) before Bodies and density 1 for dynamic stages.
std::string with_lists(const std::string& more) {
  return replace(replace(kMinimalDeck, "<Parameter name=\"D\" type=\"double\" value=\"2\"/>",
                         "<Parameter name=\"D\" type=\"double\" value=\"2\"/><Parameter name=\"density\" type=\"double\" value=\"1\"/>"),
                 "  <ParameterList name=\"Bodies\">", more + "  <ParameterList name=\"Bodies\">");
}
std::string stages_list(const std::string& a, const std::string& b) {
  return "<ParameterList name=\"Stages\"><ParameterList name=\"one\"><Parameter name=\"duration\" type=\"double\" value=\"1\"/>" + a +
         "</ParameterList><ParameterList name=\"two\"><Parameter name=\"duration\" type=\"double\" value=\"1\"/>" + b +
         "</ParameterList></ParameterList>\n";
}
const std::string kDynamic = R"(<Parameter name="analysis" type="string" value="dynamic"/>)";
}  // namespace

// Each stage has its own analysis and scheme; the defaults are Problem->analysis and Time
// Integration->scheme.
TEST_F(Deck, StageAnalysisAndScheme) {
  const Config c = read_deck(write(with_lists(
      "<ParameterList name=\"Time Integration\"><Parameter name=\"scheme\" type=\"string\" value=\"hht\"/></ParameterList>\n" +
      stages_list("", kDynamic + R"(<Parameter name="scheme" type="string" value="newmark"/>)"))));
  ASSERT_EQ(c.stages.size(), 2u);
  EXPECT_EQ(c.stages[0].analysis, "static");
  EXPECT_EQ(c.stages[1].analysis, "dynamic");
  EXPECT_EQ(c.stages[1].scheme, "newmark");
  EXPECT_TRUE(c.any_dynamic());
  EXPECT_TRUE(c.any_static());
  EXPECT_FALSE(c.dynamic_in(0));
  EXPECT_TRUE(c.dynamic_in(1));
  const Config d = read_deck(write(with_lists(
      "<ParameterList name=\"Problem\">" + kDynamic + "</ParameterList>\n" +
      stages_list("", R"(<Parameter name="analysis" type="string" value="static"/>)"))));
  EXPECT_TRUE(d.dynamic_in(0));
  EXPECT_EQ(d.scheme_in(0), "gonzalez");
  EXPECT_FALSE(d.dynamic_in(1));
  // Velocity output needs some dynamic stage, not a dynamic Problem.
  const Config v = read_deck(write(with_lists(
      "<ParameterList name=\"Output\"><Parameter name=\"field list\" type=\"string\" value=\"velocity\"/></ParameterList>\n" +
      stages_list("", kDynamic))));
  EXPECT_TRUE(v.output.wants("velocity"));
}

TEST_F(Deck, StageAnalysisErrors) {
  expect_error(with_lists(stages_list(R"(<Parameter name="scheme" type="string" value="newmark"/>)", "")),
               {"'Stages->one->scheme' is the time scheme of a dynamic stage, and the stage is static",
                "set 'Stages->one->analysis' = dynamic"});
  expect_error(with_lists(stages_list(R"(<Parameter name="analysis" type="string" value="dynamc"/>)", "")),
               {"'Stages->one->analysis'", "dynamic"});
  expect_error(with_lists("<ParameterList name=\"Initial Conditions\"><Parameter name=\"velocity\" type=\"Array(double)\" value=\"{1, 0}\"/>"
                          "</ParameterList>\n" + stages_list("", kDynamic)),
               {"'Initial Conditions' needs the first stage 'Stages->one' to be dynamic"});
  expect_error(with_lists("<ParameterList name=\"Time Integration\"></ParameterList>\n" + stages_list("", "")),
               {"'Time Integration' needs a dynamic stage"});
  expect_error(replace(with_lists(stages_list("", kDynamic)), "<Parameter name=\"density\" type=\"double\" value=\"1\"/>", ""),
               {"'Materials->steel->density' must be > 0 in a dynamic analysis (a stage has 'analysis' = dynamic)"});
  const std::string pair =
      "<ParameterList name=\"Contact\"><ParameterList name=\"floor\"><Parameter name=\"slave\" type=\"string\" value=\"outer\"/>"
      "<Parameter name=\"obstacle\" type=\"string\" value=\"plane\"/><Parameter name=\"point\" type=\"Array(double)\" value=\"{0, 0}\"/>"
      "<Parameter name=\"normal\" type=\"Array(double)\" value=\"{0, 1}\"/>"
      "<Parameter name=\"formulation\" type=\"string\" value=\"persistence\"/></ParameterList></ParameterList>\n";
  expect_error(with_lists(pair + stages_list(kDynamic, "")),
               {"'Contact->floor->formulation' = persistence needs a dynamic analysis, and the pair is active in the static stage "
                "'Stages->two'"});
  // Left out of the static stage, the pair is fine.
  const Config ok = read_deck(write(with_lists(pair + stages_list(kDynamic, R"(<Parameter name="contact" type="string" value="none"/>)"))));
  EXPECT_EQ(ok.stages.size(), 2u);
}

// Per-body initial rotation and displacement: read, and their errors.
TEST_F(Deck, BodyInitialRotationAndDisplacement) {
  const std::string body = R"X(<Parameter name="initial angular velocity" type="Array(double)" value="{2}"/>
      <Parameter name="rotation center" type="Array(double)" value="{0.5, 0.05}"/>
      <Parameter name="initial displacement" type="Array(double)" value="{0.1, 0.2}"/>)X";
  const std::string dyn = "<ParameterList name=\"Problem\">" + kDynamic + "</ParameterList>\n";
  auto deck = [&](const std::string& params, const std::string& more) {
    return replace(with_lists(more), "<Parameter name=\"material\" type=\"string\" value=\"steel\"/>",
                   "<Parameter name=\"material\" type=\"string\" value=\"steel\"/>" + params);
  };
  const Config c = read_deck(write(deck(body, dyn)));
  const BodyConfig& b = c.bodies.front();
  EXPECT_TRUE(b.has_angular_velocity && b.own_velocity() && !b.has_velocity && b.has_displacement);
  EXPECT_EQ(b.angular_velocity, (std::array<double, 3>{0, 0, 2}));
  EXPECT_EQ(b.center, (std::array<double, 3>{0.5, 0.05, 0}));
  EXPECT_EQ(b.displacement, (std::array<double, 3>{0.1, 0.2, 0}));
  expect_error(deck(R"X(<Parameter name="initial angular velocity" type="Array(double)" value="{2}"/>)X", dyn),
               {"'Bodies->stent->rotation center' is required with 'Bodies->stent->initial angular velocity'"});
  expect_error(deck(R"X(<Parameter name="initial angular velocity" type="Array(double)" value="{2, 1}"/>
      <Parameter name="rotation center" type="Array(double)" value="{0.5, 0.05}"/>)X", dyn),
               {"'Bodies->stent->initial angular velocity' must have 1 value (2D, about z) or 3 values (3D), got 2"});
  expect_error(deck(body, ""), {"'Bodies->stent->initial angular velocity' needs 'Problem->analysis' = dynamic"});
  expect_error(deck(R"X(<Parameter name="initial velocity" type="Array(double)" value="{1, 0}"/>)X", stages_list("", kDynamic)),
               {"'Bodies->stent->initial velocity' needs the first stage 'Stages->one' to be dynamic"});
}
