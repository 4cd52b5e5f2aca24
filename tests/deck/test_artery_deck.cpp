// `Mesh->generator` = artery and `Mesh->Artery` (deck/Config.cpp, deck/ArteryConfig.hpp):
// every parameter reaches MeshConfig::artery, bad layers are refused naming the parameter,
// and the HGO dispersion `kappa` reaches the material.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "deck/Config.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

std::string deck(const std::string& mesh, const std::string& material_extra = "") {
  return R"XML(<ParameterList name="stentor">
  <ParameterList name="Mesh">)XML" + mesh + R"XML(</ParameterList>
  <ParameterList name="Materials"><ParameterList name="media">
    <Parameter name="model" type="string" value="Holzapfel-Gasser-Ogden"/>
    <Parameter name="mu" type="double" value="0.0015"/><Parameter name="lambda" type="double" value="0.75"/>
    <Parameter name="k1" type="double" value="0.00236"/><Parameter name="k2" type="double" value="0.84"/>
    <Parameter name="fibre angle" type="double" value="39"/>)XML" + material_extra + R"XML(
  </ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="media">
    <Parameter name="material" type="string" value="media"/>
  </ParameterList></ParameterList>
</ParameterList>)XML";
}

std::string artery(const std::string& media_thickness = "0.21") {
  return R"XML(<Parameter name="generator" type="string" value="artery"/>
    <ParameterList name="Artery">
      <Parameter name="inner diameter" type="double" value="3.0"/>
      <Parameter name="length" type="double" value="5.0"/>
      <Parameter name="intima thickness" type="double" value="0.27"/>
      <Parameter name="media thickness" type="double" value=")XML" + media_thickness + R"XML("/>
      <Parameter name="adventitia thickness" type="double" value="0.34"/>
      <Parameter name="elements through intima" type="int" value="2"/>
      <Parameter name="elements through media" type="int" value="3"/>
      <Parameter name="elements through adventitia" type="int" value="4"/>
      <Parameter name="elements around" type="int" value="40"/>
      <Parameter name="elements along" type="int" value="6"/>
      <Parameter name="sector" type="string" value="quarter"/>
      <Parameter name="half length" type="bool" value="true"/>
    </ParameterList>)XML";
}

