// Screening of a gmsh .msh file before gmsh reads it. gmsh 4.8 trusts the counts in a
// 4.x ASCII $Nodes section: a header that declares fewer nodes than its blocks hold
// makes it crash (SIGSEGV), and a header of 0 nodes made it hang. The counts are
// checked here first, so such a file is an input error naming the file.
#pragma once
#include <string>

namespace stentor {

// For a gmsh 4.x ASCII file, throws InputError("<file>: $Nodes section: ...") unless
// every $Nodes section's header (blocks, nodes, min tag, max tag) agrees with its
// blocks, every node tag lies in [min tag, max tag] and every coordinate is a finite
// number. Other files (MSH 2, binary, parametric node blocks) are left to gmsh.
void screen_msh_file(const std::string& file);

}  // namespace stentor
