// Input deck reader: Teuchos ParameterList XML -> stentor::Config, validated against
// the schema of deck/Schema.cpp. Every problem throws InputError("<deck>: ...").
#include "deck/Config.hpp"
#include "deck/MeshParameters.hpp"
#include "deck/InputLimits.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_FileInputSource.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLObject.hpp>
#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <Teuchos_XMLParameterListReader.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "deck/OutputFields.hpp"
#include "deck/Schema.hpp"
#include "material/ElasticConstants.hpp"
#include "stentor/format.hpp"

namespace stentor {

namespace {
double ramp_value(Ramp::Kind kind, const std::vector<double>& times, const std::vector<double>& factors, double t, double end_time) {
  switch (kind) {
    case Ramp::Kind::Constant: return 1.0;
    case Ramp::Kind::Linear: return end_time > 0.0 ? t / end_time : 1.0;
    case Ramp::Kind::Table: {
      if (times.empty() || factors.size() != times.size()) return 1.0;
      if (t <= times.front()) return factors.front();
      if (t >= times.back()) return factors.back();
      const auto it = std::upper_bound(times.begin(), times.end(), t);  // times[i-1] <= t < times[i]
      const std::size_t i = static_cast<std::size_t>(it - times.begin());
      const double t0 = times[i - 1], t1 = times[i];
      const double w = (t - t0) / (t1 - t0);
      return (1.0 - w) * factors[i - 1] + w * factors[i];
    }
  }
  return 1.0;
}
}  // namespace

double Ramp::operator()(double t, double end_time) const {
  if (stages.empty()) return ramp_value(kind, times, factors, t, end_time);
  // The stage (start, end] holding t; a time within round-off of a stage's end belongs
  // to that stage (its last step ends there), a time past the last stage to the last.
  const Piece* p = &stages.back();
  for (const auto& q : stages)
    if (t <= q.end + 1e-9 * (q.end - q.start)) {
      p = &q;
      break;
    }
  switch (p->mode) {
    case Piece::Mode::Off: return 0.0;
    case Piece::Mode::Hold: return p->held;
    case Piece::Mode::Active: break;
  }
  return ramp_value(p->kind, p->times, p->factors, t - p->start, p->end - p->start);
}

bool Ramp::on(double t) const {
  for (const auto& q : stages)
    if (t <= q.end + 1e-9 * (q.end - q.start)) return q.mode != Piece::Mode::Off;
  return stages.empty() || stages.back().mode != Piece::Mode::Off;
}

bool OutputConfig::wants(const std::string& field) const {
  return fields && std::find(field_names.begin(), field_names.end(), field) != field_names.end();
}

const MaterialConfig& Config::material(const std::string& name) const {
  std::string defined;
  for (const auto& m : materials) {
    if (m.name == name) return m;
    defined += (defined.empty() ? "" : ", ") + m.name;
  }
  throw InputError(deck_path + ": no material named '" + name + "'; defined materials: " +
                   (defined.empty() ? "(none)" : defined));
}

bool Config::any_dynamic() const {
  if (stages.empty()) return problem.dynamic();
  return std::any_of(stages.begin(), stages.end(), [](const StageConfig& s) { return s.dynamic(); });
}

bool Config::pairs_meet(std::size_t a, std::size_t b, const StageConfig** stage) const {
  if (stage) *stage = nullptr;
  if (stages.empty()) return true;
  for (const StageConfig& st : stages)
    if (st.contact_active[a] && st.contact_active[b]) {
      if (stage) *stage = &st;
      return true;
    }
  return false;
}

bool Config::one_analysis() const {
  for (int k = 1; k < interval_count(); ++k)
    if (analysis_in(k) != analysis_in(0)) return false;
  return true;
}

bool Config::any_static() const {
  if (stages.empty()) return !problem.dynamic();
  return std::any_of(stages.begin(), stages.end(), [](const StageConfig& s) { return !s.dynamic(); });
}

namespace {

namespace fs = std::filesystem;
using Teuchos::ParameterEntry;
using Teuchos::ParameterList;
using Teuchos::XMLObject;

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}
std::string num(double v) { return format_number(v, 15); }
std::string join(const std::vector<std::string>& v, const std::string& sep = ", ") {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}
std::string child_path(const std::string& path, const std::string& name) {
  return path.empty() ? name : path + "->" + name;
}
std::string quoted(const std::string& path) { return "'" + path + "'"; }

bool parse_ll(const std::string& s0, long long& out) {
  const std::string s = trim(s0);
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtoll(s.c_str(), &end, 10);
  return errno == 0 && end == s.c_str() + s.size();
}
// The one reader of every real number in a deck (scalars and array entries, pass-through
// lists included): a finite decimal number, [+-]digits[.digits][(e|E)[+-]digits] (".5"
// and "5." too). No nan, inf, hex floats (0x1p-2), overflow (1e999) or a non-zero value
// that underflows to 0 (1e-400; denormals such as 1e-310 stay): strtod takes them
// all and Teuchos turned some into 0. The value parsed here is the value used
// (apply_numbers overwrites Teuchos' own conversion).
bool parse_dbl(const std::string& s0, double& out) {
  const std::string s = trim(s0);
  std::size_t i = 0, digits = 0;
  auto is_digit = [&](std::size_t k) { return k < s.size() && std::isdigit(static_cast<unsigned char>(s[k])); };
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  while (is_digit(i)) ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (is_digit(i)) ++i, ++digits;
  }
  if (digits == 0) return false;
  const bool nonzero = s.find_first_of("123456789") < i;  // in the digits before the exponent
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (!is_digit(i)) return false;
    while (is_digit(i)) ++i;
  }
  if (i != s.size()) return false;
  errno = 0;
  out = std::strtod(s.c_str(), nullptr);
  // Underflow to a denormal keeps a non-zero value; to 0 it would change the meaning
  // (1e-400 as 'Mesh->size' meant the .geo's own size, as 'friction' no friction).
  if (nonzero && out == 0.0) return false;
  return std::isfinite(out) && !(errno == ERANGE && std::abs(out) > 1.0);
}

// Teuchos types a deck may use outside the pass-through sublists.
const std::vector<std::string> kScalarTypes = {"int", "short", "long long", "double", "float", "bool", "string"};
const std::vector<std::string> kXmlTypes = {"int",           "short",        "long long",   "double",
                                            "float",         "bool",         "string",      "Array(int)",
                                            "Array(double)", "Array(float)", "Array(string)"};

// Checks that `value` really is a `type` (Teuchos silently turns "abc" into 0 for a
// double and "2.5" into 2 for an int). Returns "" if fine, else what it should be.
std::string check_xml_value(const std::string& type, const std::string& value) {
  long long ll;
  double d;
  if (type == "int" || type == "short" || type == "long long") {
    if (!parse_ll(value, ll)) return "an integer";
    if (type == "int" && (ll < INT_MIN || ll > INT_MAX)) return "an integer that fits an int";
    if (type == "short" && (ll < SHRT_MIN || ll > SHRT_MAX)) return "an integer that fits a short";
    return "";
  }
  if (type == "double" || type == "float")
    return parse_dbl(value, d) && (type == "double" || std::isfinite(static_cast<float>(d)))
               ? ""
               : "a number (finite and decimal, like 2.5 or -1e-3; no nan, inf, hex or overflow)";
  if (type == "bool") {
    const std::string u = upper(trim(value));
    return (u == "TRUE" || u == "FALSE" || u == "YES" || u == "NO" || u == "1" || u == "0") ? ""
                                                                                              : "true or false";
  }
  if (type.rfind("Array(", 0) == 0 && type.back() == ')') {
    const std::string elem = type.substr(6, type.size() - 7);
    const std::string v = trim(value);
    if (v.size() < 2 || v.front() != '{' || v.back() != '}') return "an array written as {a, b, ...}";
    const std::string inner = v.substr(1, v.size() - 2);
    if (trim(inner).empty() || elem == "string") return "";
    std::stringstream ss(inner);
    std::string item;
    while (std::getline(ss, item, ',')) {
      const std::string bad = check_xml_value(elem, item);
      if (!bad.empty()) return "an array {a, b, ...} of " + elem + " values ('" + trim(item) + "' is not " + bad + ")";
    }
    if (trim(inner).back() == ',') return "an array written as {a, b, ...} (trailing comma)";
    return "";
  }
  return "";
}

// The deepest element nesting of an XML text, and the line where it is first exceeded
// (> limit). Teuchos converts nested lists recursively, so a deck nesting thousands of
// sublists would overflow the stack: the raw text is scanned, without recursion, before
// Teuchos reads it. Comments, CDATA, processing instructions and <!DOCTYPE ...> are
// skipped; quoted attribute values may hold '>'.
struct Nesting {
  int depth = 0;
  int line = 0;  // line of the first element deeper than the limit (0: none)
};
Nesting xml_nesting(const std::string& text, int limit) {
  Nesting n;
  int depth = 0, line = 1;
  const std::size_t size = text.size();
  auto skip_to = [&](std::size_t from, const char* end) {
    const std::size_t e = text.find(end, from);
    const std::size_t stop = e == std::string::npos ? size : e + std::char_traits<char>::length(end);
    line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(from), text.begin() + static_cast<std::ptrdiff_t>(stop), '\n'));
    return stop;
  };
  std::size_t i = 0;
  while (i < size) {
    const char c = text[i];
    if (c != '<') {
      if (c == '\n') ++line;
      ++i;
      continue;
    }
    if (text.compare(i, 4, "<!--") == 0) { i = skip_to(i, "-->"); continue; }
    if (text.compare(i, 9, "<![CDATA[") == 0) { i = skip_to(i, "]]>"); continue; }
    if (text.compare(i, 2, "<?") == 0) { i = skip_to(i, "?>"); continue; }
    if (text.compare(i, 2, "<!") == 0) { i = skip_to(i, text.find('[', i) < text.find('>', i) ? "]>" : ">"); continue; }
    const bool closing = text.compare(i, 2, "</") == 0;
    char quote = 0, prev = 0;
    std::size_t j = i + 1;
    for (; j < size && (quote || text[j] != '>'); ++j) {  // to the tag's '>', quotes respected
      if (text[j] == '\n') ++line;
      if (quote) { if (text[j] == quote) quote = 0; }
      else if (text[j] == '"' || text[j] == '\'') quote = text[j];
      if (!std::isspace(static_cast<unsigned char>(text[j]))) prev = text[j];
    }
    if (closing) --depth;
    else if (prev != '/') ++depth;  // not <x/>
    n.depth = std::max(n.depth, depth);
    if (depth > limit && !n.line) n.line = line;
    i = j + 1;
  }
  return n;
}

