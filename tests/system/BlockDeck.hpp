// The rubber block of the Dirichlet and reaction tests as deck XML: a Dirichlet entry and
// the whole deck (a .geo or .msh of the unit cube, Mesh->size 0.5, Ciarlet-Geymonat rubber,
// direct solver; by default 2 static steps and no field output).
#pragma once
#include <string>

namespace stentor::testing {

// A `Boundary Conditions` entry of type Dirichlet (values: "" for the default zeros).
inline std::string dirichlet_xml(const std::string& name, const std::string& group, const std::string& comps,
                                 const std::string& values = "") {
  std::string s = R"X(<ParameterList name=")X" + name + R"X("><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value=")X" + group + R"X("/><Parameter name="components" type="string" value=")X" + comps +
                  R"X("/>)X";
  if (!values.empty()) s += R"X(<Parameter name="values" type="Array(double)" value=")X" + values + R"X("/>)X";
  return s + "</ParameterList>\n";
}

// output: the Output parameters besides the basename; stepping: the Stepping (or Stages) sublist.
inline std::string block_deck_xml(
    const std::string& mesh, const std::string& bcs, const std::string& basename,
    const std::string& output = R"X(<Parameter name="fields" type="bool" value="false"/>)X",
    const std::string& stepping = R"X(<ParameterList name="Stepping"><Parameter name="steps" type="int" value="2"/></ParameterList>)X") {
  return R"X(<ParameterList name="stentor">
  <ParameterList name="Mesh"><Parameter name="file" type="string" value=")X" + mesh + R"X("/>
    <Parameter name="size" type="double" value="0.5"/></ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber">
    <Parameter name="C1" type="double" value="0.5e6"/><Parameter name="C2" type="double" value="0.005e6"/>
    <Parameter name="D" type="double" value="0.35e6"/></ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="block">
    <Parameter name="material" type="string" value="rubber"/></ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions">
)X" + bcs + R"X(
  </ParameterList>
  )X" + stepping + R"X(
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output"><Parameter name="basename" type="string" value=")X" + basename + R"X("/>
)X" + output + R"X(</ParameterList>
</ParameterList>
)X";
}

}  // namespace stentor::testing
