// Screening of gmsh .geo text before gmsh runs it. The .geo language can run programs
// (SystemCall), write files (Printf > "f", Save, Print, CreateDir, ...), end the process
// (Exit) or mesh without Stentor's bounds (Mesh 3;, RefineMesh). A deck's mesh is input,
// never a program: such statements are refused before gmsh sees the file. (gmsh itself
// then runs in a process confined by the kernel: mesh/Confine.hpp.)
//
// The screen reads the text as gmsh 4.8.4's lexer and grammar do (Parser/Gmsh.l, Gmsh.y)
// and decides on what a statement does, not on how it is spelt:
//  - tokens: "..." and '...' strings with no escapes, comments, numbers, names, gmsh's
//    operators; any other character outside strings and comments is refused;
//  - every keyword of gmsh's lexer is either allowed or refused (Exit, Abort, OnelabRun,
//    Plugin, SetString/SetNumber, ShapeFromFile, ListFromFile, RefineMesh, GUI and
//    post-processing commands...);
//  - a name that starts a statement and takes arguments is a command (gmsh compares the
//    name: Save, Print, SystemCall, Mesh, ...): only Include, Merge, MergeWithBoundingBox
//    of a literal file name and `Background Field` pass, any other is refused, known or not;
//  - Printf/Error/Warning(...) followed by > or >> is refused whatever forms the target;
//    a Printf/Sprintf format must be a literal with numeric conversions;
//  - option assignments: every Solver option, gmsh's string options (file and program
//    names, commands), General options but Terminal/Verbosity/ExpertMode, fields of type
//    ExternalProcess/Structured/PostView and field options naming files or programs.
// It holds at any depth: inside loops, If blocks and macros (their text is screened
// where it stands) and in every file included or merged (an Include'd file is .geo
// text whatever its name, a Merge'd one too unless it is a .msh (then the .msh screen)
// or a CAD/mesh data format; and the <file>.opt that gmsh merges after each file it
// reads; a name that is not a regular file, /dev/zero say, is
// refused). A refusal is an InputError "<file>:<line>: '<statement>' <why>".
// Files larger than the input size limits (deck/InputLimits.hpp) are refused unread.
#pragma once
#include <string>
#include <vector>

namespace stentor {

// Screens `file` and everything it includes; returns the files read (`file` first).
// Throws InputError at the first refused statement, or when a file cannot be read.
// Test hook: STENTOR_TEST_NO_GEO_SCREEN=1 turns the screen off (returns {file}), to show
// that the confinement of gmsh's process alone stops a write (tests/cli/geo_confine.sh).
std::vector<std::string> screen_geo_file(const std::string& file);
bool geo_screen_disabled();

// The same check on `text` (for tests): `name` is the file name used in messages and
// `dir` the folder relative to which Include/Merge names are resolved; the files read
// are appended to `files` when given.
void screen_geo_text(const std::string& text, const std::string& name, const std::string& dir, int depth = 0,
                     std::vector<std::string>* files = nullptr);

// Screens <file>.opt when it exists (gmsh merges it after reading `file`).
void screen_options_file(const std::string& file, int depth, std::vector<std::string>* files);

// Screens the file an Include/Merge/MergeWithBoundingBox names (`where`: "<file>:<line>: ").
void screen_included(const std::string& where, const std::string& word, const std::string& file, int depth,
                     std::vector<std::string>* files);

}  // namespace stentor