class DeckReader {
 public:
  explicit DeckReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& msg) const { throw InputError(file_ + ": " + msg); }

  Config read();

 private:
  std::string file_;  // as given by the user: every message starts with it
  Config cfg_;

  // ---- pass 0: the raw text (nesting depth, before Teuchos recurses over it) ----
  void check_nesting() const;
  // ---- pass 1: the raw XML tree (before Teuchos converts and merges values) ----
  void check_xml(const XMLObject& x, const std::string& path, bool passthrough) const;

  // ---- pass 2: the ParameterList against the schema ----
  void check_list(const ParameterList& pl, const std::string& path, const std::vector<const ListSpec*>& specs) const;
  void check_param(const ParameterEntry& e, const std::string& path, const ParamSpec& p) const;
  void require(const ParameterList& pl, const std::string& path, const std::vector<const ListSpec*>& specs) const;

  // Typed access (after check_list): the value, or the schema default when absent.
  static const ParamSpec& spec(const ListSpec& ls, const std::string& name) {
    const ParamSpec* p = ls.find(name);
    if (!p) throw std::logic_error("stentor deck: no parameter '" + name + "' in schema list '" + ls.key + "'");
    return *p;
  }
  double get_double(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  int get_int(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  bool get_bool(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  std::string get_string(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  std::vector<double> get_array(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;

  void read_problem(const ParameterList& pl);
  void read_mesh(const ParameterList& pl);
  void read_stent(const ParameterList& pl);
  void read_artery(const ParameterList& pl, bool around_stent);
  void read_balloon(const ParameterList& pl);
  void check_stent_plastic() const;
  void read_materials(const ParameterList& pl);
  void read_elastic_constants(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const;
  void read_fibres(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m);
  void read_inelastic(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const;
  void read_hardening(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const;
  void read_bodies(const ParameterList& pl);
  void read_loads(const ParameterList& pl);
  void read_fluid_cavity(const ParameterList& sub, const ListSpec& ls, const std::string& path, LoadConfig& lc);
  void read_stepping(const ParameterList& pl);
  void read_initial(const ParameterList& pl);
  void read_time(const ParameterList& pl);
  void read_newton(const ParameterList& pl);
  void read_linear(const ParameterList& pl);
  void read_output(const ParameterList& pl);
  void resolve_output();  // after Contact and Stages: field names and output times
  void merge_output_interval(OutputConfig& o, double end) const;
  Ramp read_ramp(const ParameterList& pl, const std::string& path, const ListSpec& ls, const std::string& key = "ramp") const;
  void read_contact(const ParameterList& pl);
  void read_stages(const ParameterList& pl, const ParameterList* stepping);
  void read_body_initial_state(const ParameterList& sub, const std::string& path, BodyConfig& b);
  void check_analysis(bool initial_conditions, bool time_integration);
  void read_stage_analysis(const ParameterList& sub, const std::string& path, StageConfig& st);
  std::vector<bool> read_active(const ParameterList& sub, const std::string& path, const std::string& key,
                                const std::vector<std::string>& names, const std::string& what) const;
  void read_stage_ramps(const ParameterList& sub, const std::string& path, std::size_t k);
  void read_contact_obstacle(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c);
  void read_stent_metrics(const ParameterList& sub);
  void read_obstacle_axis(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c);
  // Records a dimension-dependent vector (Config::dim_vectors) and, when Mesh->dimension is
  // set, checks it now. in2d / in3d: the number of values a 2D / 3D problem takes.
  void check_dim_length(const std::vector<double>& v, const std::string& path, int in2d = 2, int in3d = 3);
  void check_step(double step, double end, const std::string& what) const;
  void check_safe_name(const std::string& text, const std::string& path, const std::string& what) const;
  void unit_direction(std::array<double, 3>& v, const std::string& path) const;
};

// ------------------------------------------------------------------------------------
// Pass 0: raw text. A Stentor deck nests 5 levels (Linear Solver->MueLu->... sublists
// a few more); kMaxNesting leaves ample room and stays far from the stack's limit.

constexpr int kMaxNesting = 64;
// The most steps a procedure may take (all stages together): the run counts steps and
// attempts in int, and caps the attempts at 100 x steps + 1000 (Stepping->max steps).
constexpr long long kMaxTotalSteps = 20000000;

void DeckReader::check_nesting() const {
  std::ifstream in(cfg_.deck_path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) fail("cannot read the deck (" + cfg_.deck_path + ")");
  const Nesting n = xml_nesting(text.str(), kMaxNesting);
  if (n.line)
    fail("line " + std::to_string(n.line) + ": elements nested " + std::to_string(n.depth) + " deep; a deck nests at most " +
         std::to_string(kMaxNesting) + " levels of <ParameterList>");
}

// ------------------------------------------------------------------------------------
// Pass 1: raw XML.

void DeckReader::check_xml(const XMLObject& x, const std::string& path, bool passthrough) const {
  const std::string where = path.empty() ? "the root list" : quoted(path);
  std::set<std::string> seen;
  for (int i = 0; i < x.numChildren(); ++i) {
    const XMLObject& c = x.getChild(i);
    const std::string& tag = c.getTag();
    if (tag != "Parameter" && tag != "ParameterList")
      fail("unexpected element <" + tag + "> in " + where + "; a list holds only <Parameter> and <ParameterList> elements");
    if (!c.hasAttribute("name") || trim(c.getAttribute("name")).empty())
      fail("a <" + tag + "> in " + where + " has no name attribute");
    const std::string& name = c.getAttribute("name");
    const std::string p = child_path(path, name);
    if (!seen.insert(name).second) fail(quoted(p) + " is given twice; each name may appear once per list");
    if (tag == "ParameterList") {
      check_xml(c, p, passthrough || (path == "Linear Solver" && (name == "Belos" || name == "Ifpack2" ||
                                                                  name == "MueLu" || name == "Amesos2")));
      continue;
    }
    if (!c.hasAttribute("type"))
      fail("parameter " + quoted(p) + " has no type attribute (e.g. type=\"double\"; types: int, double, bool, "
           "string, Array(double))");
    if (!c.hasAttribute("value")) fail("parameter " + quoted(p) + " has no value attribute");
    const std::string& type = c.getAttribute("type");
    const std::string& value = c.getAttribute("value");
    const bool known = std::find(kXmlTypes.begin(), kXmlTypes.end(), type) != kXmlTypes.end();
    if (!known && !passthrough) {
      const std::string near = nearest_name(type, kXmlTypes);
      fail("parameter " + quoted(p) + " has unknown type '" + type +
           "'; deck types are int, double, bool, string, Array(double)" +
           (near.empty() ? std::string() : "; did you mean '" + near + "'?"));
    }
    if (known) {
      const std::string bad = check_xml_value(type, value);
      if (!bad.empty())
        fail("wrong value for " + quoted(p) + ": type=\"" + type + "\" needs " + bad + ", got '" + value + "'");
    }
  }
}

// Replaces Teuchos' conversion of every real number (scalar or array, after check_xml
// accepted it) by parse_dbl's, so that one reader decides every value.
void apply_numbers(const XMLObject& x, ParameterList& pl) {
  for (int i = 0; i < x.numChildren(); ++i) {
    const XMLObject& c = x.getChild(i);
    const std::string& name = c.getAttribute("name");
    if (c.getTag() == "ParameterList") {
      if (pl.isSublist(name)) apply_numbers(c, pl.sublist(name));
      continue;
    }
    const std::string& type = c.getAttribute("type");
    const std::string& value = c.getAttribute("value");
    double d = 0.0;
    if (type == "double" && parse_dbl(value, d)) pl.set(name, d);
    if (type == "float" && parse_dbl(value, d)) pl.set(name, static_cast<float>(d));
    if (type != "Array(double)" && type != "Array(float)") continue;
    const std::string v = trim(value);
    std::stringstream ss(v.size() >= 2 ? v.substr(1, v.size() - 2) : std::string());
    std::string item;
    Teuchos::Array<double> ad;
    while (std::getline(ss, item, ','))
      if (!trim(item).empty() && parse_dbl(item, d)) ad.push_back(d);
    if (type == "Array(double)") {
      pl.set(name, ad);
    } else {
      Teuchos::Array<float> af;
      for (double e : ad) af.push_back(static_cast<float>(e));
      pl.set(name, af);
    }
  }
}

// Strips Teuchos' exception boilerplate (source location, throw number, test text).
std::string clean_teuchos_message(const std::string& what) {
  std::istringstream is(what);
  std::string line, out;
  while (std::getline(is, line)) {
    const std::string t = trim(line);
    if (t.empty() || t.rfind("Throw number", 0) == 0 || t.rfind("Throw test that evaluated to true", 0) == 0) continue;
    if ((t.find(".cpp:") != std::string::npos || t.find(".hpp:") != std::string::npos) && t.back() == ':' &&
        t.find(' ') == std::string::npos)
      continue;  // "./packages/teuchos/.../Teuchos_XMLParser.cpp:435:"
    out += (out.empty() ? "" : " ") + t;
  }
  return out.empty() ? what : out;
}

std::string rewrap_xml_error(const std::string& what) {
  std::string msg = clean_teuchos_message(what);
  if (msg.find("empty XML") != std::string::npos) return "malformed XML: the file is empty (no root element)";
  const std::string marker = "XML parse error at line ";
  const auto pos = msg.find(marker);
  if (pos != std::string::npos) {
    std::size_t e = pos + marker.size();
    std::size_t q = e;
    while (q < msg.size() && std::isdigit(static_cast<unsigned char>(msg[q]))) ++q;
    const std::string line = msg.substr(e, q - e);
    std::string rest = msg.substr(q);
    if (rest.rfind(": ", 0) == 0) rest = rest.substr(2);
    return "malformed XML at line " + line + ": " + rest;
  }
  return "malformed XML: " + msg;
}

// ------------------------------------------------------------------------------------
// Pass 2: schema validation.

std::string xml_type_of(const Teuchos::any& a) {
  const auto& t = a.type();
  if (t == typeid(int)) return "int";
  if (t == typeid(short)) return "short";
  if (t == typeid(long long)) return "long long";
  if (t == typeid(double)) return "double";
  if (t == typeid(float)) return "float";
  if (t == typeid(bool)) return "bool";
  if (t == typeid(std::string)) return "string";
  if (t == typeid(Teuchos::Array<double>)) return "Array(double)";
  if (t == typeid(Teuchos::Array<float>)) return "Array(float)";
  if (t == typeid(Teuchos::Array<int>)) return "Array(int)";
  if (t == typeid(Teuchos::Array<std::string>)) return "Array(string)";
  return a.typeName();
}

bool as_double(const Teuchos::any& a, double& v);
bool as_array(const Teuchos::any& a, std::vector<double>& v);

std::string value_text(const Teuchos::any& a) {
  std::ostringstream os;
  std::vector<double> v;
  double d;
  if (a.type() == typeid(std::string))
    os << "'" << Teuchos::any_cast<std::string>(a) << "'";
  else if (a.type() == typeid(bool))
    os << (Teuchos::any_cast<bool>(a) ? "true" : "false");
  else if (as_array(a, v)) {
    os << "{";
    for (std::size_t i = 0; i < v.size(); ++i) os << (i ? ", " : "") << num(v[i]);
    os << "}";
  } else if (as_double(a, d))
    os << num(d);
  else
    os << a;
  return os.str();
}

bool as_double(const Teuchos::any& a, double& v) {
  const auto& t = a.type();
  if (t == typeid(double)) v = Teuchos::any_cast<double>(a);
  else if (t == typeid(float)) v = Teuchos::any_cast<float>(a);
  else if (t == typeid(int)) v = Teuchos::any_cast<int>(a);
  else if (t == typeid(short)) v = Teuchos::any_cast<short>(a);
  else if (t == typeid(long long)) v = static_cast<double>(Teuchos::any_cast<long long>(a));
  else return false;
  return true;
}

bool as_int(const Teuchos::any& a, long long& v) {
  const auto& t = a.type();
  if (t == typeid(int)) v = Teuchos::any_cast<int>(a);
  else if (t == typeid(short)) v = Teuchos::any_cast<short>(a);
  else if (t == typeid(long long)) v = Teuchos::any_cast<long long>(a);
  else return false;
  return true;
}

bool as_array(const Teuchos::any& a, std::vector<double>& v) {
  const auto& t = a.type();
  v.clear();
  if (t == typeid(Teuchos::Array<double>)) {
    for (double x : Teuchos::any_cast<Teuchos::Array<double>>(a)) v.push_back(x);
  } else if (t == typeid(Teuchos::Array<float>)) {
    for (float x : Teuchos::any_cast<Teuchos::Array<float>>(a)) v.push_back(x);
  } else if (t == typeid(Teuchos::Array<int>)) {
    for (int x : Teuchos::any_cast<Teuchos::Array<int>>(a)) v.push_back(x);
  } else {
    return false;
  }
  return true;
}

// Canonical spelling of `s` among `choices` (case-insensitive), or "".
std::string match_choice(const std::string& s, const std::vector<std::string>& choices) {
  for (const auto& c : choices)
    if (lower(trim(s)) == lower(c)) return c;
  return "";
}

void DeckReader::check_param(const ParameterEntry& e, const std::string& path, const ParamSpec& p) const {
  const Teuchos::any& a = e.getAny();
  auto wrong_type = [&]() {
    fail("wrong type for " + quoted(path) + ": expected " + param_type_name(p.type) + ", got " + xml_type_of(a) +
         " " + value_text(a));
  };
  auto out_of_range = [&](const std::string& what) {
    fail(quoted(path) + " must be " + p.range_text() + ", got " + what);
  };
  auto not_a_choice = [&](const std::string& given) {
    const bool is_str = p.type == ParamType::String;
    std::string msg = quoted(path) + " must be one of " + join(p.choices) + "; got " + (is_str ? "'" + given + "'" : given);
    const std::string near = nearest_name(trim(given), p.choices);
    if (!near.empty() && is_str) msg += "; did you mean '" + near + "'?";
    fail(msg);
  };
  switch (p.type) {
    case ParamType::Double: {
      double v;
      if (!as_double(a, v)) wrong_type();
      if (!std::isfinite(v)) fail(quoted(path) + " must be a finite number, got " + num(v));
      if (!p.in_range(v)) out_of_range(num(v));
      break;
    }
    case ParamType::Int: {
      long long v;
      if (!as_int(a, v)) wrong_type();
      if (v < INT_MIN || v > INT_MAX) fail(quoted(path) + " does not fit an int, got " + std::to_string(v));
      if (!p.in_range(static_cast<double>(v))) out_of_range(std::to_string(v));
      if (!p.choices.empty() &&
          std::find(p.choices.begin(), p.choices.end(), std::to_string(v)) == p.choices.end())
        not_a_choice(std::to_string(v));
      break;
    }
    case ParamType::Bool:
      if (a.type() != typeid(bool)) wrong_type();
      break;
    case ParamType::String: {
      if (a.type() != typeid(std::string)) wrong_type();
      const auto& s = Teuchos::any_cast<std::string>(a);
      if (!p.choices.empty() && match_choice(s, p.choices).empty()) not_a_choice(s);
      if (p.required && trim(s).empty()) fail(quoted(path) + " must not be empty");
      break;
    }
    case ParamType::DoubleArray: {
      std::vector<double> v;
      if (!as_array(a, v)) wrong_type();
      const int n = static_cast<int>(v.size());
      if ((p.min_len > 0 && n < p.min_len) || (p.max_len > 0 && n > p.max_len)) {
        std::string want;
        if (p.min_len == p.max_len) want = std::to_string(p.min_len);
        else if (p.max_len == 0) want = "at least " + std::to_string(p.min_len);
        else want = std::to_string(p.min_len) + " to " + std::to_string(p.max_len);
        fail(quoted(path) + " must have " + want + " values, got " + std::to_string(n) + " " + value_text(a));
      }
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (!std::isfinite(v[i])) fail(quoted(path) + " must hold finite numbers, got " + value_text(a));
        if (!p.in_range(v[i]))
          fail("each value of " + quoted(path) + " must be " + p.range_text() + ", got " + num(v[i]) + " at position " +
               std::to_string(i + 1));
      }
      break;
    }
  }
}

void DeckReader::check_list(const ParameterList& pl, const std::string& path,
                            const std::vector<const ListSpec*>& specs) const {
  std::vector<std::string> param_names, fixed_sublists;
  std::string named;  // what a user-named sublist is ("material", ...), "" if none allowed
  for (const ListSpec* s : specs) {
    if (s->passthrough) return;
    for (const auto& p : s->params) param_names.push_back(p.name);
    fixed_sublists.insert(fixed_sublists.end(), s->sublists.begin(), s->sublists.end());
    if (!s->named_sublists.empty()) named = s->named_sublists;
  }
  auto find_param = [&](const std::string& n) -> const ParamSpec* {
    for (const ListSpec* s : specs)
      if (const ParamSpec* p = s->find(n)) return p;
    return nullptr;
  };
  const std::string where = path.empty() ? "the root list" : quoted(path);

  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const ParameterEntry& e = pl.entry(it);
    const std::string p = child_path(path, name);
    const bool is_fixed = std::find(fixed_sublists.begin(), fixed_sublists.end(), name) != fixed_sublists.end();
    if (e.isList()) {
      if (is_fixed || !named.empty()) continue;  // validated by the caller
      if (const ParamSpec* ps = find_param(name))
        fail(quoted(p) + " must be a parameter (" + param_type_name(ps->type) + "), not a sublist");
      std::vector<std::string> cands = fixed_sublists;
      cands.insert(cands.end(), param_names.begin(), param_names.end());
      const std::string near = nearest_name(name, cands);
      if (!near.empty()) fail("unknown sublist " + quoted(p) + "; did you mean '" + near + "'?");
      fail("unknown sublist " + quoted(p) + "; " +
           (fixed_sublists.empty() ? where + " has no sublists"
                                   : "valid sublists of " + where + ": " + join(fixed_sublists)));
    }
    if (const ParamSpec* ps = find_param(name)) {
      check_param(e, p, *ps);
      continue;
    }
    if (is_fixed) fail(quoted(p) + " must be a sublist (<ParameterList name=\"" + name + "\">), not a parameter");
    if (!named.empty() && param_names.empty())
      fail(quoted(p) + " is a parameter, but " + where + " holds only sublists, one per " + named +
           " (<ParameterList name=\"...\">)");
    std::vector<std::string> cands = param_names;
    cands.insert(cands.end(), fixed_sublists.begin(), fixed_sublists.end());
    const std::string near = nearest_name(name, cands);
    if (!near.empty()) fail("unknown parameter " + quoted(p) + "; did you mean '" + near + "'?");
    fail("unknown parameter " + quoted(p) + "; " +
         (param_names.empty() ? where + " takes no parameters" : "valid parameters of " + where + ": " + join(param_names)));
  }
}

void DeckReader::require(const ParameterList& pl, const std::string& path,
                         const std::vector<const ListSpec*>& specs) const {
  for (const ListSpec* s : specs) {
    for (const auto& p : s->params)
      if (p.required && !pl.isParameter(p.name)) {
        std::string what = param_type_name(p.type);
        const std::string allowed = p.allowed_text();
        if (allowed != "any") what += ", " + allowed;
        std::string msg = "missing required parameter " + quoted(child_path(path, p.name)) + " (" + what + "): " + p.doc;
        msg.erase(std::remove(msg.begin(), msg.end(), '`'), msg.end());
        fail(msg);
      }
    for (const auto& l : s->required_sublists)
      if (!pl.isSublist(l)) fail("missing required sublist " + quoted(child_path(path, l)));
  }
}

double DeckReader::get_double(const ParameterList& pl, const ListSpec& ls, const std::string& name) const {
  const ParamSpec& p = spec(ls, name);
  double v = p.num;
  if (pl.isParameter(name)) as_double(pl.getEntry(name).getAny(), v);
  return v;
}
int DeckReader::get_int(const ParameterList& pl, const ListSpec& ls, const std::string& name) const {
  const ParamSpec& p = spec(ls, name);
  long long v = static_cast<long long>(p.num);
  if (pl.isParameter(name)) as_int(pl.getEntry(name).getAny(), v);
  return static_cast<int>(v);
}
bool DeckReader::get_bool(const ParameterList& pl, const ListSpec& ls, const std::string& name) const {
  const ParamSpec& p = spec(ls, name);
  return pl.isParameter(name) ? pl.get<bool>(name) : p.num != 0.0;
}
std::string DeckReader::get_string(const ParameterList& pl, const ListSpec& ls, const std::string& name) const {
  const ParamSpec& p = spec(ls, name);
  std::string s = pl.isParameter(name) ? trim(pl.get<std::string>(name)) : p.str;
  if (!p.choices.empty()) {
    const std::string c = match_choice(s, p.choices);
    if (!c.empty()) s = c;
  }
  return s;
}
std::vector<double> DeckReader::get_array(const ParameterList& pl, const ListSpec& ls, const std::string& name) const {
  spec(ls, name);
  std::vector<double> v;
  if (pl.isParameter(name)) as_array(pl.getEntry(name).getAny(), v);
  return v;
}

void DeckReader::check_dim_length(const std::vector<double>& v, const std::string& path, int in2d, int in3d) {
  cfg_.dim_vectors.push_back({path, static_cast<int>(v.size()), in2d, in3d});
  const int dim = cfg_.mesh.dimension;
  const int want = dim == 2 ? in2d : in3d;
  if ((dim == 2 || dim == 3) && static_cast<int>(v.size()) != want)
    fail(quoted(path) + " must have " + std::to_string(want) + " value" + (want == 1 ? "" : "s") + " ('Mesh->dimension' = " +
         std::to_string(dim) + "), got " + std::to_string(v.size()));
}

// Names that end up in output file names, CSV column headers and plot labels (loads,
// probes, contact pairs, the basename) are restricted to a character set that no shell,
// gnuplot or file system interprets: letters, digits, space and _ . + -, and to 100
// characters (a file name holds at most 255 bytes).
// A step the time loop can take: t + step > t up to the interval's end `end`, with a
// margin (step >= 1e-12 x end), and far from underflow (step >= 1e-300), so that its
// halvings and the default min dt (1e-6 x step) are positive normal numbers. A step of
// 4.9e-324 (a denormal) would be 0 after one halving and the time would never advance.
void DeckReader::check_step(double step, double end, const std::string& what) const {
  if (step >= 1e-300 && step >= 1e-12 * std::abs(end)) return;
  fail(what + " = " + num(step) + " is too small: it must be at least 1e-300 and 1e-12 x the end time " + num(end) +
       " (else the time cannot advance); use a larger end time or fewer steps");
}

void DeckReader::check_safe_name(const std::string& text, const std::string& path, const std::string& what) const {
  // File names are at most 255 bytes: <basename>_reaction_<load>.gp.log must fit (a load
  // named with 300 characters failed the run at its end, writing the plot script).
  if (text.size() > 100)
    fail(quoted(path) + ": " + what + " has " + std::to_string(text.size()) +
         " characters; at most 100 (it names output files, CSV columns and plot labels)");
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) && u < 128) continue;
    if (c == ' ' || c == '_' || c == '.' || c == '+' || c == '-') continue;
    std::ostringstream bad;
    if (std::isprint(u) && u < 128)
      bad << "'" << c << "'";
    else
      bad << "byte 0x" << std::hex << static_cast<int>(u);
    fail(quoted(path) + ": " + what + " '" + text + "' contains " + bad.str() +
         "; it may contain only letters, digits, spaces and _ . + - (it names output files, CSV columns and plot labels)");
  }
}

// Normalises a direction in place; its length must be a positive finite number (a zero
// vector, or one whose squared length underflows to 0 or overflows, is refused).
void DeckReader::unit_direction(std::array<double, 3>& v, const std::string& path) const {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0.0) || !std::isfinite(n))
    fail(quoted(path) + " must be a direction of nonzero, finite length (its squared length " +
         (n > 0.0 ? std::string("overflows") : std::string("is 0")) + "); got (" + num(v[0]) + ", " + num(v[1]) +
         ", " + num(v[2]) + ")");
  for (auto& x : v) x /= n;
}

