#include "mesh/GeoScreen.hpp"

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "deck/Config.hpp"
#include "deck/InputLimits.hpp"
#include "mesh/MshScreen.hpp"

namespace stentor {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------ tokens
//
// The .geo text as gmsh 4.8's lexer (Parser/Gmsh.l) reads it: "..." and '...' strings
// with no escapes (a string ends at the first quote of its kind), // and /* */ comments,
// numbers, names ({alpha}({alpha}|{digit})*, a keyword when gmsh's lexer lists it) and
// the operators of its grammar. Any other character outside strings and comments is no
// part of the language and is refused.

enum class Kind { Name, Number, String, Punct };

struct Token {
  Kind kind;
  std::string text;
  int line;
};

const char* const kMultiPunct[] = {"...", "::", "||", "&&", "++", "--", "==", "!=", "<=", ">=", ">>", "<<",
                                   "+=",  "-=", "*=", "/="};
const char kSinglePunct[] = ";=+-*/^%()[]{},.:<>!&|?#~";

[[noreturn]] void refuse_char(const std::string& name, int line, unsigned char c) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", c);
  throw InputError(name + ":" + std::to_string(line) + ": the character " +
                   (std::isprint(c) ? "'" + std::string(1, static_cast<char>(c)) + "' (" + hex + ")" : std::string(hex)) +
                   " outside a string or comment is no part of gmsh's .geo language; refused");
}

std::size_t skip_comment(const std::string& t, std::size_t i, int& line) {
  if (t[i + 1] == '/') {
    while (i < t.size() && t[i] != '\n') ++i;
    return i;
  }
  i += 2;
  while (i < t.size() && t.compare(i, 2, "*/") != 0) line += t[i++] == '\n';
  return std::min(t.size(), i + 2);
}

std::vector<Token> tokenize(const std::string& t, const std::string& name) {
  std::vector<Token> toks;
  int line = 1;
  const auto digit = [&](std::size_t k) { return k < t.size() && std::isdigit(static_cast<unsigned char>(t[k])); };
  for (std::size_t i = 0; i < t.size();) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    if (c == '\n' || c == ' ' || c == '\t' || c == '\r' || c == '\f') {
      line += c == '\n';
      ++i;
    } else if (c == '/' && i + 1 < t.size() && (t[i + 1] == '/' || t[i + 1] == '*')) {
      i = skip_comment(t, i, line);
    } else if (c == '"' || c == '\'') {
      const std::size_t end = std::min(t.find(static_cast<char>(c), i + 1), t.size());
      toks.push_back({Kind::String, t.substr(i + 1, end - i - 1), line});
      for (std::size_t k = i; k < end; ++k) line += t[k] == '\n';
      i = end + 1;
    } else if (std::isalpha(c) || c == '_') {
      std::size_t e = i;
      while (e < t.size() && (std::isalnum(static_cast<unsigned char>(t[e])) || t[e] == '_')) ++e;
      toks.push_back({Kind::Name, t.substr(i, e - i), line});
      i = e;
    } else if (digit(i) || (c == '.' && digit(i + 1))) {
      std::size_t e = i;
      while (digit(e) || t[e] == '.') ++e;
      if (e < t.size() && (t[e] == 'e' || t[e] == 'E')) {
        std::size_t k = e + 1 + (e + 1 < t.size() && (t[e + 1] == '+' || t[e + 1] == '-'));
        if (digit(k)) {
          while (digit(k)) ++k;
          e = k;
        }
      }
      toks.push_back({Kind::Number, t.substr(i, e - i), line});
      i = e;
    } else {
      std::string p;
      for (const char* m : kMultiPunct)
        if (t.compare(i, std::strlen(m), m) == 0) {
          p = m;
          break;
        }
      if (p.empty() && c != 0 && std::strchr(kSinglePunct, c)) p = std::string(1, static_cast<char>(c));
      if (p.empty()) refuse_char(name, line, c);
      toks.push_back({Kind::Punct, p, line});
      i += p.size();
    }
  }
  return toks;
}

