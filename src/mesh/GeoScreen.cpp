#include "mesh/GeoScreen.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "deck/Config.hpp"

namespace stentor {
namespace {

namespace fs = std::filesystem;

// The .geo text with comments removed and string literals kept apart: `code` has every
// comment and every string's contents replaced by spaces (newlines kept, so offsets
// give line numbers); `strings[i]` is the literal that starts at `string_at[i]`.
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
    } else if (t[i] == '"') {
      s.string_at.push_back(i);
      std::string lit;
      ++i;
      while (i < t.size() && t[i] != '"') {
        if (t[i] == '\\' && i + 1 < t.size()) lit += t[i], blank(i++);
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
      word == "OnelabAction")
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
    std::size_t e = next + 1;
    while (e < code.size() && ident_char(code[e])) ++e;
    const std::string opt = code.substr(next + 1, e - next - 1);
    if (word == "Solver" || opt.find("FileName") != std::string::npos || opt.rfind("Save", 0) == 0 ||
        opt.find("Executable") != std::string::npos)
      return "sets an option that names a file or program (" + word + "." + opt + ")";
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
    if (word == "Include" || word == "Merge") {
      const std::string f = literal_after(s, e);
      if (f.empty())
        throw InputError(where + "'" + word + "' needs a literal \"file\" name (computed names are refused)");
      fs::path p(f);
      if (p.is_relative()) p = fs::path(dir) / p;
      std::string ext = p.extension().string();
      for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      if (ext == ".geo") {
        std::ifstream in(p);
        if (!in) throw InputError(where + "cannot read the included file '" + p.string() + "'");
        std::stringstream ss;
        ss << in.rdbuf();
        screen_geo_text(ss.str(), p.string(), p.parent_path().string(), depth + 1);
      }
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