// ------------------------------------------------------------------------------------
// Sections.

void DeckReader::read_problem(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Problem");
  check_list(pl, "Problem", {&ls});
  cfg_.problem.title = get_string(pl, ls, "title");
  cfg_.problem.analysis = get_string(pl, ls, "analysis");
  cfg_.problem.assembly = get_string(pl, ls, "assembly");
  cfg_.problem.units = get_string(pl, ls, "units");
  cfg_.problem.kinematics = get_string(pl, ls, "kinematics");
}

void DeckReader::read_mesh(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Mesh");
  check_list(pl, "Mesh", {&ls});
  require(pl, "Mesh", {&ls});
  auto& m = cfg_.mesh;
  const std::string generator = get_string(pl, ls, "generator");
  m.generator = lower(generator) == "none" ? "" : lower(generator);
  if (m.generator.empty() == !pl.isParameter("file"))
    fail(m.generator.empty() ? "missing required parameter 'Mesh->file' (string, existing .msh or .geo file), or give "
                               "'Mesh->generator'"
                             : "'Mesh->file' and 'Mesh->generator' = " + generator + " exclude each other: give one");
  if (m.generator.empty() && pl.isParameter("write mesh"))
    fail("'Mesh->write mesh' applies to 'Mesh->generator', not to a mesh file");
  if (pl.isSublist("Stent") && m.generator != "stent") fail("'Mesh->Stent' needs 'Mesh->generator' = stent");
  if (pl.isSublist("Artery") && m.generator != "artery" && m.generator != "stent")
    fail("'Mesh->Artery' needs 'Mesh->generator' = artery (or stent: the artery around the stent)");
  if (pl.isSublist("Balloon") && m.generator != "stent")
    fail("'Mesh->Balloon' needs 'Mesh->generator' = stent (the balloon is mounted in the generated stent)");
  if (pl.isSublist("Parameters") && !m.generator.empty())
    fail("'Mesh->Parameters' sets the parameters of a .geo 'Mesh->file', not of 'Mesh->generator'");
  m.max_cells = get_double(pl, ls, "max cells");
  if (!m.generator.empty()) {
    for (const char* p : {"size", "order", "recombine", "dimension", "time limit"})
      if (pl.isParameter(p)) fail(quoted(std::string("Mesh->") + p) + " applies to a mesh file, not to 'Mesh->generator'");
    const std::string sub = m.generator == "stent" ? "Stent" : "Artery";
    if (!pl.isSublist(sub)) fail("missing required sublist 'Mesh->" + sub + "' ('Mesh->generator' = " + m.generator + ")");
    if (m.generator == "stent") {
      read_stent(pl.sublist("Stent"));
      if (pl.isSublist("Balloon")) read_balloon(pl.sublist("Balloon"));
      if (pl.isSublist("Artery")) read_artery(pl.sublist("Artery"), true);
    } else
      read_artery(pl.sublist("Artery"), false);
    m.write_mesh = get_bool(pl, ls, "write mesh");
    m.dimension = 3;
    m.file = cfg_.deck_path;  // messages about the mesh name the deck
    return;
  }
  const std::string file = get_string(pl, ls, "file");
  fs::path f(file);
  if (f.is_relative()) f = fs::path(cfg_.deck_path).parent_path() / f;
  f = f.lexically_normal();
  m.file = f.string();
  const std::string ext = lower(f.extension().string());
  if (ext != ".msh" && ext != ".geo")
    fail("'Mesh->file' must be a gmsh .msh or .geo file, got '" + file + "'");
  std::error_code ec;
  if (!fs::exists(f, ec)) fail("'Mesh->file': mesh file '" + m.file + "' does not exist (resolved from '" + file +
                               "' relative to the deck's folder)");
  if (!fs::is_regular_file(f, ec)) fail("'Mesh->file': '" + m.file + "' is not a regular file");
  if (pl.isSublist("Parameters")) {
    if (ext != ".geo") fail("'Mesh->Parameters' sets the DefineNumber parameters of a .geo file; '" + file + "' is a .msh");
    m.parameters = read_mesh_parameters(pl.sublist("Parameters"), file_);
  }
  m.size = get_double(pl, ls, "size");
  m.order = get_int(pl, ls, "order");
  m.recombine = get_bool(pl, ls, "recombine");
  m.dimension = get_int(pl, ls, "dimension");
  m.time_limit = get_double(pl, ls, "time limit");
  if (m.recombine && m.order == 2)
    fail("'Mesh->recombine' = true needs 'Mesh->order' = 1 (quad8/hex20 bodies are not supported)");
}

void DeckReader::read_stent(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Mesh/Stent");
  check_list(pl, "Mesh->Stent", {&ls});
  require(pl, "Mesh->Stent", {&ls});
  StentConfig& s = cfg_.mesh.stent;
  s.rings = get_int(pl, ls, "rings");
  s.crowns = get_int(pl, ls, "crowns");
  s.outer_diameter = get_double(pl, ls, "outer diameter");
  s.thickness = get_double(pl, ls, "thickness");
  s.strut_width = get_double(pl, ls, "strut width");
  s.ring_length = get_double(pl, ls, "ring length");
  s.gap = get_double(pl, ls, "gap");
  s.links = lower(get_string(pl, ls, "links"));
  s.links_per_ring = get_int(pl, ls, "links per ring");
  s.link_width = get_double(pl, ls, "link width");
  s.elements_width = get_int(pl, ls, "elements through width");
  s.elements_thickness = get_int(pl, ls, "elements through thickness");
  s.element_length = get_double(pl, ls, "element length");
  s.sector = lower(get_string(pl, ls, "sector"));
  s.half_length = get_bool(pl, ls, "half length");
  const std::string why = stent_config_error(s);
  if (!why.empty()) fail(why);
}

void DeckReader::read_balloon(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Mesh/Balloon");
  check_list(pl, "Mesh->Balloon", {&ls});
  require(pl, "Mesh->Balloon", {&ls});
  BalloonConfig& b = cfg_.mesh.balloon;
  b.enabled = true;
  b.outer_diameter = get_double(pl, ls, "outer diameter");
  b.thickness = get_double(pl, ls, "thickness");
  b.length = get_double(pl, ls, "length");
  b.elements_thickness = get_int(pl, ls, "elements through thickness");
  b.element_length = get_double(pl, ls, "element length");
  const std::string why = balloon_config_error(b, cfg_.mesh.stent);
  if (!why.empty()) fail(why);
}

