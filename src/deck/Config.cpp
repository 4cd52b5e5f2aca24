// Input deck reader: Teuchos ParameterList XML -> stentor::Config, validated against
// the schema of deck/Schema.cpp. Every problem throws InputError("<deck>: ..."). This file:
// Config's own queries, the raw-text, XML and schema passes, typed access and read(); the
// sections are read in ConfigModel.cpp, ConfigLoads.cpp and ConfigStages.cpp.
#include "deck/Config.hpp"
#include "deck/DeckReader.hpp"
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

namespace deck_reader {


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
std::string join(const std::vector<std::string>& v, const std::string& sep) {
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


// ------------------------------------------------------------------------------------
// Pass 0: raw text. A Stentor deck nests 5 levels (Linear Solver->MueLu->... sublists
// a few more); kMaxNesting leaves ample room and stays far from the stack's limit.

constexpr int kMaxNesting = 64;

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

}  // namespace deck_reader

Config read_deck(const std::string& path) {
  check_input_size(path, false, "deck");  // before a byte of it is read
  deck_reader::DeckReader reader(path);
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
