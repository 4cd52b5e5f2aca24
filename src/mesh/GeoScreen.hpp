// Screening of gmsh .geo text before gmsh runs it. The .geo language can run programs
// (SystemCall), write files (Printf > "f", Save, Print, CreateDir, ...), end the process
// (Exit) or mesh without Stentor's bounds (Mesh 3;, RefineMesh). A deck's mesh is input,
// never a program: such commands are refused before gmsh sees the file.
#pragma once
#include <string>

namespace stentor {

// Reads `file` (and, recursively, every .geo it Includes or Merges by a literal file
// name) and throws InputError("<file>:<line>: ...") at the first command that runs a
// program, writes or deletes a file, ends the process, waits, meshes by itself, or sets
// a General/Solver option that names a file or program. Comments and string contents
// are not commands. Throws InputError when a file cannot be read.
void screen_geo_file(const std::string& file);

// The same check on `text` (for tests): `name` is the file name used in messages and
// `dir` the folder relative to which Include/Merge names are resolved.
void screen_geo_text(const std::string& text, const std::string& name, const std::string& dir, int depth = 0);

}  // namespace stentor