// around_stent: `Mesh->Artery` in a stent deck, the artery around the stent, which takes
// the stent's sector and half length (its own are refused).
void DeckReader::read_artery(const ParameterList& pl, bool around_stent) {
  const ListSpec& ls = deck_list_spec("Mesh/Artery");
  check_list(pl, "Mesh->Artery", {&ls});
  require(pl, "Mesh->Artery", {&ls});
  ArteryConfig& a = cfg_.mesh.artery;
  a.around_stent = around_stent;
  if (around_stent)
    for (const char* p : {"sector", "half length"})
      if (pl.isParameter(p))
        fail(quoted(std::string("Mesh->Artery->") + p) + " does not apply with 'Mesh->generator' = stent: the artery around "
             "the stent takes the stent's " + quoted(std::string("Mesh->Stent->") + p) + "; remove it");
  a.inner_diameter = get_double(pl, ls, "inner diameter");
  a.length = get_double(pl, ls, "length");
  for (int l = 0; l < 3; ++l) {
    a.thickness[l] = get_double(pl, ls, std::string(kArteryLayer[l]) + " thickness");
    a.elements_layer[l] = get_int(pl, ls, std::string("elements through ") + kArteryLayer[l]);
  }
  a.elements_around = get_int(pl, ls, "elements around");
  a.elements_along = get_int(pl, ls, "elements along");
  a.sector = lower(get_string(pl, ls, "sector"));
  a.half_length = get_bool(pl, ls, "half length");
  a.plaque_stenosis = get_double(pl, ls, "plaque stenosis");
  a.plaque_length = get_double(pl, ls, "plaque length");
  a.plaque_centre = get_double(pl, ls, "plaque centre");
  a.plaque_shape = lower(get_string(pl, ls, "plaque shape"));
  a.elements_plaque = get_int(pl, ls, "elements through plaque");
  const std::string why = around_stent ? artery_around_stent_error(a, cfg_.mesh.stent) : artery_config_error(a);
  if (!why.empty()) fail(why);
}

// A plastic body on a generated stent needs 3 cells through the width and the thickness
// (fewer cannot carry the bending of a crown's plastic hinge).
void DeckReader::check_stent_plastic() const {
  const StentConfig& s = cfg_.mesh.stent;
  if (cfg_.mesh.generator != "stent" || (s.elements_width >= 3 && s.elements_thickness >= 3)) return;
  for (const BodyConfig& b : cfg_.bodies)
    for (const MaterialConfig& m : cfg_.materials)
      if (m.name == b.material && m.model.find("plasticity") != std::string::npos)
        fail("'Mesh->Stent->" + std::string(s.elements_width < 3 ? "elements through width" : "elements through thickness") +
             "' = " + std::to_string(std::min(s.elements_width, s.elements_thickness)) + ": body '" + b.name +
             "' is plastic ('" + m.model + "'), which needs at least 3 cells through the strut's width and thickness");
}

// Exactly one of the sets C1 + D (+ C2), E + nu, mu + lambda (material/ElasticConstants.hpp).
void DeckReader::read_elastic_constants(const ParameterList& sub, const ListSpec& ls, const std::string& path,
                                        MaterialConfig& m) const {
  struct Set {
    const char* a;
    const char* b;
  };
  const Set sets[] = {{"C1", "D"}, {"E", "nu"}, {"mu", "lambda"}};
  const Set* given = nullptr;
  for (const Set& s : sets) {
    const bool ha = sub.isParameter(s.a), hb = sub.isParameter(s.b);
    if (!ha && !hb) continue;
    if (given)
      fail(quoted(path) + ": give exactly one set of elastic constants (C1 + D, E + nu, or mu + lambda), got both " +
           given->a + "/" + given->b + " and " + s.a + "/" + s.b);
    if (ha != hb) {
      const ParamSpec& missing = spec(ls, ha ? s.b : s.a);
      fail("missing required parameter " + quoted(path + "->" + missing.name) + " (double, " + missing.allowed_text() +
           "): '" + s.a + "' and '" + s.b + "' are given together");
    }
    given = &s;
  }
  const bool cg = m.ciarlet_geymonat();
  if (!given)
    fail(quoted(path) + " needs one set of elastic constants: " +
         (cg ? "C1 + D (+ C2), E + nu, or mu + lambda [stress]" : "E + nu or mu + lambda [stress]"));
  if (!cg && given == &sets[0])
    fail(quoted(path + "->" + (sub.isParameter("C1") ? "C1" : "D")) + " is a Ciarlet-Geymonat parameter; 'model' = " +
         m.model + " takes E + nu or mu + lambda");
  if ((m.neo_hookean() || m.model == "Holzapfel-Gasser-Ogden") && sub.isParameter("C2"))
    fail(quoted(path + "->C2") + " needs 'model' = Ciarlet-Geymonat or Mooney-Rivlin (" + m.model + " has no I2 term)");
  m.C2 = get_double(sub, ls, "C2");
  if (given == &sets[0]) {
    m.C1 = get_double(sub, ls, "C1");
    m.D = get_double(sub, ls, "D");
    m.mu = 2.0 * (m.C1 + m.C2);
    m.lambda = 4.0 * (m.C2 + m.D);
    return;
  }
  const Lame l = given == &sets[1] ? lame_from_young(get_double(sub, ls, "E"), get_double(sub, ls, "nu"))
                                   : Lame{get_double(sub, ls, "mu"), get_double(sub, ls, "lambda")};
  m.mu = l.mu;
  m.lambda = l.lambda;
  const std::string from = std::string(given->a) + "/" + given->b;
  if (m.model == "Mooney-Rivlin") {
    const MooneyRivlinCoefficients c = mooney_rivlin_from_lame(l, m.C2);
    m.C1 = c.C1;
    if (!(c.C1 > 0.0))
      fail(quoted(path) + ": C1 = mu/2 - C2 = " + num(c.C1) + " from " + from + " and 'C2' = " + num(m.C2) +
           "; Mooney-Rivlin needs C1 > 0 (lower 'C2' below mu/2 = " + num(0.5 * l.mu) + ")");
    if (!(c.lam >= 0.0))
      fail(quoted(path) + ": the volumetric coefficient lambda - 4 C2 = " + num(c.lam) + " from " + from + " and 'C2' = " +
           num(m.C2) + "; Mooney-Rivlin needs it >= 0 (lower 'C2' to at most lambda/4 = " + num(0.25 * l.lambda) + ")");
  }
  if (!cg) return;
  const CiarletGeymonatCoefficients c = ciarlet_geymonat_from_lame(l, m.C2);
  m.C1 = c.C1;
  m.D = c.D;
  if (!(m.C1 > 0.0))
    fail(quoted(path) + ": C1 = mu/2 - C2 = " + num(m.C1) + " from " + from + " and 'C2' = " + num(m.C2) +
         "; Ciarlet-Geymonat needs C1 > 0 (lower 'C2' below mu/2 = " + num(0.5 * l.mu) + ")");
  if (!(m.D > 0.0))
    fail(quoted(path) + ": D = lambda/4 - C2 = " + num(m.D) + " from " + from + " and 'C2' = " + num(m.C2) +
         "; Ciarlet-Geymonat needs D > 0 (nu > 0, and 'C2' below lambda/4 = " + num(0.25 * l.lambda) + ")");
}

// Holzapfel-Gasser-Ogden: k1, k2, fibre angle required, frame and kappa optional; none of them with other models.
void DeckReader::read_fibres(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) {
  const char* keys[] = {"k1", "k2", "fibre angle", "axis point", "axis", "kappa"};
  const bool hgo = m.model == "Holzapfel-Gasser-Ogden";
  for (const char* k : keys) {
    const std::string key(k);
    if (!hgo && sub.isParameter(k)) fail(quoted(path + "->" + k) + " needs 'model' = Holzapfel-Gasser-Ogden");
    if (hgo && key != "axis point" && key != "axis" && key != "kappa" && !sub.isParameter(k)) {
      const ParamSpec& p = spec(ls, k);
      fail("missing required parameter " + quoted(path + "->" + k) + " (double, " + p.allowed_text() +
           ") for model = Holzapfel-Gasser-Ogden: " + p.doc);
    }
  }
  if (!hgo) return;
  m.k1 = get_double(sub, ls, "k1");
  m.k2 = get_double(sub, ls, "k2");
  m.fibre_angle = get_double(sub, ls, "fibre angle");
  if (sub.isParameter("kappa")) m.kappa = get_double(sub, ls, "kappa");
  if (sub.isParameter("axis point")) {
    const auto p = get_array(sub, ls, "axis point");
    check_dim_length(p, path + "->axis point");
    for (std::size_t c = 0; c < p.size(); ++c) m.axis_point[c] = p[c];
  }
  if (sub.isParameter("axis")) {
    const auto a = get_array(sub, ls, "axis");
    for (std::size_t c = 0; c < 3; ++c) m.axis[c] = a[c];
    unit_direction(m.axis, path + "->axis");
  }
}