// ------------------------------------------------------------------ gmsh's keywords
//
// Every keyword of gmsh 4.8.4's lexer is either allowed or refused here, with the reason;
// a name that is no keyword is a variable, a macro, an option category or a command
// name (Include, Save, SystemCall, ... are names that gmsh's grammar compares, see
// command_refusal).

const std::set<std::string>& allowed_keywords() {
  static const std::set<std::string> k = {
      "Abs", "AbsolutePath", "Acos", "Affine", "Append", "ArcCos", "ArcSin", "ArcTan", "ArcTan2", "Asin", "Atan",
      "Atan2", "BSpline", "Bezier", "Box", "Block", "BooleanCoherence", "BooleanCommon", "BooleanCut",
      "BooleanDifference", "BooleanFragments", "BooleanFuse", "BooleanIntersection", "BooleanSection", "BooleanUnion",
      "BoundingBox", "Call", "Catenary", "CatmullRom", "Ceil", "CenterOfMass", "Chamfer", "Characteristic", "Circle",
      "ClassifySurfaces", "Coherence", "Color", "Compound", "Cone", "Coordinates", "Cos", "Cosh", "Cpu",
      "CreateGeometry", "CreateTopology", "CurrentDir", "CurrentDirectory", "CurrentFileName", "Curve", "Cylinder",
      "DefineConstant", "DefineNumber", "DefineString", "Degenerated", "Delete", "Dilate", "DimNameSpace", "DirName",
      "Disk", "Ellipse", "Ellipsis", "Ellipsoid", "Elliptic", "Else", "ElseIf", "EndFor", "EndIf", "Error",
      "Euclidian", "Exists", "Exp", "Extrude", "Fabs", "Field", "FileExists", "Fillet", "Find", "FixRelativePath",
      "Floor", "Fmod", "For", "Function", "GMSH_MAJOR_VERSION", "GMSH_MINOR_VERSION", "GMSH_PATCH_VERSION",
      "GeoEntity", "GetEnv", "GetForced", "GetForcedStr", "GetNumber", "GetString", "GmshExecutableName", "Hide",
      "Hole", "Hypot", "INTERPOLATION_SCHEME", "If", "In", "Intersect", "Knots", "Layers", "Length", "Levelset",
      "LinSpace", "Line", "List", "Log", "Log10", "LogSpace", "LowerCase", "LowerCaseIn", "MPI_Rank", "MPI_Size",
      "Macro", "Mass", "MatrixOfInertia", "Max", "Memory", "MeshAlgorithm", "MeshSize", "MeshSizeFromBoundary",
      "Min", "Modulo", "N2S", "NameStruct", "NameToString", "NewModel", "Nurbs", "Order", "Parametric", "Parent",
      "Periodic", "Physical", "Pi", "Plane", "Point", "PolarSphere", "Printf", "Quadric", "Rand", "Recombine",
      "Rectangle", "Recursive", "ReorientMesh", "Return", "ReverseMesh", "Reverse", "Rotate", "Round", "Ruled", "S2N",
      "ScaleLastLayer", "SetFactory", "SetTag", "SetMaxTag", "Sewing", "Show", "Sin", "Sinh", "Slide", "Smoother",
      "Sphere", "Spline", "Split", "Sprintf", "Sqrt", "Str", "StrCat", "StrChoice", "StrCmp", "StrFind", "StrLen",
      "StrPrefix", "StrRelative", "StrReplace", "StrSub", "StringToName", "Struct", "Surface", "Symmetry",
      "SyncModel", "TIME", "Tan", "Tanh", "TestLevel", "ThickSolid", "ThruSections", "Today", "Torus", "TotalMemory",
      "Transfinite", "Translate", "UndefineConstant", "Unique", "UpperCase", "Using", "Volume", "Warning", "Wedge",
      "Wire"};
  return k;
}

const char* kMeshes = "meshes or changes the mesh inside the .geo (Stentor meshes the geometry itself, with "
                      "'Mesh->size' and 'Mesh->max cells')";