struct ArteryDeck : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() / ("stentor_test_artery_deck_" + std::to_string(::getpid()) + "_" +
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

TEST_F(ArteryDeck, EveryParameterReachesTheConfig) {
  const Config c = read_deck(write(deck(artery(), R"XML(<Parameter name="kappa" type="double" value="0.226"/>)XML")));
  const ArteryConfig& a = c.mesh.artery;
  EXPECT_EQ(c.mesh.generator, "artery");
  EXPECT_EQ(c.mesh.dimension, 3);
  EXPECT_EQ(a.inner_diameter, 3.0);
  EXPECT_EQ(a.length, 5.0);
  EXPECT_EQ(a.thickness[0], 0.27);
  EXPECT_EQ(a.thickness[1], 0.21);
  EXPECT_EQ(a.thickness[2], 0.34);
  EXPECT_EQ(a.elements_layer[0], 2);
  EXPECT_EQ(a.elements_layer[1], 3);
  EXPECT_EQ(a.elements_layer[2], 4);
  EXPECT_EQ(a.elements_around, 40);
  EXPECT_EQ(a.elements_along, 6);
  EXPECT_EQ(a.sector, "quarter");
  EXPECT_TRUE(a.half_length);
  EXPECT_EQ(c.material("media").kappa, 0.226);
  EXPECT_EQ(read_deck(write(deck(artery()))).material("media").kappa, 0.0);
  EXPECT_EQ(read_deck(write(deck(artery()))).material("media").anisotropy, 1.0);
  const Config r = read_deck(write(deck(artery(), R"XML(<Parameter name="anisotropy" type="double" value="0.51"/>)XML")));
  EXPECT_EQ(r.material("media").anisotropy, 0.51);
}

TEST_F(ArteryDeck, BadInputNamesTheParameter) {
  EXPECT_NE(error(deck(artery("0"))).find("'Mesh->Artery->media thickness'"), std::string::npos) << error(deck(artery("0")));
  EXPECT_NE(error(deck(R"XML(<Parameter name="generator" type="string" value="artery"/>)XML"))
                .find("missing required sublist 'Mesh->Artery'"),
            std::string::npos);
  EXPECT_NE(error(deck(R"XML(<Parameter name="file" type="string" value="x.msh"/><ParameterList name="Artery"/>)XML"))
                .find("'Mesh->Artery' needs 'Mesh->generator' = artery"),
            std::string::npos);
  const std::string k = error(deck(artery(), R"XML(<Parameter name="kappa" type="double" value="0.4"/>)XML"));
  EXPECT_NE(k.find("kappa"), std::string::npos) << k;
  const std::string r = error(deck(artery(), R"XML(<Parameter name="anisotropy" type="double" value="0"/>)XML"));
  EXPECT_NE(r.find("anisotropy"), std::string::npos) << r;
  const std::string both = error(deck(artery(), R"XML(<Parameter name="kappa" type="double" value="0.1"/>
      <Parameter name="anisotropy" type="double" value="0.5"/>)XML"));
  EXPECT_NE(both.find("'Materials->media->anisotropy' = 0.5 with 'Materials->media->kappa' = 0.1: give one of them"),
            std::string::npos)
      << both;
}

// The plaque's parameters reach the configuration (defaults: none, concentric, centred, 2
// cells); bad ones are refused naming the parameter.
TEST_F(ArteryDeck, PlaqueParameters) {
  EXPECT_FALSE(read_deck(write(deck(artery()))).mesh.artery.has_plaque());
  std::string x = artery();
  x.replace(x.find("</ParameterList>"), 0, R"XML(  <Parameter name="plaque stenosis" type="double" value="0.2"/>
      <Parameter name="plaque length" type="double" value="1.5"/>
      <Parameter name="plaque shape" type="string" value="Concentric"/>
      <Parameter name="elements through plaque" type="int" value="3"/>
    )XML");
  const ArteryConfig a = read_deck(write(deck(x))).mesh.artery;
  EXPECT_EQ(a.plaque_stenosis, 0.2);
  EXPECT_EQ(a.plaque_length, 1.5);
  EXPECT_EQ(a.plaque_shape, "concentric");
  EXPECT_EQ(a.elements_plaque, 3);
  EXPECT_EQ(a.plaque_z(), 2.5);
  EXPECT_EQ(a.cells_through(), 2 + 3 + 3 + 4);
  std::string bad = x;
  bad.replace(bad.find("value=\"1.5\""), 11, "value=\"9.0\"");
  EXPECT_NE(error(deck(bad)).find("'Mesh->Artery->plaque length' = 9) must lie within"), std::string::npos) << error(deck(bad));
  bad = x;
  bad.replace(bad.find("value=\"0.2\""), 11, "value=\"1.2\"");
  EXPECT_NE(error(deck(bad)).find("'Mesh->Artery->plaque stenosis'"), std::string::npos) << error(deck(bad));
}

// A curved artery: `centreline radius` reaches the configuration (0 by default), and so do
// the material's bend; what cannot be built is refused naming the parameter.
TEST_F(ArteryDeck, CurvedArtery) {
  auto curved = [](const std::string& radius, const std::string& sector = "half", const std::string& length = "5.0") {
    std::string x = artery();
    x.replace(x.find("quarter"), 7, sector);
    x.replace(x.find(R"(value="5.0")"), 11, "value=\"" + length + "\"");
    return x.replace(x.find("</ParameterList>"), 0,
                     R"XML(<Parameter name="centreline radius" type="double" value=")XML" + radius + "\"/>");
  };
  EXPECT_EQ(read_deck(write(deck(artery()))).mesh.artery.centreline_radius, 0.0);
  const std::string bend = R"XML(<Parameter name="centreline radius" type="double" value="20"/>
      <Parameter name="bend direction" type="Array(double)" value="{1, 0, 0}"/>)XML";
  const Config c = read_deck(write(deck(curved("20"), bend)));
  EXPECT_EQ(c.mesh.artery.centreline_radius, 20.0);
  EXPECT_TRUE(c.mesh.artery.curved());
  EXPECT_EQ(c.material("media").centreline_radius, 20.0);
  EXPECT_EQ(c.material("media").bend_direction[0], 1.0);
  const std::string tight = error(deck(curved("2.0")));
  EXPECT_NE(tight.find("'Mesh->Artery->centreline radius' = 2 must exceed the tube's outer radius"), std::string::npos) << tight;
  const std::string quarter = error(deck(curved("20", "quarter")));
  EXPECT_NE(quarter.find("'Mesh->Artery->sector' = quarter"), std::string::npos) << quarter;
  const std::string long_ = error(deck(curved("20", "half", "70")));
  EXPECT_NE(long_.find("'Mesh->Artery->length' = 70 bends the tube by more than 180 deg"), std::string::npos) << long_;
  const std::string oblique = error(deck(curved("20"), R"XML(<Parameter name="centreline radius" type="double" value="20"/>
      <Parameter name="bend direction" type="Array(double)" value="{1, 0, 1}"/>)XML"));
  EXPECT_NE(oblique.find("'Materials->media->bend direction' must be normal to 'Materials->media->axis'"), std::string::npos)
      << oblique;
  const std::string alone = error(deck(artery(), R"XML(<Parameter name="bend direction" type="Array(double)" value="{1, 0, 0}"/>)XML"));
  EXPECT_NE(alone.find("needs 'Materials->media->centreline radius' > 0"), std::string::npos) << alone;
}
