#include "deck/MeshParameters.hpp"

#include <cmath>
#include <set>

#include <Teuchos_ParameterList.hpp>

#include "deck/Config.hpp"

namespace stentor {

std::vector<std::pair<std::string, double>> read_mesh_parameters(const Teuchos::ParameterList& pl, const std::string& deck) {
  std::vector<std::pair<std::string, double>> out;
  std::set<std::string> seen;
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const Teuchos::ParameterEntry& e = pl.entry(it);
    const std::string where = "'Mesh->Parameters->" + name + "'";
    const auto fail = [&](const std::string& why) { throw InputError(deck + ": " + where + " " + why); };
    if (e.isList()) fail("must be a number (double or int), not a sublist");
    double v = 0.0;
    if (e.isType<double>())
      v = e.getValue<double>(nullptr);
    else if (e.isType<int>())
      v = e.getValue<int>(nullptr);
    else
      fail("must be a number: give it type=\"double\" or type=\"int\"");
    if (!std::isfinite(v)) fail("must be finite");
    bool ok = !name.empty() && name.size() <= 100 && name.front() != '/' && name.back() != '/';
    for (char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == ' ' || c == '_' || c == '.' || c == '-' || c == '/');
    if (!ok) fail("is not a parameter name: letters, digits, spaces and _ . - / only (at most 100, no leading or trailing /)");
    const std::string onelab = name.find('/') == std::string::npos ? "Parameters/" + name : name;
    if (!seen.insert(onelab).second) fail("sets '" + onelab + "' a second time");
    out.emplace_back(onelab, v);
  }
  return out;
}

}  // namespace stentor