// The parameters of the laws with Gauss-point history: `yield stress` (required, > 0) and
// `hardening` and `plastic dynamic step` of the plasticity models, `saturation damage` and `damage energy scale`
// (both required) of neo-Hookean damage; none of them with another model.
void DeckReader::read_inelastic(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const {
  const auto needs = [&](const char* key, bool ok, const char* models) {
    if (!ok && sub.isParameter(key)) fail(quoted(path + "->" + key) + " needs 'model' = " + models);
  };
  const auto require_for_model = [&](const char* key) {
    if (sub.isParameter(key)) return;
    const ParamSpec& p = spec(ls, key);
    fail("missing required parameter " + quoted(path + "->" + key) + " (double, " + p.allowed_text() + ") for model = " +
         m.model);
  };
  needs("yield stress", m.plastic(), "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  needs("hardening", m.plastic(), "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  needs("plastic dynamic step", m.plastic(), "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  needs("saturation damage", m.damage(), "neo-Hookean damage");
  needs("damage energy scale", m.damage(), "neo-Hookean damage");
  if (m.plastic()) {
    read_hardening(sub, ls, path, m);
    m.plastic_dynamic_step = get_string(sub, ls, "plastic dynamic step");
  } else {
    for (const char* k : {"hardening law", "saturation stress", "saturation rate", "hardening table strains",
                          "hardening table stresses"})
      needs(k, false, "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  }
  if (m.damage()) {
    require_for_model("saturation damage");
    require_for_model("damage energy scale");
    m.saturation_damage = get_double(sub, ls, "saturation damage");
    m.damage_energy_scale = get_double(sub, ls, "damage energy scale");
  }
}

// The hardening of a plasticity model: `hardening law` linear (`yield stress`, `hardening`), Voce
// (+ `saturation stress` >= `yield stress`, `saturation rate`) or table (`hardening table strains`
// from 0, strictly increasing, and as many non-decreasing `hardening table stresses`, the first of
// which is the yield stress: `yield stress` and `hardening` are refused with it).
void DeckReader::read_hardening(const ParameterList& sub, const ListSpec& ls, const std::string& path,
                                MaterialConfig& m) const {
  m.hardening_law = get_string(sub, ls, "hardening law");
  const bool voce = m.hardening_law == "Voce", table = m.hardening_law == "table";
  const auto only = [&](const char* key, bool ok, const char* law) {
    if (!ok && sub.isParameter(key))
      fail(quoted(path + "->" + key) + " needs 'hardening law' = " + law + ", got " + m.hardening_law);
  };
  const auto required = [&](const char* key, bool with) {
    if (!with || sub.isParameter(key)) return;
    const ParamSpec& p = spec(ls, key);
    fail("missing required parameter " + quoted(path + "->" + key) + " (" + p.allowed_text() + ") for 'hardening law' = " +
         m.hardening_law);
  };
  only("saturation stress", voce, "Voce");
  only("saturation rate", voce, "Voce");
  only("hardening table strains", table, "table");
  only("hardening table stresses", table, "table");
  only("hardening", !table, "linear or Voce");
  if (table && sub.isParameter("yield stress"))
    fail(quoted(path + "->yield stress") + " is not allowed with 'hardening law' = table: the first of " +
         quoted(path + "->hardening table stresses") + " is the initial yield stress");
  for (const char* k : {"saturation stress", "saturation rate"}) required(k, voce);
  for (const char* k : {"hardening table strains", "hardening table stresses"}) required(k, table);
  if (!table) {
    if (!sub.isParameter("yield stress")) {
      const ParamSpec& p = spec(ls, "yield stress");
      fail("missing required parameter " + quoted(path + "->yield stress") + " (double, " + p.allowed_text() +
           ") for model = " + m.model);
    }
    m.yield_stress = get_double(sub, ls, "yield stress");
    m.hardening = get_double(sub, ls, "hardening");
  }
  if (voce) {
    m.saturation_stress = get_double(sub, ls, "saturation stress");
    m.saturation_rate = get_double(sub, ls, "saturation rate");
    if (m.saturation_stress < m.yield_stress)
      fail(quoted(path + "->saturation stress") + " = " + num(m.saturation_stress) + " is below " +
           quoted(path + "->yield stress") + " = " + num(m.yield_stress) +
           "; expected >= the yield stress (softening is not supported)");
  }
  if (table) {
    const std::string se = quoted(path + "->hardening table strains"), ss = quoted(path + "->hardening table stresses");
    m.table_strains = get_array(sub, ls, "hardening table strains");
    m.table_stresses = get_array(sub, ls, "hardening table stresses");
    if (m.table_strains.size() != m.table_stresses.size())
      fail(ss + " has " + std::to_string(m.table_stresses.size()) + " values and " + se + " " +
           std::to_string(m.table_strains.size()) + "; expected one stress per strain");
    if (m.table_strains[0] != 0.0) fail(se + " must start at 0, got " + num(m.table_strains[0]));
    for (std::size_t i = 1; i < m.table_strains.size(); ++i) {
      if (!(m.table_strains[i] > m.table_strains[i - 1]))
        fail(se + " must be strictly increasing, got " + num(m.table_strains[i]) + " after " + num(m.table_strains[i - 1]));
      if (m.table_stresses[i] < m.table_stresses[i - 1])
        fail(ss + " must be non-decreasing (softening is not supported), got " + num(m.table_stresses[i]) + " after " +
             num(m.table_stresses[i - 1]) + " at strain " + num(m.table_strains[i]));
    }
    m.yield_stress = m.table_stresses[0];
    m.hardening = 0.0;
  }
}

void DeckReader::read_materials(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Materials");
  const ListSpec& ls = deck_list_spec("Materials/*");
  check_list(pl, "Materials", {&top});
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Materials->" + name;
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    require(sub, path, {&ls});
    MaterialConfig m;
    m.name = name;
    m.model = get_string(sub, ls, "model");
    read_elastic_constants(sub, ls, path, m);
    // 1e308 is a double, but the law's moduli from it are not (the run checks the stiffness
    // itself; this names it here, under --check too).
    if (!std::isfinite(m.mu) || !std::isfinite(m.lambda))
      fail(quoted(path) + ": the elastic constants overflow double precision (small-strain mu = " + num(m.mu) + ", lambda = " +
           num(m.lambda) + "); expected smaller values (a deck in smaller units, e.g. mm-N-s with moduli in MPa, helps)");
    read_fibres(sub, ls, path, m);
    m.density = get_double(sub, ls, "density");
    m.viscosity = get_double(sub, ls, "viscosity");
    read_inelastic(sub, ls, path, m);
    cfg_.materials.push_back(m);
  }
  if (cfg_.materials.empty()) fail("'Materials' defines no material; add one sublist per material");
}

// A body's own initial rotation and displacement (its "initial velocity" is read above).
void DeckReader::read_body_initial_state(const ParameterList& sub, const std::string& path, BodyConfig& b) {
  const ListSpec& ls = deck_list_spec("Bodies/*");
  const bool w = sub.isParameter("initial angular velocity"), c = sub.isParameter("rotation center");
  if (w != c)
    fail(quoted(path + (w ? "->rotation center" : "->initial angular velocity")) + " is required with " +
         quoted(path + (w ? "->initial angular velocity" : "->rotation center")));
  if (w) {
    const auto a = get_array(sub, ls, "initial angular velocity");
    if (a.size() != 1 && a.size() != 3)
      fail(quoted(path + "->initial angular velocity") + " must have 1 value (2D, about z) or 3 values (3D), got " + std::to_string(a.size()));
    check_dim_length(a, path + "->initial angular velocity", 1, 3);
    if (a.size() == 1)
      b.angular_velocity[2] = a[0];
    else
      for (std::size_t k = 0; k < 3; ++k) b.angular_velocity[k] = a[k];
    const auto x = get_array(sub, ls, "rotation center");
    check_dim_length(x, path + "->rotation center");
    for (std::size_t k = 0; k < x.size() && k < 3; ++k) b.center[k] = x[k];
    b.has_angular_velocity = true;
  }
  if (sub.isParameter("initial displacement")) {
    const auto d = get_array(sub, ls, "initial displacement");
    check_dim_length(d, path + "->initial displacement");
    for (std::size_t k = 0; k < d.size() && k < 3; ++k) b.displacement[k] = d[k];
    b.has_displacement = true;
  }
}

void DeckReader::read_bodies(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Bodies");
  const ListSpec& ls = deck_list_spec("Bodies/*");
  check_list(pl, "Bodies", {&top});
  std::vector<std::string> defined;
  for (const auto& m : cfg_.materials) defined.push_back(m.name);
  std::map<std::string, std::string> group_owner;
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Bodies->" + name;
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    require(sub, path, {&ls});
    BodyConfig b;
    b.name = name;
    b.group = sub.isParameter("physical group") ? get_string(sub, ls, "physical group") : name;
    if (b.group.empty()) fail(quoted(path + "->physical group") + " must not be empty");
    b.material = get_string(sub, ls, "material");
    b.element_technology = get_string(sub, ls, "element technology");
    if (sub.isParameter("initial velocity")) {
      const auto v = get_array(sub, ls, "initial velocity");
      check_dim_length(v, path + "->initial velocity");
      b.has_velocity = true;
      for (std::size_t k = 0; k < v.size() && k < 3; ++k) b.velocity[k] = v[k];
    }
    read_body_initial_state(sub, path, b);
    if (std::find(defined.begin(), defined.end(), b.material) == defined.end()) {
      std::string msg = quoted(path + "->material") + " names undefined material '" + b.material +
                        "'; defined materials: " + join(defined);
      const std::string near = nearest_name(b.material, defined);
      if (!near.empty()) msg += "; did you mean '" + near + "'?";
      fail(msg);
    }
    const auto [pos, fresh] = group_owner.emplace(b.group, name);
    if (!fresh)
      fail("'Bodies->" + pos->second + "' and " + quoted(path) + " both use physical group '" + b.group +
           "'; a physical group belongs to one body");
    cfg_.bodies.push_back(b);
  }
  if (cfg_.bodies.empty()) fail("'Bodies' defines no body; add one sublist per body");
}

Ramp DeckReader::read_ramp(const ParameterList& pl, const std::string& path, const ListSpec& ls, const std::string& key) const {
  Ramp r;
  const std::string kt = key + " times", kf = key + " factors";
  const std::string kind = get_string(pl, ls, key);
  const bool has_t = pl.isParameter(kt), has_f = pl.isParameter(kf);
  if (kind != "table") {
    r.kind = kind == "constant" ? Ramp::Kind::Constant : Ramp::Kind::Linear;
    if (has_t || has_f)
      fail(quoted(path + "->" + (has_t ? kt : kf)) + " is only used with \"" + key + "\" = table (" + key + " is " + kind + ")");
    return r;
  }
  r.kind = Ramp::Kind::Table;
  if (!has_t) fail("missing required parameter " + quoted(path + "->" + kt) + " (Array(double)) for \"" + key + "\" = table");
  if (!has_f) fail("missing required parameter " + quoted(path + "->" + kf) + " (Array(double)) for \"" + key + "\" = table");
  r.times = get_array(pl, ls, kt);
  r.factors = get_array(pl, ls, kf);
  if (r.times.size() != r.factors.size())
    fail(quoted(path + "->" + kf) + " must have as many values as '" + kt + "' (" + std::to_string(r.times.size()) + "), got " +
         std::to_string(r.factors.size()));
  for (std::size_t i = 1; i < r.times.size(); ++i)
    if (!(r.times[i] > r.times[i - 1]))
      fail(quoted(path + "->" + kt) + " must be strictly increasing, got " + num(r.times[i - 1]) + " then " + num(r.times[i]) +
           " at positions " + std::to_string(i) + ", " + std::to_string(i + 1));
  return r;
}

// "axis" (cylinder: 3 values; capsule: one per dimension) and "length" (capsule).
void DeckReader::read_obstacle_axis(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c) {
  const bool cyl = c.obstacle == "cylinder", cap = c.obstacle == "capsule";
  if (!cyl && !cap) {
    if (sub.isParameter("axis")) fail(quoted(path + "->axis") + " is only used by cylinder and capsule obstacles");
    if (sub.isParameter("length")) fail(quoted(path + "->length") + " is only used by a capsule obstacle");
    return;
  }
  if (!sub.isParameter("axis"))
    fail("missing required parameter " + quoted(path + "->axis") + " (Array(double), " + (cyl ? "3 values" : "one value per dimension") +
         ") for a " + c.obstacle + " obstacle");
  const auto a = get_array(sub, ls, "axis");
  c.axis_len = static_cast<int>(a.size());
  if (cyl && a.size() != 3) fail(quoted(path + "->axis") + " must have 3 values for a cylinder obstacle, got " + std::to_string(a.size()));
  if (cap && c.axis_len != c.point_len)
    fail(quoted(path + "->axis") + " must have as many values as 'point' (" + std::to_string(c.point_len) + ")");
  for (std::size_t k = 0; k < a.size(); ++k) c.axis[k] = a[k];
  unit_direction(c.axis, path + "->axis");
  if (cyl) {
    if (sub.isParameter("length")) fail(quoted(path + "->length") + " is only used by a capsule obstacle");
    return;
  }
  if (!sub.isParameter("length")) fail("missing required parameter " + quoted(path + "->length") + " (double, >= 0) for a capsule obstacle");
  c.length = get_double(sub, ls, "length");
}

void DeckReader::read_contact_obstacle(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c) {
  c.obstacle = get_string(sub, ls, "obstacle");
  if (c.obstacle != "plane" && c.obstacle != "circle" && c.obstacle != "cylinder" && c.obstacle != "sphere" && c.obstacle != "capsule")
    fail(quoted(path + "->obstacle") + " must be one of 'plane', 'circle', 'cylinder', 'sphere', 'capsule', got '" + c.obstacle + "'");
  const bool curved = c.obstacle != "plane";
  auto vec = [&](const std::string& key, std::array<double, 3>& out, int& len) {
    const auto v = get_array(sub, ls, key);
    check_dim_length(v, path + "->" + key);
    len = static_cast<int>(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) out[k] = v[k];
  };
  if (!sub.isParameter("point")) fail("missing required parameter " + quoted(path + "->point") + " (Array(double)) for an obstacle");
  vec("point", c.point, c.point_len);
  const int dim = cfg_.mesh.dimension;
  if (c.obstacle == "plane") {
    if (!sub.isParameter("normal")) fail("missing required parameter " + quoted(path + "->normal") + " (Array(double)) for a plane obstacle");
    vec("normal", c.normal, c.normal_len);
    unit_direction(c.normal, path + "->normal");
    if (c.normal_len != c.point_len)
      fail(quoted(path + "->normal") + " must have as many values as 'point' (" + std::to_string(c.point_len) + ")");
    for (const char* k : {"radius", "radius change", "axis", "side", "length"})
      if (sub.isParameter(k)) fail(quoted(path + "->" + k) + " is not used by a plane obstacle");
  } else {
    if (!sub.isParameter("radius"))
      fail("missing required parameter " + quoted(path + "->radius") + " (double, > 0) for a " + c.obstacle + " obstacle");
    c.radius = get_double(sub, ls, "radius");
    c.side = get_string(sub, ls, "side");
    if (sub.isParameter("normal")) fail(quoted(path + "->normal") + " is only used by a plane obstacle");
    if (c.obstacle == "circle" && (dim == 3 || c.point_len == 3))
      fail(quoted(path + "->obstacle") + " = circle is 2D only; use cylinder or sphere in 3D");
    if ((c.obstacle == "cylinder" || c.obstacle == "sphere") && (dim == 2 || c.point_len == 2))
      fail(quoted(path + "->obstacle") + " = " + c.obstacle + " is 3D only; use circle in 2D" +
           (cfg_.problem.axisymmetric() ? std::string(" (in axisymmetry a cylinder about the axis is a `plane` with normal (1, 0) or "
                                                      "(-1, 0), a sphere a `circle` centred on the axis, a balloon a `capsule` along it)")
                                        : std::string("")));
    read_obstacle_axis(sub, path, ls, c);
  }
  int tl = 0;
  if (sub.isParameter("translation")) {
    vec("translation", c.translation, tl);
    if (tl != c.point_len) fail(quoted(path + "->translation") + " must have as many values as 'point' (" + std::to_string(c.point_len) + ")");
  }
  c.translation_ramp = read_ramp(sub, path, ls, "translation ramp");
  c.radius_change = get_double(sub, ls, "radius change");
  c.radius_ramp = read_ramp(sub, path, ls, "radius ramp");
  if (!curved && (sub.isParameter("radius ramp") || sub.isParameter("radius ramp times")))
    fail(quoted(path + "->radius ramp") + " is not used by a plane obstacle");
}

void DeckReader::read_contact(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Contact");
  const ListSpec& ls = deck_list_spec("Contact/*");
  check_list(pl, "Contact", {&top});
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Contact->" + name;
    check_safe_name(name, path, "the contact pair name");
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    require(sub, path, {&ls});
    ContactPairConfig c;
    c.name = name;
    c.slave = get_string(sub, ls, "slave");
    if (c.slave.empty()) fail(quoted(path + "->slave") + " must name a boundary physical group");
    const bool has_obstacle = sub.isParameter("obstacle"), has_master = sub.isParameter("master");
    if (has_obstacle == has_master)
      fail(quoted(path) + " needs exactly one of 'obstacle' (a rigid analytic surface) and 'master' (a boundary group of a "
           "deformable body)" + (has_obstacle ? std::string(", not both") : std::string("")));
    if (has_master) {
      c.master = get_string(sub, ls, "master");
      if (c.master.empty()) fail(quoted(path + "->master") + " must name a boundary physical group");
      if (c.master == c.slave) fail(quoted(path + "->master") + " names the slave group '" + c.slave + "'; self-contact is not supported");
      for (const char* k : {"point", "normal", "axis", "length", "radius", "side", "translation", "translation ramp", "translation ramp times",
                            "translation ramp factors", "radius change", "radius ramp", "radius ramp times", "radius ramp factors"})
        if (sub.isParameter(k)) fail(quoted(path + "->" + k) + " describes a rigid obstacle; a pair with 'master' has none");
    } else {
      read_contact_obstacle(sub, path, ls, c);
    }
    c.friction = get_double(sub, ls, "friction");
    c.c_normal = get_double(sub, ls, "c normal");
    c.c_tangent = get_double(sub, ls, "c tangent");
    c.formulation = get_string(sub, ls, "formulation");
    c.discretization = get_string(sub, ls, "discretization");
    c.linearised_sets = get_string(sub, ls, "set update") == "linearised";
    if (c.discretization == "mortar" && !has_master)
      fail(quoted(path + "->discretization") + " = mortar couples two meshed surfaces; it needs 'master' (a rigid obstacle is "
           "exact at every slave node already)");
    cfg_.contact.push_back(c);
  }
  if (cfg_.contact.empty()) fail("'Contact' defines no contact pair; add one sublist per pair or remove 'Contact'");
}

// A fluid cavity (LoadConfig::FluidCavity): 3D only (checked with the mesh, bc/Loads.cpp) and
// static stages only (check_analysis).
void DeckReader::read_fluid_cavity(const ParameterList& sub, const ListSpec& ls, const std::string& path, LoadConfig& lc) {
  lc.type = LoadConfig::Type::FluidCavity;
  lc.group = get_string(sub, ls, "boundary");
  lc.volume_ratio = get_double(sub, ls, "volume ratio");
  lc.bulk_modulus = get_double(sub, ls, "bulk modulus");
  const auto point = get_array(sub, ls, "axis point"), axis = get_array(sub, ls, "axis");
  if (point.size() != 3) fail(quoted(path + "->axis point") + " must have 3 values (a fluid cavity is 3D), got " + std::to_string(point.size()));
  if (axis.size() != 3) fail(quoted(path + "->axis") + " must have 3 values (a fluid cavity is 3D), got " + std::to_string(axis.size()));
  for (std::size_t c = 0; c < 3; ++c) lc.axis_point[c] = point[c], lc.axis[c] = axis[c];
  unit_direction(lc.axis, path + "->axis");
}

void DeckReader::read_loads(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Boundary Conditions");
  const ListSpec& common = deck_list_spec("Boundary Conditions/*");
  const std::vector<std::string> types = spec(common, "type").choices;
  check_list(pl, "Boundary Conditions", {&top});
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Boundary Conditions->" + name;
    check_safe_name(name, path, "the load name");
    const ParameterList& sub = pl.sublist(name);
    if (!sub.isParameter("type"))
      fail("missing required parameter " + quoted(path + "->type") + " (string, one of " + join(types) + ")");
    check_param(sub.getEntry("type"), path + "->type", spec(common, "type"));
    const std::string type = get_string(sub, common, "type");
    const ListSpec& typed = deck_list_spec("Boundary Conditions/*/" + type);
    // A parameter of another load type gets a specific message.
    for (auto jt = sub.begin(); jt != sub.end(); ++jt) {
      const std::string& pn = sub.name(jt);
      if (common.find(pn) || typed.find(pn)) continue;
      for (const auto& other : types)
        if (other != type && deck_list_spec("Boundary Conditions/*/" + other).find(pn)) {
          std::vector<std::string> valid;
          for (const auto& p : typed.params) valid.push_back(p.name);
          for (const auto& p : common.params) valid.push_back(p.name);
          fail("unknown parameter " + quoted(path + "->" + pn) + " for a load of type '" + type + "' ('" + pn +
               "' belongs to type '" + other + "'); a " + type + " load takes: " + join(valid));
        }
    }
    check_list(sub, path, {&common, &typed});
    require(sub, path, {&common, &typed});

    LoadConfig lc;
    lc.name = name;
    lc.ramp = read_ramp(sub, path, common);
    if (type == "Dirichlet") {
      lc.type = LoadConfig::Type::Dirichlet;
      lc.group = get_string(sub, typed, "boundary");
      const std::string comp = get_string(sub, typed, "components");
      const std::string cpath = path + "->components";
      std::string tokens = comp;
      std::replace(tokens.begin(), tokens.end(), ',', ' ');
      std::istringstream is(tokens);
      std::string tok;
      std::vector<int> listed;
      bool all = false;
      const std::string expect = " must list components x, y, z (separated by spaces or commas) or be 'all' or 'normal'";
      bool normal = false;
      while (is >> tok) {
        const std::string t = lower(tok);
        if (t == "all") {
          all = true;
          continue;
        }
        if (t == "normal") {
          normal = true;
          continue;
        }
        if (t != "x" && t != "y" && t != "z") fail(quoted(cpath) + expect + "; got '" + comp + "' ('" + tok + "' is not a component)");
        const int c = t[0] - 'x';
        if (std::find(listed.begin(), listed.end(), c) != listed.end())
          fail(quoted(cpath) + " lists '" + tok + "' twice; got '" + comp + "'");
        listed.push_back(c);
      }
      if (all && !listed.empty()) fail(quoted(cpath) + ": 'all' cannot be combined with other components; got '" + comp + "'");
      if (normal && (all || !listed.empty()))
        fail(quoted(cpath) + ": 'normal' cannot be combined with other components; got '" + comp + "'");
      if (normal) {
        // The displacement along the boundary's unit outward normal (Loads: the group must be planar).
        lc.normal = true;
        if (sub.isParameter("values")) {
          const auto v = get_array(sub, typed, "values");
          if (v.size() != 1)
            fail(quoted(path + "->values") + " must have one value (the displacement along the normal) for components 'normal', got " +
                 std::to_string(v.size()));
          lc.value = v[0];
        }
        cfg_.loads.push_back(lc);
        continue;
      }
      if (!all && listed.empty()) fail(quoted(cpath) + expect + "; got '" + comp + "'");
      const int dim = cfg_.mesh.dimension;
      if (dim == 2 && std::find(listed.begin(), listed.end(), 2) != listed.end())
        fail(quoted(cpath) + ": 'z' is not a component of a 2D problem ('Mesh->dimension' = 2)");
      lc.all_components = all;
      if (all) {
        lc.components = {true, true, dim != 2};
      } else {
        for (int c : listed) lc.components[static_cast<std::size_t>(c)] = true;
      }
      if (sub.isParameter("values")) {
        const auto v = get_array(sub, typed, "values");
        const std::string vpath = path + "->values";
        if (all) {
          if (v.size() < 2 || v.size() > 3)
            fail(quoted(vpath) + " must have one value per dimension (2 or 3) for components 'all', got " + std::to_string(v.size()));
          check_dim_length(v, vpath);
          for (std::size_t c = 0; c < v.size(); ++c) lc.vector[c] = v[c];
        } else {
          if (v.size() != listed.size())
            fail(quoted(vpath) + " must have one value per listed component (" + std::to_string(listed.size()) + " for '" +
                 comp + "'), got " + std::to_string(v.size()));
          for (std::size_t k = 0; k < listed.size(); ++k) lc.vector[static_cast<std::size_t>(listed[k])] = v[k];
        }
      }
    } else if (type == "traction") {
      lc.type = LoadConfig::Type::Traction;
      lc.group = get_string(sub, typed, "boundary");
      const auto v = get_array(sub, typed, "traction");
      check_dim_length(v, path + "->traction");
      for (std::size_t c = 0; c < v.size(); ++c) lc.vector[c] = v[c];
    } else if (type == "pressure") {
      lc.type = LoadConfig::Type::Pressure;
      lc.group = get_string(sub, typed, "boundary");
      lc.value = get_double(sub, typed, "pressure");
    } else if (type == "fluid cavity") {
      read_fluid_cavity(sub, typed, path, lc);
    } else {  // body force
      lc.type = LoadConfig::Type::BodyForce;
      const auto v = get_array(sub, typed, "force");
      check_dim_length(v, path + "->force");
      for (std::size_t c = 0; c < v.size(); ++c) lc.vector[c] = v[c];
      const std::string body = get_string(sub, typed, "body");
      if (!body.empty()) {
        // A body's name or its physical group; stored as the physical group.
        std::vector<std::string> names;
        for (const auto& b : cfg_.bodies) {
          if (b.name == body || b.group == body) lc.group = b.group;
          names.push_back(b.name);
        }
        if (lc.group.empty()) {
          std::string msg = quoted(path + "->body") + " names undefined body '" + body + "'; defined bodies: " + join(names);
          const std::string near = nearest_name(body, names);
          if (!near.empty()) msg += "; did you mean '" + near + "'?";
          fail(msg);
        }
      }
    }
    cfg_.loads.push_back(lc);
  }
}

void DeckReader::read_initial(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Initial Conditions");
  check_list(pl, "Initial Conditions", {&ls});
  auto& ic = cfg_.initial;
  if (pl.isParameter("displacement")) {
    const auto d = get_array(pl, ls, "displacement");
    check_dim_length(d, "Initial Conditions->displacement");
    for (std::size_t c = 0; c < d.size(); ++c) ic.displacement[c] = d[c];
  }
  if (pl.isParameter("velocity")) {
    const auto v = get_array(pl, ls, "velocity");
    check_dim_length(v, "Initial Conditions->velocity");
    for (std::size_t c = 0; c < v.size(); ++c) ic.velocity[c] = v[c];
  }
  if (pl.isParameter("angular velocity")) {
    const auto w = get_array(pl, ls, "angular velocity");
    if (w.size() != 1 && w.size() != 3)
      fail("'Initial Conditions->angular velocity' must have 1 value (2D, about z) or 3 values (3D), got " +
           std::to_string(w.size()));
    check_dim_length(w, "Initial Conditions->angular velocity", 1, 3);
    if (w.size() == 1) {
      ic.angular_velocity[2] = w[0];
    } else {
      for (std::size_t c = 0; c < 3; ++c) ic.angular_velocity[c] = w[c];
    }
  }
  if (pl.isParameter("center")) {
    const auto c = get_array(pl, ls, "center");
    check_dim_length(c, "Initial Conditions->center");
    for (std::size_t k = 0; k < c.size(); ++k) ic.center[k] = c[k];
  }
}

void DeckReader::read_time(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Time Integration");
  check_list(pl, "Time Integration", {&ls});
  cfg_.time.scheme = get_string(pl, ls, "scheme");
  cfg_.time.hht_alpha = get_double(pl, ls, "hht alpha");
}

void DeckReader::read_stepping(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Stepping");
  check_list(pl, "Stepping", {&ls});
  cfg_.stepping.end_time = get_double(pl, ls, "end time");
  cfg_.stepping.num_steps = get_int(pl, ls, "steps");
  cfg_.stepping.max_cutbacks = get_int(pl, ls, "max cutbacks");
  cfg_.stepping.growth = get_double(pl, ls, "growth");
  cfg_.stepping.target_iterations = get_int(pl, ls, "target iterations");
  if (cfg_.stepping.target_iterations > 0 && cfg_.stepping.target_iterations < 4)
    fail("'Stepping->target iterations' = " + std::to_string(cfg_.stepping.target_iterations) +
         ": must be 0 (off) or at least 4 (a Newton solve to the tolerances takes 2 to 3 iterations, so a smaller target "
         "would shrink every step)");
  cfg_.stepping.predictor = get_string(pl, ls, "predictor");
  cfg_.stepping.stabilization = get_double(pl, ls, "stabilization");
  cfg_.stepping.min_dt = get_double(pl, ls, "min dt");
  cfg_.stepping.max_steps = get_int(pl, ls, "max steps");
}

void DeckReader::read_newton(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Newton");
  check_list(pl, "Newton", {&ls});
  auto& n = cfg_.newton;
  n.max_iterations = get_int(pl, ls, "max iterations");
  n.residual_tolerance = get_double(pl, ls, "relative residual tolerance");
  n.residual_tolerance_given = pl.isParameter("relative residual tolerance");
  n.absolute_tolerance = get_double(pl, ls, "absolute residual tolerance");
  n.increment_tolerance = get_double(pl, ls, "increment tolerance");
  n.line_search = get_bool(pl, ls, "line search");
  n.line_search_max = get_int(pl, ls, "line search max halvings");
  n.line_search_watchdog = get_int(pl, ls, "line search watchdog");
  n.forcing = get_string(pl, ls, "forcing");
  n.forcing_max = get_double(pl, ls, "forcing max");
  n.max_increment = get_double(pl, ls, "max increment");
}

void DeckReader::read_linear(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Linear Solver");
  check_list(pl, "Linear Solver", {&ls});
  auto& l = cfg_.linear;
  l.method = get_string(pl, ls, "method");
  l.direct_solver = get_string(pl, ls, "direct solver");
  l.preconditioner = get_string(pl, ls, "preconditioner");
  l.tolerance = get_double(pl, ls, "tolerance");
  l.max_iterations = get_int(pl, ls, "max iterations");
  l.restart = get_int(pl, ls, "restart");
  l.overlap = get_int(pl, ls, "overlap");
  l.subdomain_solver = get_string(pl, ls, "subdomain solver");
  l.fill_level = get_int(pl, ls, "fill level");
  l.preconditioner_reuse = get_int(pl, ls, "preconditioner reuse");
  l.preconditioner_rebuild_cost = get_double(pl, ls, "preconditioner rebuild cost");
  l.preconditioner_rebuild_on_change = get_bool(pl, ls, "preconditioner rebuild on contact change");
#ifndef STENTOR_HAVE_MUELU
  if (l.preconditioner == "muelu")
    fail("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
#endif
#ifndef STENTOR_HAVE_AMESOS2
  if (l.method == "direct" && l.direct_solver != "mumps")
    fail("'Linear Solver->method' = direct needs Trilinos with Amesos2 for KLU2, which this build lacks; use gmres, or "
         "'direct solver' = mumps");
  if (l.subdomain_solver == "KLU2")
    fail("'Linear Solver->subdomain solver' = KLU2 needs Trilinos with Amesos2, which this build lacks; use RILUK or ILUT");
#endif
  auto xml_of = [&](const char* name) -> std::string {
    if (!pl.isSublist(name)) return "";
    ParameterList copy = pl.sublist(name);
    copy.setName(name);
    std::ostringstream os;
    Teuchos::writeParameterListToXmlOStream(copy, os);
    return os.str();
  };
  l.belos_xml = xml_of("Belos");
  l.ifpack2_xml = xml_of("Ifpack2");
  l.muelu_xml = xml_of("MueLu");
  l.amesos2_xml = xml_of("Amesos2");
}

void DeckReader::read_output(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Output");
  check_list(pl, "Output", {&ls});
  auto& o = cfg_.output;
  o.directory = get_string(pl, ls, "directory");
  o.basename = get_string(pl, ls, "basename");
  o.every = get_int(pl, ls, "every");
  o.fields = get_bool(pl, ls, "fields");
  o.field_list = get_string(pl, ls, "field list");
  o.times = get_array(pl, ls, "times");
  o.interval = get_double(pl, ls, "interval");
  for (const char* p : {"field list", "times", "interval"})
    if (!o.fields && pl.isParameter(p))
      fail("'Output->" + std::string(p) + "' is given but 'Output->fields' is false (no fields are written)");
  o.checkpoint_every = get_int(pl, ls, "checkpoint every");
  if (o.directory.empty()) fail("'Output->directory' must not be empty");
  if (o.basename.empty()) fail("'Output->basename' must not be empty");
  if (o.basename.find('/') != std::string::npos)
    fail("'Output->basename' must be a file name stem without '/', got '" + o.basename + "'");
  check_safe_name(o.basename, "Output->basename", "the file name stem");
  if (pl.isSublist("Probes")) {
    const ParameterList& probes = pl.sublist("Probes");
    const ListSpec& pls = deck_list_spec("Output/Probes/*");
    check_list(probes, "Output->Probes", {&deck_list_spec("Output/Probes")});
    for (auto it = probes.begin(); it != probes.end(); ++it) {
      const std::string& name = probes.name(it);
      const std::string path = "Output->Probes->" + name;
      check_safe_name(name, path, "the probe name");
      const ParameterList& sub = probes.sublist(name);
      check_list(sub, path, {&pls});
      require(sub, path, {&pls});
      ProbeConfig p;
      p.name = name;
      const auto v = get_array(sub, pls, "point");
      check_dim_length(v, path + "->point");
      for (std::size_t c = 0; c < v.size(); ++c) p.point[c] = v[c];
      o.probes.push_back(p);
    }
  }
  if (pl.isSublist("Stent Metrics")) read_stent_metrics(pl.sublist("Stent Metrics"));
}

void DeckReader::resolve_output() {
  OutputConfig& o = cfg_.output;
  OutputDeckTraits traits;
  traits.dynamic = cfg_.any_dynamic();
  traits.contact = !cfg_.contact.empty();
  for (const auto& c : cfg_.contact) traits.master_surface |= !c.master.empty();
  traits.stent_in_artery = cfg_.mesh.generator == "stent" && cfg_.mesh.artery.around_stent && o.metrics.enabled;
  for (const auto& b : cfg_.bodies)
    for (const auto& m : cfg_.materials)
      if (m.name == b.material) {
        traits.plastic |= m.plastic();
        traits.damage |= m.damage();
      }
  try {
    o.field_names = o.fields ? resolve_output_fields(o.field_list, traits) : std::vector<std::string>{};
  } catch (const std::invalid_argument& e) {
    fail("'Output->field list' " + std::string(e.what()) + "; got '" + o.field_list + "'");
  }
  const double end = cfg_.stepping.end_time;
  for (std::size_t i = 0; i < o.times.size(); ++i) {
    const double t = o.times[i];
    if (!(t > 0.0) || t > end * (1.0 + 1e-12))
      fail("'Output->times' must lie in (0, end time = " + num(end) + "], got " + num(t) + " at position " + std::to_string(i + 1));
    if (i > 0 && !(t > o.times[i - 1]))
      fail("'Output->times' must be strictly increasing, got " + num(o.times[i - 1]) + " then " + num(t) + " at positions " +
           std::to_string(i) + ", " + std::to_string(i + 1));
  }
  merge_output_interval(o, end);
}

// Output->interval: its multiples in (0, end] merged into Output->times (sorted; a multiple
// within 1e-10 end time of a given time is the same output).
void DeckReader::merge_output_interval(OutputConfig& o, double end) const {
  if (!(o.interval > 0.0)) return;
  const double count = std::floor(end / o.interval * (1.0 + 1e-12));
  if (count > 100000.0)
    fail("'Output->interval' = " + num(o.interval) + " would write " + num(count) + " field outputs over the end time " + num(end) +
         " (at most 100,000); raise it");
  std::vector<double> all = o.times;
  for (long k = 1; k <= static_cast<long>(count); ++k) all.push_back(std::min(end, static_cast<double>(k) * o.interval));
  std::sort(all.begin(), all.end());
  const double tol = 1e-10 * end;
  o.times.clear();
  for (double t : all)
    if (o.times.empty() || t > o.times.back() + tol) o.times.push_back(t);
}

void DeckReader::read_stent_metrics(const ParameterList& sub) {
  const std::string path = "Output->Stent Metrics";
  const ListSpec& ls = deck_list_spec("Output/Stent Metrics");
  check_list(sub, path, {&ls});
  require(sub, path, {&ls});
  StentMetricsConfig& m = cfg_.output.metrics;
  m.enabled = true;
  m.end_fraction = get_double(sub, ls, "end fraction");
  m.malapposition_threshold = get_double(sub, ls, "malapposition threshold");
  if (sub.isParameter("malapposition threshold") && !(cfg_.mesh.generator == "stent" && cfg_.mesh.artery.around_stent))
    fail(quoted(path + "->malapposition threshold") + " applies to a generated stent in a generated artery ('Mesh->generator' = "
         "stent with 'Mesh->Artery'); this deck has none: remove it");
  const char* named[] = {"axis point", "axis", "stent", "lumen", "artery"};
  if (cfg_.mesh.generator == "stent") {
    // The generated stent's axis is z through the origin and its groups are the generator's.
    for (const char* n : named)
      if (sub.isParameter(n))
        fail(quoted(path + "->" + n) + ": not with 'Mesh->generator' = stent (the metrics take the generated "
             "stent's axis, the z axis through the origin, and its groups); remove it");
    m.axis = {0.0, 0.0, 1.0};
    return;
  }
  for (const char* n : named)
    if (!sub.isParameter(n))
      fail("missing required parameter " + quoted(path + "->" + n) + " (required unless 'Mesh->generator' = stent: "
           "the metrics of a mesh file name the vessel axis and the groups 'stent', 'lumen', 'artery')");
  const auto p = get_array(sub, ls, "axis point");
  check_dim_length(p, path + "->axis point");
  for (std::size_t c = 0; c < p.size(); ++c) m.axis_point[c] = p[c];
  const auto a = get_array(sub, ls, "axis");
  for (std::size_t c = 0; c < 3; ++c) m.axis[c] = a[c];
  unit_direction(m.axis, path + "->axis");
  m.stent = get_string(sub, ls, "stent");
  m.lumen = get_string(sub, ls, "lumen");
  m.artery = get_string(sub, ls, "artery");
  for (const std::string* g : {&m.stent, &m.lumen, &m.artery})
    if (g->empty()) fail(quoted(path) + ": 'stent', 'lumen' and 'artery' must name physical groups");
}

// ------------------------------------------------------------------------------------
// Stages: a procedure of consecutive intervals. Each load's and obstacle's ramp becomes
// one Ramp::Piece per stage (stage-local time; held or off where not active).

std::vector<bool> DeckReader::read_active(const ParameterList& sub, const std::string& path, const std::string& key,
                                          const std::vector<std::string>& names, const std::string& what) const {
  const ListSpec& ls = deck_list_spec("Stages/*");
  const std::string text = get_string(sub, ls, key), kpath = path + "->" + key;
  if (lower(trim(text)) == "all") return std::vector<bool>(names.size(), true);
  std::vector<bool> active(names.size(), false);
  if (lower(trim(text)) == "none") return active;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const std::string n = trim(item);
    if (n.empty()) fail(quoted(kpath) + " must be 'all', 'none' or names separated by commas; got '" + text + "'");
    const auto it = std::find(names.begin(), names.end(), n);
    if (it == names.end()) {
      std::string msg = quoted(kpath) + " names undefined " + what + " '" + n + "'; defined: " + (names.empty() ? "(none)" : join(names));
      const std::string near = nearest_name(n, names);
      if (!near.empty()) msg += "; did you mean '" + near + "'?";
      fail(msg);
    }
    const auto i = static_cast<std::size_t>(it - names.begin());
    if (active[i]) fail(quoted(kpath) + " lists '" + n + "' twice");
    active[i] = true;
  }
  return active;
}

namespace {
Ramp::Piece piece_of(const Ramp& r, const StageConfig& st) {
  Ramp::Piece p;
  p.start = st.start;
  p.end = st.end;
  p.kind = r.kind;
  p.times = r.times;
  p.factors = r.factors;
  return p;
}
// The factor at the end of a piece.
double end_value(const Ramp::Piece& p) {
  Ramp r;
  r.stages = {p};
  return r(p.end, p.end);
}
}  // namespace

// "Ramps" of stage k: ramp overrides (stage-local time) of active loads and obstacles,
// written into the k-th piece of their ramps.
void DeckReader::read_stage_ramps(const ParameterList& sub, const std::string& path, std::size_t k) {
  const ListSpec& ls = deck_list_spec("Stages/*/Ramps/*");
  const StageConfig& st = cfg_.stages[k];
  check_list(sub, path, {&deck_list_spec("Stages/*/Ramps")});
  for (auto it = sub.begin(); it != sub.end(); ++it) {
    const std::string& name = sub.name(it);
    const std::string p = path + "->" + name;
    const ParameterList& r = sub.sublist(name);
    check_list(r, p, {&ls});
    int load = -1, pair = -1;
    for (std::size_t i = 0; i < cfg_.loads.size(); ++i)
      if (cfg_.loads[i].name == name) load = static_cast<int>(i);
    for (std::size_t i = 0; i < cfg_.contact.size(); ++i)
      if (cfg_.contact[i].name == name) pair = static_cast<int>(i);
    if (load < 0 && pair < 0) fail(quoted(p) + ": no load ('Boundary Conditions') or contact pair ('Contact') is named '" + name + "'");
    if (load >= 0 && pair >= 0) fail(quoted(p) + ": '" + name + "' names both a load and a contact pair; rename one");
    auto uses = [&](const std::vector<std::string>& keys) {
      for (const auto& key : keys)
        if (r.isParameter(key)) return key;
      return std::string();
    };
    const std::vector<std::string> load_keys = {"ramp", "ramp times", "ramp factors"};
    const std::vector<std::string> obstacle_keys = {"translation ramp", "translation ramp times", "translation ramp factors",
                                                    "radius ramp", "radius ramp times", "radius ramp factors"};
    if (load >= 0) {
      if (!st.load_active[static_cast<std::size_t>(load)])
        fail(quoted(p) + ": load '" + name + "' is not active in this stage (see 'Stages->" + st.name + "->loads')");
      if (const std::string bad = uses(obstacle_keys); !bad.empty()) fail(quoted(p + "->" + bad) + " belongs to a contact obstacle, '" + name + "' is a load");
      if (uses(load_keys).empty()) continue;
      Ramp& ramp = cfg_.loads[static_cast<std::size_t>(load)].ramp;
      const Ramp over = read_ramp(r, p, ls, "ramp");
      ramp.stages[k] = piece_of(over, st);
    } else {
      ContactPairConfig& c = cfg_.contact[static_cast<std::size_t>(pair)];
      if (!st.contact_active[static_cast<std::size_t>(pair)])
        fail(quoted(p) + ": contact pair '" + name + "' is not active in this stage (see 'Stages->" + st.name + "->contact')");
      if (const std::string bad = uses(load_keys); !bad.empty()) fail(quoted(p + "->" + bad) + " belongs to a load, '" + name + "' is a contact pair (use 'translation ramp' or 'radius ramp')");
      if (c.obstacle.empty()) fail(quoted(p) + ": contact pair '" + name + "' has a deformable master and no obstacle to program");
      if (r.isParameter("translation ramp") || r.isParameter("translation ramp times") || r.isParameter("translation ramp factors"))
        c.translation_ramp.stages[k] = piece_of(read_ramp(r, p, ls, "translation ramp"), st);
      if (r.isParameter("radius ramp") || r.isParameter("radius ramp times") || r.isParameter("radius ramp factors")) {
        if (c.obstacle == "plane") fail(quoted(p + "->radius ramp") + " is not used by a plane obstacle");
        c.radius_ramp.stages[k] = piece_of(read_ramp(r, p, ls, "radius ramp"), st);
      }
    }
  }
}

// A stage's analysis and scheme (defaults: Problem->analysis, Time Integration->scheme),
// and the contact pairs that need a dynamic stage.
void DeckReader::read_stage_analysis(const ParameterList& sub, const std::string& path, StageConfig& st) {
  const ListSpec& ls = deck_list_spec("Stages/*");
  st.analysis = sub.isParameter("analysis") ? get_string(sub, ls, "analysis") : cfg_.problem.analysis;
  st.scheme = cfg_.time.scheme;
  if (sub.isParameter("scheme")) {
    if (!st.dynamic())
      fail(quoted(path + "->scheme") + " is the time scheme of a dynamic stage, and the stage is static; set " +
           quoted(path + "->analysis") + " = dynamic or remove 'scheme'");
    st.scheme = get_string(sub, ls, "scheme");
  }
  st.stabilization = st.dynamic() ? 0.0 : cfg_.stepping.stabilization;
  if (sub.isParameter("stabilization")) {
    if (st.dynamic())
      fail(quoted(path + "->stabilization") + " stabilises static steps, and the stage is dynamic (inertia already "
           "holds its bodies); remove it or set " + quoted(path + "->analysis") + " = static");
    st.stabilization = get_double(sub, ls, "stabilization");
  }
  if (st.dynamic()) return;
  for (std::size_t i = 0; i < cfg_.contact.size(); ++i)
    if (st.contact_active[i] && cfg_.contact[i].formulation == "persistence")
      fail(quoted("Contact->" + cfg_.contact[i].name + "->formulation") + " = persistence needs a dynamic analysis, and the pair is active in the static stage " +
           quoted(path) + "; use gap or auto (gap in static stages), or leave the pair out of the stage's 'contact'");
}

// What the analysis asks of the rest of the deck, once the stages (each with its own
// analysis and scheme) are known.
void DeckReader::check_analysis(bool initial_conditions, bool time_integration) {
  const bool staged = !cfg_.stages.empty();
  // Two pairs may share a slave group (a stent's outer surface: the crimper's, then the
  // lumen's) only when no stage activates both.
  for (std::size_t i = 0; i < cfg_.contact.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const ContactPairConfig &a = cfg_.contact[j], &b = cfg_.contact[i];
      const StageConfig* st = nullptr;
      if (a.slave == b.slave && cfg_.pairs_meet(i, j, &st))
        fail("'Contact->" + a.name + "' and 'Contact->" + b.name + "' both use slave group '" + a.slave + "' and " +
             (st ? "stage 'Stages->" + st->name + "' activates both" : std::string("without 'Stages' every pair is active throughout")) +
             "; a node may be a slave of two pairs only when no stage activates both");
    }
  for (int k = 0; k < cfg_.interval_count(); ++k) {
    if (cfg_.analysis_in(k) != "midpoint") continue;
    for (const auto& m : cfg_.materials)
      if (m.has_history())  // the element kernels have no midpoint evaluation of a law with history
        fail("'Materials->" + m.name + "->model' = " + m.model + " needs " +
             (staged ? quoted("Stages->" + cfg_.stages[static_cast<std::size_t>(k)].name + "->scheme") : std::string("'Time Integration->scheme'")) +
             " = gonzalez (energy-dissipative), newmark or hht, not midpoint");
  }
  if (cfg_.any_dynamic()) {
    for (const auto& b : cfg_.bodies)
      if (b.fbar())  // the energy-consistent schemes need Delta C linear in the step's displacement increment
        fail(quoted("Bodies->" + b.name + "->element technology") + " = f-bar is for static analysis only; " +
             (staged ? std::string("a stage has 'analysis' = dynamic") : std::string("'Problem->analysis' = dynamic")) +
             " (use 'full')");
    for (const auto& m : cfg_.materials)
      if (!(m.density > 0.0))
        fail("'Materials->" + m.name + "->density' must be > 0 in a dynamic analysis (" +
             (staged ? std::string("a stage has 'analysis' = dynamic") : std::string("'Problem->analysis' = dynamic")) + ")");
  }
  for (int k = 0; k < cfg_.interval_count(); ++k) {
    if (!cfg_.dynamic_in(k)) continue;
    for (std::size_t i = 0; i < cfg_.loads.size(); ++i)
      if (cfg_.loads[i].type == LoadConfig::Type::FluidCavity && (!staged || cfg_.stages[static_cast<std::size_t>(k)].load_active[i]))
        fail(quoted("Boundary Conditions->" + cfg_.loads[i].name) + ": a fluid cavity is for static analysis only, and " +
             (staged ? "the dynamic stage " + quoted("Stages->" + cfg_.stages[static_cast<std::size_t>(k)].name) + " activates it"
                     : std::string("'Problem->analysis' = dynamic")) +
             " (its work is not in the energy audit); use a `pressure` load there, or a static stage");
  }
  if (!cfg_.dynamic_in(0))
    for (const auto& b : cfg_.bodies)
      if (b.own_velocity() || b.has_displacement)
        fail(quoted("Bodies->" + b.name + (b.has_velocity ? "->initial velocity" : b.has_angular_velocity ? "->initial angular velocity" : "->initial displacement")) +
             " needs " + (staged ? "the first stage " + quoted("Stages->" + cfg_.stages.front().name) + " to be dynamic (a static stage starts at rest)"
                                 : std::string("'Problem->analysis' = dynamic (a static analysis has no initial state)")));
  if (initial_conditions && !cfg_.dynamic_in(0))
    fail(staged ? "'Initial Conditions' needs the first stage " + quoted("Stages->" + cfg_.stages.front().name) +
                      " to be dynamic (a static stage starts at rest)"
                : std::string("'Initial Conditions' needs 'Problem->analysis' = dynamic (a static analysis has no velocity)"));
  if (time_integration && !cfg_.any_dynamic())
    fail(staged ? std::string("'Time Integration' needs a dynamic stage ('analysis' = dynamic in a stage or in 'Problem')")
                : std::string("'Time Integration' needs 'Problem->analysis' = dynamic"));
}

void DeckReader::read_stages(const ParameterList& pl, const ParameterList* stepping) {
  const ListSpec& ls = deck_list_spec("Stages/*");
  check_list(pl, "Stages", {&deck_list_spec("Stages")});
  if (stepping)
    for (const char* k : {"end time", "steps"})
      if (stepping->isParameter(k))
        fail(std::string("'Stepping->") + k + "' is not used with 'Stages' (each stage has its own duration and steps); remove it");
  std::vector<std::string> load_names, pair_names;
  for (const auto& l : cfg_.loads) load_names.push_back(l.name);
  for (const auto& c : cfg_.contact) pair_names.push_back(c.name);
  double t = 0.0;
  long long total = 0;
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Stages->" + name;
    check_safe_name(name, path, "the stage name");
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    StageConfig st;
    st.name = name;
    st.start = t;
    const bool has_d = sub.isParameter("duration"), has_e = sub.isParameter("end time");
    if (has_d == has_e) fail(quoted(path) + " needs exactly one of 'duration' and 'end time'" + (has_d ? ", not both" : ""));
    st.end = has_d ? t + get_double(sub, ls, "duration") : get_double(sub, ls, "end time");
    if (!(st.end > t)) fail(quoted(path + "->end time") + " must be after the previous stage's end " + num(t) + ", got " + num(st.end));
    if (!std::isfinite(st.end) || st.end > 1e300)
      fail(quoted(path) + ": the stage ends at " + num(st.end) + " (the previous end " + num(t) + " plus its duration); the procedure's "
           "times must stay finite, at most 1e300 s");
    if (sub.isParameter("steps") && sub.isParameter("step")) fail(quoted(path) + " takes 'steps' or 'step', not both");
    st.num_steps = get_int(sub, ls, "steps");
    if (sub.isParameter("step")) {
      const double n = std::ceil((st.end - st.start) / get_double(sub, ls, "step") * (1.0 - 1e-12));
      if (n > 1e7) fail(quoted(path + "->step") + " gives more than 1e7 steps");
      st.num_steps = std::max(1, static_cast<int>(n));
    }
    check_step(st.step(), st.end, "the step of stage " + quoted(path));
    if (cfg_.stepping.min_dt > st.step())
      fail("'Stepping->min dt' = " + num(cfg_.stepping.min_dt) + " exceeds the step " + num(st.step()) + " of stage " + quoted(path));
    st.load_active = read_active(sub, path, "loads", load_names, "load");
    st.contact_active = read_active(sub, path, "contact", pair_names, "contact pair");
    read_stage_analysis(sub, path, st);
    cfg_.stages.push_back(st);
    const std::size_t k = cfg_.stages.size() - 1;
    // Default pieces: the deck's ramp in stage-local time where active, else held
    // (Dirichlet values, obstacle motion) or off (forces).
    for (std::size_t i = 0; i < cfg_.loads.size(); ++i) {
      Ramp& r = cfg_.loads[i].ramp;
      Ramp::Piece p = piece_of(r, st);
      if (!st.load_active[i]) p.mode = cfg_.loads[i].type == LoadConfig::Type::Dirichlet ? Ramp::Piece::Mode::Hold : Ramp::Piece::Mode::Off;
      r.stages.push_back(p);
    }
    for (auto& c : cfg_.contact) {
      c.translation_ramp.stages.push_back(piece_of(c.translation_ramp, st));
      c.radius_ramp.stages.push_back(piece_of(c.radius_ramp, st));
      if (!st.contact_active[static_cast<std::size_t>(&c - cfg_.contact.data())]) {
        c.translation_ramp.stages.back().mode = Ramp::Piece::Mode::Hold;
        c.radius_ramp.stages.back().mode = Ramp::Piece::Mode::Hold;
      }
    }
    if (sub.isSublist("Ramps")) read_stage_ramps(sub.sublist("Ramps"), path + "->Ramps", k);
    t = st.end;
    total += st.num_steps;
    if (total > kMaxTotalSteps)
      fail("the stages up to " + quoted(path) + " take " + std::to_string(total) + " steps in all; at most " +
           std::to_string(kMaxTotalSteps) + " (the step counter's range): use fewer steps or larger 'step's");
  }
  if (cfg_.stages.empty()) fail("'Stages' defines no stage; add one sublist per stage or remove 'Stages'");
  // Held values: the factor at the end of the stage before (0 before the first).
  auto fill_held = [](Ramp& r) {
    double prev = 0.0;
    for (auto& p : r.stages) {
      if (p.mode == Ramp::Piece::Mode::Hold) p.held = prev;
      prev = p.mode == Ramp::Piece::Mode::Off ? 0.0 : end_value(p);
    }
  };
  for (auto& l : cfg_.loads) fill_held(l.ramp);
  for (auto& c : cfg_.contact) {
    fill_held(c.translation_ramp);
    fill_held(c.radius_ramp);
  }
  cfg_.stepping.end_time = t;
  cfg_.stepping.num_steps = static_cast<int>(total);
}

