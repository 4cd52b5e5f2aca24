#include "mesh/GeoScreen.hpp"

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "deck/Config.hpp"
#include "mesh/MshScreen.hpp"

namespace stentor {
namespace {

namespace fs = std::filesystem;

// The .geo text with comments removed and string literals kept apart: `code` has every
// comment and every string's contents replaced by spaces (newlines kept, so offsets
// give line numbers); `strings[i]` is the literal that starts at `string_at[i]`.
// gmsh's lexer (Gmsh.l) takes "..." and '...' as strings, with no escapes: a string ends
// at the first quote of its kind (a backslash escapes nothing; "\" is one backslash and
// the string ends). Reading them any other way would let a command hide inside what the
// screen takes for a string.
struct Stripped {
  std::string code;
  std::vector<std::size_t> string_at;
  std::vector<std::string> strings;
};

Stripped strip(const std::string& t) {
  Stripped s;
  s.code = t;
  std::size_t i = 0;
  auto blank = [&](std::size_t k) {
    if (s.code[k] != '\n') s.code[k] = ' ';
  };
  while (i < t.size()) {
    if (t.compare(i, 2, "//") == 0) {
      while (i < t.size() && t[i] != '\n') blank(i++);
    } else if (t.compare(i, 2, "/*") == 0) {
      blank(i++), blank(i++);
      while (i < t.size() && t.compare(i, 2, "*/") != 0) blank(i++);
      for (int k = 0; k < 2 && i < t.size(); ++k) blank(i++);
    } else if (t[i] == '"' || t[i] == '\'') {
      const char quote = t[i];
      s.string_at.push_back(i);
      std::string lit;
      ++i;
      while (i < t.size() && t[i] != quote) {
        lit += t[i];
        blank(i++);
      }
      s.strings.push_back(lit);
      ++i;
    } else {
      ++i;
    }
  }
  return s;
}

int line_of(const std::string& text, std::size_t pos) {
  int line = 1;
  for (std::size_t k = 0; k < pos && k < text.size(); ++k) line += text[k] == '\n';
  return line;
}

bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::size_t skip_space(const std::string& c, std::size_t k) {
  while (k < c.size() && std::isspace(static_cast<unsigned char>(c[k]))) ++k;
  return k;
}

// Why the command `word` (at `pos` in the stripped code) is refused, or "".
std::string refusal(const std::string& word, const std::string& code, std::size_t pos) {
  const std::size_t next = skip_space(code, pos + word.size());
  const char nc = next < code.size() ? code[next] : '\0';
  if (word == "SystemCall" || word == "System" || word == "NonBlockingSystemCall" || word == "OnelabRun" ||
      word == "OnelabAction" || word == "SendToServer")
    return "runs a program";
  if (word == "Save" || word == "CreateDir" || word == "DeleteFile" || word == "RenameFile")
    return "writes or deletes files";
  if (word == "Print" && nc != '.') return "writes files";
  if (word == "Exit" || word == "Abort") return "ends the process";
  if (word == "Sleep") return "makes the process wait";
  if (word == "RefineMesh" || (word == "Mesh" && (std::isdigit(static_cast<unsigned char>(nc)) || nc == '(')))
    return "meshes inside the .geo (Stentor meshes the geometry itself, with 'Mesh->size' and 'Mesh->max cells')";
  if (word == "Printf") {
    // Printf("...", args) > "file";  or  >> "file": the redirection writes a file.
    const std::size_t semi = code.find(';', pos);
    const std::size_t close = code.rfind(')', semi);
    if (close != std::string::npos && close > pos && skip_space(code, close + 1) < code.size() &&
        code[skip_space(code, close + 1)] == '>')
      return "writes a file (Printf with > or >>)";
  }
  if ((word == "General" || word == "Solver") && nc == '.') {
    const std::size_t b = skip_space(code, next + 1);  // gmsh allows "General . X"
    std::size_t e = b;
    while (e < code.size() && ident_char(code[e])) ++e;
    const std::string opt = code.substr(b, e - b);
    if (word == "Solver" || opt.find("FileName") != std::string::npos || opt.rfind("Save", 0) == 0 ||
        opt.find("Executable") != std::string::npos)
      return "sets an option that names a file or program (" + word + "." + opt + ")";
    if (opt == "AbortOnError")
      return "sets General.AbortOnError, which makes gmsh end the process at an error";
  }
  return "";
}

// The literal file name after Include/Merge at `pos`, or "" when it is not a literal.
std::string literal_after(const Stripped& s, std::size_t pos) {
  const std::size_t k = skip_space(s.code, pos);
  for (std::size_t i = 0; i < s.string_at.size(); ++i)
    if (s.string_at[i] == k) return s.strings[i];
  return "";
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

// Why the format of the Printf/Sprintf at `e` (just after the word) is refused, or "".
// gmsh hands the format and the numbers to the C library's sprintf: %s, %n, %p or %c with
// a number crashes or writes memory, and a width of 999999999 overflows its buffer. The
// format must be a literal with numeric conversions and widths of at most 3 digits.
std::string format_refusal(const Stripped& s, std::size_t e) {
  std::size_t k = skip_space(s.code, e);
  if (k >= s.code.size() || s.code[k] != '(') return "";
  k = skip_space(s.code, k + 1);
  const std::string* fmt = nullptr;
  for (std::size_t i = 0; i < s.string_at.size(); ++i)
    if (s.string_at[i] == k) fmt = &s.strings[i];
  if (!fmt) return "needs a literal \"format\" (a computed format is refused)";
  const std::string& f = *fmt;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f[i] != '%') continue;
    ++i;
    if (i < f.size() && f[i] == '%') continue;
    while (i < f.size() && std::strchr("-+ #0", f[i])) ++i;
    for (int part = 0; part < 2; ++part) {
      std::size_t digits = 0;
      while (i < f.size() && std::isdigit(static_cast<unsigned char>(f[i]))) ++i, ++digits;
      if (digits > 3) return "has a format width or precision of more than 3 digits";
      if (part == 0 && i < f.size() && f[i] == '.') ++i; else break;
    }
    while (i < f.size() && std::strchr("hlLqjzt", f[i])) ++i;
    if (i >= f.size() || !std::strchr("diouxXeEfFgGaA", f[i]))
      return "has a format conversion other than a number's (%g, %f, %e, %d...): '" + f + "'";
  }
  return "";
}

// Screens the file an Include/Merge/MergeWithBoundingBox at `where` names.
void screen_included(const std::string& where, const std::string& word, const fs::path& p, int depth) {
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (ec || !fs::exists(st)) throw InputError(where + "'" + word + "' names '" + p.string() + "', which does not exist");
  // A device, FIFO or folder would block or never end (/dev/zero, /dev/stdin).
  if (!fs::is_regular_file(st))
    throw InputError(where + "'" + word + "' names '" + p.string() + "', which is not a regular file");
  if (word != "Include" && msh_content(p)) {
    screen_msh_file(p.string());
    return;
  }
  if (word != "Include" && data_extension(p)) return;
  std::ifstream in(p, std::ios::binary);
  if (!in) throw InputError(where + "cannot read the included file '" + p.string() + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  screen_geo_text(ss.str(), p.string(), p.parent_path().string(), depth + 1);
}

}  // namespace

void screen_geo_text(const std::string& text, const std::string& name, const std::string& dir, int depth) {
  if (depth > 16) throw InputError(name + ": Include/Merge nested more than 16 deep");
  const Stripped s = strip(text);
  const std::string& c = s.code;
  for (std::size_t i = 0; i < c.size();) {
    if (!ident_char(c[i]) || (i > 0 && (ident_char(c[i - 1]) || c[i - 1] == '.'))) {
      ++i;
      continue;
    }
    std::size_t e = i;
    while (e < c.size() && ident_char(c[e])) ++e;
    const std::string word = c.substr(i, e - i);
    const std::string why = refusal(word, c, i);
    const std::string where = name + ":" + std::to_string(line_of(text, i)) + ": ";
    if (!why.empty())
      throw InputError(where + "'" + word + "' " + why + "; Stentor refuses .geo commands that run programs, " +
                       "write files, end the process or mesh by themselves (SystemCall, Printf > file, Save, " +
                       "Print, CreateDir, Exit, Sleep, Mesh N, RefineMesh, OnelabRun); remove it from the .geo");
    if (word == "Printf" || word == "Sprintf") {
      const std::string bad = format_refusal(s, e);
      if (!bad.empty()) throw InputError(where + "'" + word + "' " + bad);
    }
    if (word == "Include" || word == "Merge" || word == "MergeWithBoundingBox") {
      const std::string f = literal_after(s, e);
      if (f.empty())
        throw InputError(where + "'" + word + "' needs a literal \"file\" name (computed names are refused)");
      fs::path p(f);
      if (p.is_relative()) p = fs::path(dir) / p;
      screen_included(where, word, p, depth);
    }
    i = e;
  }
}

void screen_geo_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open mesh file (missing or unreadable)");
  std::stringstream ss;
  ss << in.rdbuf();
  screen_geo_text(ss.str(), file, fs::path(file).parent_path().string());
}

}  // namespace stentor
