// Screening of gmsh .geo text before gmsh runs it. The .geo language can run programs
// (SystemCall), write files (Printf > "f", Save, Print, CreateDir, ...), end the process
// (Exit) or mesh without Stentor's bounds (Mesh 3;, RefineMesh). A deck's mesh is input,
// never a program: such commands are refused before gmsh sees the file.
#pragma once
#include <string>

namespace stentor {

// Reads `file` (and, recursively, every file it Includes, Merges or
// MergeWithBoundingBox's by a literal name: an Include'd file is .geo text whatever its
// name, a Merge'd one too unless it is a .msh (then the .msh screen) or a CAD/mesh data
// format; a name that is not a regular file, /dev/zero say, is refused) and throws
// InputError("<file>:<line>: ...") at the first command that runs a program, writes or
// deletes a file, ends the process, waits, meshes by itself, sets a General/Solver option
// that names a file or program or General.AbortOnError, or a Printf/Sprintf whose format
// is not a literal with numeric conversions (gmsh hands it to sprintf: %s or %n crash it).
// Comments and string contents are not commands; strings are "..." or '...', with no
// escapes, as gmsh's lexer reads them. Throws InputError when a file cannot be read.
void screen_geo_file(const std::string& file);

// The same check on `text` (for tests): `name` is the file name used in messages and
// `dir` the folder relative to which Include/Merge names are resolved.
void screen_geo_text(const std::string& text, const std::string& name, const std::string& dir, int depth = 0);

}  // namespace stentor