Config DeckReader::read() {
  std::error_code ec;
  const fs::path abs = fs::absolute(fs::path(file_), ec).lexically_normal();
  cfg_.deck_path = abs.string();
  if (!fs::exists(abs, ec)) fail("cannot read the deck: no such file (" + cfg_.deck_path + ")");
  if (!fs::is_regular_file(abs, ec)) fail("cannot read the deck: not a regular file (" + cfg_.deck_path + ")");

  check_nesting();
  XMLObject xml;
  try {
    xml = Teuchos::FileInputSource(cfg_.deck_path).getObject();
  } catch (const std::exception& e) {
    fail(rewrap_xml_error(e.what()));
  }
  if (xml.getTag() != "ParameterList")
    fail("the root element must be <ParameterList name=\"stentor\">, found <" + xml.getTag() + ">");
  check_xml(xml, "", false);

  ParameterList root;
  try {
    // What Teuchos::getParametersFromXmlFile does, on the tree already read and checked.
    Teuchos::XMLParameterListReader reader;
    root = reader.toParameterList(xml);
  } catch (const std::exception& e) {
    fail("invalid parameter list: " + clean_teuchos_message(e.what()));
  }

  apply_numbers(xml, root);
  const std::vector<const ListSpec*> root_spec = {&deck_list_spec("")};
  check_list(root, "", root_spec);
  require(root, "", root_spec);
  if (root.isSublist("Problem")) read_problem(root.sublist("Problem"));
  read_mesh(root.sublist("Mesh"));
  read_materials(root.sublist("Materials"));
  read_bodies(root.sublist("Bodies"));
  check_stent_plastic();
  if (root.isSublist("Boundary Conditions")) read_loads(root.sublist("Boundary Conditions"));
  if (root.isSublist("Initial Conditions")) read_initial(root.sublist("Initial Conditions"));
  if (root.isSublist("Time Integration")) read_time(root.sublist("Time Integration"));
  if (root.isSublist("Stepping")) read_stepping(root.sublist("Stepping"));
  if (root.isSublist("Newton")) read_newton(root.sublist("Newton"));
  if (root.isSublist("Linear Solver")) read_linear(root.sublist("Linear Solver"));
  if (root.isSublist("Output")) read_output(root.sublist("Output"));
  if (root.isSublist("Contact")) read_contact(root.sublist("Contact"));
  if (root.isSublist("Stages")) read_stages(root.sublist("Stages"), root.isSublist("Stepping") ? &root.sublist("Stepping") : nullptr);
  check_analysis(root.isSublist("Initial Conditions"), root.isSublist("Time Integration"));
  resolve_output();
  // "{deck}" in Output->directory (the default results/{deck}): the deck's file name
  // without its extension, so that two decks never share a result folder by default.
  const std::string stem = fs::path(cfg_.deck_path).stem().string();
  std::string& dir = cfg_.output.directory;
  for (std::size_t at = dir.find("{deck}"); at != std::string::npos; at = dir.find("{deck}", at + stem.size()))
    dir.replace(at, 6, stem);
  if (cfg_.stages.empty() && cfg_.stepping.num_steps > kMaxTotalSteps)
    fail("'Stepping->steps' = " + std::to_string(cfg_.stepping.num_steps) + " exceeds " + std::to_string(kMaxTotalSteps) +
         " (the step counter's range)");
  const double step = cfg_.stepping.end_time / cfg_.stepping.num_steps;
  if (cfg_.stages.empty())
    check_step(step, cfg_.stepping.end_time, "the step 'Stepping->end time' / 'Stepping->steps'");
  if (cfg_.stages.empty() && cfg_.stepping.min_dt > step)
    fail("'Stepping->min dt' must not exceed the step 'Stepping->end time' / 'Stepping->steps' = " + num(step) + ", got " +
         num(cfg_.stepping.min_dt));
  return cfg_;
}

}  // namespace

Config read_deck(const std::string& path) {
  check_input_size(path, false, "deck");  // before a byte of it is read
  DeckReader reader(path);
  return reader.read();
}

void check_vector_dimensions(const Config& cfg, int dim) {
  for (const DimVector& v : cfg.dim_vectors) {
    const int want = dim == 2 ? v.in2d : v.in3d;
    if (v.given == want) continue;
    throw InputError(cfg.deck_path + ": '" + v.path + "' must have " + std::to_string(want) + " value" + (want == 1 ? "" : "s") +
                     " (the mesh is " + std::to_string(dim) + "D), got " + std::to_string(v.given));
  }
}

}  // namespace stentor