// Why gmsh's keyword `w` is refused, or "" when it is allowed or no keyword.
std::string keyword_refusal(const std::string& w) {
  if (w == "Exit" || w == "Abort") return "ends the process";
  if (w == "OnelabRun" || w == "OnelabAction" || w == "CodeName") return "runs a program";
  if (w == "ShapeFromFile" || w == "ListFromFile") return "reads a file by a name of its own";
  if (w == "Plugin") return "runs a post-processing plugin (plugins write files)";
  if (w == "SetString" || w == "SetNumber") return "sets an option or parameter by a computed name";
  if (w == "GetValue" || w == "GetStringValue") return "reads the terminal";
  if (w == "RefineMesh" || w == "AdaptMesh" || w == "RecombineMesh" || w == "RelocateMesh" ||
      w == "RenumberMeshNodes" || w == "RenumberMeshElements" || w == "SetPartition" || w == "Homology" ||
      w == "Cohomology" || w == "Betti")
    return kMeshes;
  if (w == "Draw" || w == "SetChanged" || w == "UnsplitWindow" || w == "TextAttributes" || w == "T2" || w == "T3" ||
      w == "ColorTable" || w == "Combine" || w == "CopyOptions" || w == "Alias" || w == "AliasWithOptions")
    return "is a graphics or post-processing command";
  return "";
}

bool is_keyword(const std::string& w) {
  if (allowed_keywords().count(w) || !keyword_refusal(w).empty()) return true;
  std::string l;  // Quad[tT]ri[aA]dd[vV]erts and the like, in any of their spellings
  for (char c : w) l += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return l == "quadtriaddverts" || l == "quadtrinonewverts" || l == "recomblaterals" || l == "transfquadtri";
}

// Why the command `w` (a name that starts a statement and is followed by its arguments,
// as gmsh's `Command` rule reads `tSTRING StringExprVar ;` and its siblings) is refused.
std::string command_refusal(const std::string& w) {
  if (w == "Save" || w == "Print") return "writes files";
  if (w == "SystemCall" || w == "System" || w == "NonBlockingSystemCall" || w == "OnelabRun" || w == "SendToServer")
    return "runs a program";
  if (w == "CreateDir" || w == "DeleteFile" || w == "RenameFile") return "writes or deletes files";
  if (w == "Sleep") return "makes the process wait";
  if (w == "Mesh" || w == "Remesh" || w == "OptimizeMesh" || w == "SetOrder" || w == "PartitionMesh" ||
      w == "RefineMesh")
    return kMeshes;
  return "is a command Stentor does not know, so it is refused (a .geo may use Include, Merge, "
         "MergeWithBoundingBox and Background Field of gmsh's commands)";
}

// gmsh 4.8's string options (Common/DefaultOptions.h) of the categories a .geo may set:
// file names, programs, commands run on a click, fonts and labels.
bool string_option(const std::string& cat, const std::string& opt) {
  static const std::set<std::string> general = {
      "AxesFormatX", "AxesFormatY", "AxesFormatZ", "AxesLabelX", "AxesLabelY", "AxesLabelZ",
      "BackgroundImageFileName", "BuildInfo", "BuildOptions", "DefaultFileName", "Display", "ErrorFileName",
      "ExecutableFileName", "FileName", "FltkTheme", "GraphicsFont", "GraphicsFontEngine", "GraphicsFontTitle",
      "OptionsFileName", "ScriptingLanguages", "TextEditor", "TmpFileName", "Version", "WatchFilePattern"};
  if (cat == "General") return general.count(opt) || opt.rfind("RecentFile", 0) == 0;
  if (cat == "Geometry") return opt.find("Command") != std::string::npos;  // DoubleClicked*Command
  if (cat == "PostProcessing") return opt.find("Command") != std::string::npos;
  if (cat == "Print") return opt == "ParameterCommand";
  if (cat == "View")
    return opt == "Attributes" || opt == "DoubleClickedCommand" || opt == "FileName" || opt == "Format" ||
           opt == "Group" || opt == "Name" || opt.rfind("Axes", 0) == 0 || opt.rfind("GeneralizedRaise", 0) == 0 ||
           opt.rfind("Stipple", 0) == 0;
  return false;
}

