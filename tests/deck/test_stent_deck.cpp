// `Mesh->generator` = stent and `Mesh->Stent` (deck/Config.cpp, deck/StentConfig.hpp):
// every parameter reaches MeshConfig::stent, and the mesh-source rules.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "deck/Config.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

std::string deck(const std::string& mesh) {
  return R"XML(<ParameterList name="stentor">
  <ParameterList name="Mesh">)XML" + mesh + R"XML(</ParameterList>
  <ParameterList name="Materials"><ParameterList name="steel">
    <Parameter name="E" type="double" value="196000"/><Parameter name="nu" type="double" value="0.3"/>
  </ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="stent">
    <Parameter name="material" type="string" value="steel"/>
  </ParameterList></ParameterList>
</ParameterList>)XML";
}

const char* kStent = R"XML(<Parameter name="generator" type="string" value="stent"/>
    <ParameterList name="Stent">
      <Parameter name="rings" type="int" value="4"/>
      <Parameter name="crowns" type="int" value="12"/>
      <Parameter name="outer diameter" type="double" value="3.2"/>
      <Parameter name="thickness" type="double" value="0.09"/>
      <Parameter name="strut width" type="double" value="0.08"/>
      <Parameter name="ring length" type="double" value="0.7"/>
      <Parameter name="gap" type="double" value="0.25"/>
      <Parameter name="links" type="string" value="peak-to-peak"/>
      <Parameter name="links per ring" type="int" value="4"/>
      <Parameter name="link width" type="double" value="0.06"/>
      <Parameter name="elements through width" type="int" value="4"/>
      <Parameter name="elements through thickness" type="int" value="2"/>
      <Parameter name="element length" type="double" value="0.03"/>
      <Parameter name="sector" type="string" value="quarter"/>
      <Parameter name="half length" type="bool" value="true"/>
    </ParameterList>)XML";

struct StentDeck : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() / ("stentor_test_stent_deck_" + std::to_string(::getpid()) + "_" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string write(const std::string& xml) {
    std::ofstream(dir / "deck.xml") << xml;
    return (dir / "deck.xml").string();
  }
  std::string error(const std::string& xml) {
    try {
      read_deck(write(xml));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

}  // namespace

TEST_F(StentDeck, EveryParameterReachesTheConfig) {
  const Config c = read_deck(write(deck(kStent)));
  const StentConfig& s = c.mesh.stent;
  EXPECT_EQ(c.mesh.generator, "stent");
  EXPECT_EQ(c.mesh.dimension, 3);
  EXPECT_EQ(s.rings, 4);
  EXPECT_EQ(s.crowns, 12);
  EXPECT_EQ(s.outer_diameter, 3.2);
  EXPECT_EQ(s.thickness, 0.09);
  EXPECT_EQ(s.strut_width, 0.08);
  EXPECT_EQ(s.ring_length, 0.7);
  EXPECT_EQ(s.gap, 0.25);
  EXPECT_EQ(s.links, "peak-to-peak");
  EXPECT_EQ(s.links_per_ring, 4);
  EXPECT_EQ(s.link_width, 0.06);
  EXPECT_EQ(s.elements_width, 4);
  EXPECT_EQ(s.elements_thickness, 2);
  EXPECT_EQ(s.element_length, 0.03);
  EXPECT_EQ(s.sector, "quarter");
  EXPECT_TRUE(s.half_length);
}

TEST_F(StentDeck, OneMeshSource) {
  EXPECT_NE(error(deck("")).find("missing required parameter 'Mesh->file'"), std::string::npos);
  EXPECT_NE(error(deck(R"XML(<Parameter name="generator" type="string" value="stent"/>)XML"))
                .find("missing required sublist 'Mesh->Stent'"),
            std::string::npos);
  EXPECT_NE(error(deck(std::string(kStent) + R"XML(<Parameter name="size" type="double" value="0.1"/>)XML"))
                .find("'Mesh->size' applies to a mesh file"),
            std::string::npos);
  EXPECT_NE(error(deck(R"XML(<Parameter name="file" type="string" value="x.msh"/><ParameterList name="Stent"/>)XML"))
                .find("'Mesh->Stent' needs 'Mesh->generator' = stent"),
            std::string::npos);
}

// `Mesh->Artery` in a stent deck: the artery around the stent (around_stent), its
// parameters those of the artery generator less `sector` and `half length` (the stent's),
// checked against the stent at read.
TEST_F(StentDeck, ArteryAroundTheStent) {
  auto artery = [](const std::string& extra) {
    return std::string(kStent) + R"XML(<ParameterList name="Artery">
      <Parameter name="inner diameter" type="double" value="3.6"/>
      <Parameter name="length" type="double" value="5.0"/>
      <Parameter name="intima thickness" type="double" value="0.27"/>
      <Parameter name="media thickness" type="double" value="0.21"/>
      <Parameter name="adventitia thickness" type="double" value="0.34"/>
      <Parameter name="elements around" type="int" value="48"/>)XML" + extra + "</ParameterList>";
  };
  const Config c = read_deck(write(deck(artery(""))));
  const ArteryConfig& a = c.mesh.artery;
  EXPECT_EQ(c.mesh.generator, "stent");
  EXPECT_TRUE(a.around_stent);
  EXPECT_EQ(a.inner_diameter, 3.6);
  EXPECT_EQ(a.length, 5.0);
  EXPECT_EQ(a.elements_around, 48);
  EXPECT_EQ(cells_around_stent(a, c.mesh.stent), 12);  // the stent's quarter
  EXPECT_FALSE(read_deck(write(deck(kStent))).mesh.artery.around_stent);
  for (const char* p : {"sector", "half length"}) {
    const std::string given = std::string(R"XML(<Parameter name=")XML") + p +
                              (std::string(p) == "sector" ? R"XML(" type="string" value="quarter"/>)XML"
                                                          : R"XML(" type="bool" value="true"/>)XML");
    const std::string e = error(deck(artery(given)));
    EXPECT_NE(e.find(std::string("'Mesh->Artery->") + p + "' does not apply with 'Mesh->generator' = stent"), std::string::npos) << e;
    EXPECT_NE(e.find(std::string("'Mesh->Stent->") + p + "'"), std::string::npos) << e;
  }
  const std::string curved = error(deck(artery(R"XML(<Parameter name="centreline radius" type="double" value="20"/>)XML")));
  EXPECT_NE(curved.find("'Mesh->Artery->centreline radius' (a curved artery) is for 'Mesh->generator' = artery"), std::string::npos)
      << curved;
  std::string narrow = artery("");
  narrow.replace(narrow.find("value=\"3.6\""), 11, "value=\"3.2\"");
  EXPECT_NE(error(deck(narrow)).find("'Mesh->Artery->inner diameter' = 3.2 puts the lumen's facets"), std::string::npos)
      << error(deck(narrow));
  std::string odd = artery("");
  odd.replace(odd.find("value=\"48\""), 10, "value=\"50\"");
  EXPECT_NE(error(deck(odd)).find("'Mesh->Artery->elements around' = 50 must be divisible by 4"), std::string::npos)
      << error(deck(odd));
  EXPECT_NE(error(deck(R"XML(<Parameter name="file" type="string" value="x.msh"/><ParameterList name="Artery"/>)XML"))
                .find("'Mesh->Artery' needs 'Mesh->generator' = artery (or stent"),
            std::string::npos);
}
