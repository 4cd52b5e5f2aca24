// Mesh->Parameters: numbers for a .geo file's DefineNumber parameters (gmsh's -setnumber).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace Teuchos {
class ParameterList;
}

namespace stentor {

// The entries of `pl` (Mesh->Parameters) as (ONELAB name, value) in deck order: a name
// without '/' becomes "Parameters/<name>" (the .geo's `DefineNumber[..., Name
// "Parameters/<name>"]`), one with '/' is taken as the full ONELAB name. Throws InputError
// (prefixed by `deck`) naming the entry for a sublist, a value that is not a finite double
// or int, a name of characters other than letters, digits, space and `_ . - /`, or two
// entries with the same ONELAB name.
std::vector<std::pair<std::string, double>> read_mesh_parameters(const Teuchos::ParameterList& pl, const std::string& deck);

}  // namespace stentor