// Why setting option `cat`.`opt` is refused, or "".
std::string option_refusal(const std::string& cat, const std::string& opt) {
  const std::string full = cat + "." + opt;
  if (cat == "Solver" || string_option(cat, opt)) return "sets an option that names a file or program (" + full + ")";
  if (cat == "General") {
    if (opt == "AbortOnError") return "sets General.AbortOnError, which makes gmsh end the process at an error";
    if (opt != "Terminal" && opt != "Verbosity" && opt != "ExpertMode")
      return "sets " + full + ", an option of gmsh's session (of the General options a .geo may set only "
             "General.Terminal, General.Verbosity and General.ExpertMode)";
  }
  return "";
}

// ------------------------------------------------------------------ statements

constexpr std::size_t npos = std::string::npos;

bool is(const std::vector<Token>& t, std::size_t k, const char* text, Kind kind = Kind::Punct) {
  return k < t.size() && t[k].kind == kind && t[k].text == text;
}

bool is_assignment(const std::vector<Token>& t, std::size_t k) {
  for (const char* op : {"=", "+=", "-=", "*=", "/=", "++", "--"})
    if (is(t, k, op)) return true;
  return false;
}

// The index of the token closing the bracket opened at `k` ( ( [ { ), or npos.
std::size_t closing(const std::vector<Token>& t, std::size_t k) {
  const std::string open = t[k].text, close = open == "(" ? ")" : open == "[" ? "]" : "}";
  int depth = 0;
  for (std::size_t j = k; j < t.size(); ++j) {
    if (t[j].kind != Kind::Punct) continue;
    depth += t[j].text == open ? 1 : t[j].text == close ? -1 : 0;
    if (depth == 0) return j;
  }
  return npos;
}

// Whether token `k` starts a statement: the file's first, or after ';', ')' or '}' (the
// end of an If (...) or For ... In {...} header, or of a statement in braces), the end of a control header (EndFor, EndIf, Else, Return) or a macro's name.
bool statement_start(const std::vector<Token>& t, std::size_t k) {
  if (k == 0) return true;
  const Token& p = t[k - 1];
  if (p.kind == Kind::Punct) return p.text == ";" || p.text == ")" || p.text == "}";
  if (p.kind == Kind::Name && (p.text == "EndFor" || p.text == "EndIf" || p.text == "Else" || p.text == "Return"))
    return true;
  return k >= 2 && t[k - 2].kind == Kind::Name && (t[k - 2].text == "Macro" || t[k - 2].text == "Function");
}

// Whether the name at `k`, starting a statement, is a command: followed by an argument
// (a string, name, number, sign, or a bracket not followed by an assignment).
bool command_position(const std::vector<Token>& t, std::size_t k) {
  if (k + 1 >= t.size()) return false;
  const Token& n = t[k + 1];
  if (n.kind != Kind::Punct) return true;
  if (n.text == "-" || n.text == "+" || n.text == "!") return true;
  if (n.text == "(" || n.text == "[") {
    const std::size_t c = closing(t, k + 1);
    return c == npos || !(is_assignment(t, c + 1) || is(t, c + 1, ".") || is(t, c + 1, "("));
  }
  return false;
}

struct Screen {
  const std::vector<Token>& t;
  const std::string& name;
  const std::string& dir;
  int depth;
  std::vector<std::string>* files;

  std::string where(std::size_t k) const { return name + ":" + std::to_string(t[k].line) + ": "; }
  [[noreturn]] void refuse(std::size_t k, const std::string& why) const {
    throw InputError(where(k) + "'" + t[k].text + "' " + why + "; Stentor refuses .geo statements that run programs, " +
                     "write, delete or read files by themselves, end the process or mesh by themselves, and any " +
                     "command it does not know; remove it from the .geo");
  }
  void run();
  void name_at(std::size_t k);
  void command(std::size_t k);
  void option(std::size_t k);
  void field(std::size_t k);
  void printf_like(std::size_t k);
};

void Screen::run() {
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k].kind != Kind::Name || is(t, k - 1, ".") || is(t, k - 1, "::")) continue;
    name_at(k);
  }
}

void Screen::name_at(std::size_t k) {
  const std::string& w = t[k].text;
  if (is_keyword(w)) {
    const std::string why = keyword_refusal(w);
    if (!why.empty()) refuse(k, why);
    if (w == "Printf" || w == "Error" || w == "Warning" || w == "Sprintf") printf_like(k);
    if (w == "Field") field(k);
    return;
  }
  if (is(t, k + 1, ".") || (is(t, k + 1, "[") && (w == "View" || w == "PostProcessing"))) option(k);
  if (statement_start(t, k) && command_position(t, k)) command(k);
}

// Include/Merge/MergeWithBoundingBox of a literal name (screened in turn), Background
// Field; every other command is refused.
void Screen::command(std::size_t k) {
  const std::string& w = t[k].text;
  if (w == "Include" || w == "Merge" || w == "MergeWithBoundingBox") {
    if (t[k + 1].kind != Kind::String || !is(t, k + 2, ";"))
      throw InputError(where(k) + "'" + w + "' needs a literal \"file\" name (computed names are refused)");
    fs::path p(t[k + 1].text);
    if (p.is_relative()) p = fs::path(dir) / p;
    screen_included(where(k), w, p.string(), depth, files);
    return;
  }
  if (w == "Background" && is(t, k + 1, "Field", Kind::Name)) return;
  refuse(k, command_refusal(w));
}

// `Cat.Opt = ...`, `Cat.Color.Opt = ...`, `View[n].Opt = ...`: refused by option_refusal.
void Screen::option(std::size_t k) {
  std::size_t j = k + 1;
  if (is(t, j, "[")) {
    j = closing(t, j);
    if (j == npos) return;
    ++j;
  }
  std::string opt;
  while (is(t, j, ".") && j + 1 < t.size() && t[j + 1].kind == Kind::Name) {
    opt += (opt.empty() ? "" : ".") + t[j + 1].text;
    j += 2;
  }
  if (opt.empty() || !is_assignment(t, j)) return;
  const std::string why = option_refusal(t[k].text, opt);
  if (!why.empty()) refuse(k, why);
}

// `Field[n] = Type;` and `Field[n].Option = ...`: the field types that run a program or
// read files, and the options naming them, are refused.
void Screen::field(std::size_t k) {
  if (!is(t, k + 1, "[")) return;
  const std::size_t c = closing(t, k + 1);
  if (c == npos || c + 2 >= t.size()) return;
  const std::string& n = t[c + 2].text;
  if (is(t, c + 1, "=") && (n == "ExternalProcess" || n == "Structured" || n == "PostView"))
    refuse(k, "of type " + n + (n == "ExternalProcess" ? " runs a program" : " reads a file or view"));
  if (is(t, c + 1, ".") && (n == "FileName" || n == "CommandLine" || n == "ViewTag" || n == "ViewIndex"))
    refuse(k, "sets " + n + ", an option naming a file, program or view");
}

// Printf(...) > target / >> target writes a file, whatever forms the target. The format
// is handed to the C library's sprintf with numbers: %s, %n, %p or %c with a number
// crash or write memory, and a width of 999999999 overflows its buffer. It must be a
// literal with numeric conversions and widths of at most 3 digits.
void Screen::printf_like(std::size_t k) {
  if (!is(t, k + 1, "(")) return;
  const std::size_t c = closing(t, k + 1);
  if (c == npos) throw InputError(where(k) + "'" + t[k].text + "' has no closing ')'");
  if (is(t, c + 1, ">") || is(t, c + 1, ">>") || is(t, c + 1, ">="))
    refuse(k, "writes a file (" + t[k].text + " with " + t[c + 1].text + ", whatever names the target)");
  if (t[k].text != "Printf" && t[k].text != "Sprintf") return;
  if (t[k + 2].kind != Kind::String)
    throw InputError(where(k) + "'" + t[k].text + "' needs a literal \"format\" (a computed format is refused)");
  const std::string& f = t[k + 2].text;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f[i] != '%') continue;
    ++i;
    if (i < f.size() && f[i] == '%') continue;
    while (i < f.size() && std::strchr("-+ #0", f[i])) ++i;
    for (int part = 0; part < 2; ++part) {
      std::size_t digits = 0;
      while (i < f.size() && std::isdigit(static_cast<unsigned char>(f[i]))) ++i, ++digits;
      if (digits > 3)
        throw InputError(where(k) + "'" + t[k].text + "' has a format width or precision of more than 3 digits");
      if (part == 0 && i < f.size() && f[i] == '.') ++i; else break;
    }
    while (i < f.size() && std::strchr("hlLqjzt", f[i])) ++i;
    if (i >= f.size() || !std::strchr("diouxXeEfFgGaA", f[i]))
      throw InputError(where(k) + "'" + t[k].text + "' has a format conversion other than a number's (%g, %f, %e, " +
                       "%d...): '" + f + "'");
  }
}

// gmsh reads a Merge'd file by its extension (these lower-case ones are data: CAD or
// mesh formats that its readers take as such, never as .geo text); anything else, and
// every Include'd file whatever its name, it parses as .geo, so it is screened as one.
bool data_extension(const fs::path& p) {
  static const char* kData[] = {".step", ".stp", ".brep", ".iges", ".igs", ".stl", ".xao", ".unv", ".vtk", ".med"};
  const std::string ext = p.extension().string();
  for (const char* d : kData)
    if (ext == d) return true;
  return false;
}

// Whether `p` holds a gmsh .msh file: by its name or by its first line, as gmsh decides.
bool msh_content(const fs::path& p) {
  std::string ext = p.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".msh") return true;
  std::ifstream in(p, std::ios::binary);
  std::string head(11, '\0');
  in.read(&head[0], 11);
  return in.gcount() == 11 && head == "$MeshFormat";
}

std::string read_text(const std::string& file, const char* what) {
  check_input_size(file, false, what);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open mesh file (missing or unreadable)");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

// gmsh merges <file>.opt after every file it reads (Common/OpenFile.cpp), as .geo text.
void screen_options_file(const std::string& file, int depth, std::vector<std::string>* files) {
  std::error_code ec;
  if (fs::exists(file + ".opt", ec)) screen_included(file + ": ", "Merge", file + ".opt", depth + 1, files);
}

void screen_included(const std::string& where, const std::string& word, const std::string& file, int depth,
                     std::vector<std::string>* files) {
  const fs::path p(file);
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (ec || !fs::exists(st)) throw InputError(where + "'" + word + "' names '" + file + "', which does not exist");
  // A device, FIFO or folder would block or never end (/dev/zero, /dev/stdin).
  if (!fs::is_regular_file(st))
    throw InputError(where + "'" + word + "' names '" + file + "', which is not a regular file");
  if (files) files->push_back(file);
  screen_options_file(file, depth, files);
  if (word != "Include" && msh_content(p)) {
    check_input_size(file, true, "merged .msh file");
    screen_msh_file(file);
    return;
  }
  if (word != "Include" && data_extension(p)) {
    check_input_size(file, true, "merged CAD file");
    return;
  }
  screen_geo_text(read_text(file, "included .geo text"), file, p.parent_path().string(), depth + 1, files);
}

void screen_geo_text(const std::string& text, const std::string& name, const std::string& dir, int depth,
                     std::vector<std::string>* files) {
  if (depth > 16) throw InputError(name + ": Include/Merge nested more than 16 deep");
  const std::vector<Token> toks = tokenize(text, name);
  Screen{toks, name, dir, depth, files}.run();
}

bool geo_screen_disabled() {
  const char* v = std::getenv("STENTOR_TEST_NO_GEO_SCREEN");
  return v && std::strcmp(v, "1") == 0;
}

std::vector<std::string> screen_geo_file(const std::string& file) {
  std::vector<std::string> files = {file};
  if (geo_screen_disabled()) return files;
  screen_geo_text(read_text(file, "mesh script (.geo)"), file, fs::path(file).parent_path().string(), 0, &files);
  screen_options_file(file, 0, &files);
  return files;
}

}  // namespace stentor
