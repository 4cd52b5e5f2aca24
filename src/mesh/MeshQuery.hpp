// Looking up physical groups of a Mesh by name. The throwing lookups raise
// InputError "physical group 'left' not found in mesh <file>; available boundary
// groups: bottom, left, ..." so a misspelled deck name is easy to fix.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

bool has_volume_group(const Mesh& m, const std::string& group);
bool has_boundary_group(const Mesh& m, const std::string& group);

// All blocks (one per cell type) of the named group; throws InputError if none.
std::vector<const CellBlock*> volume_blocks(const Mesh& m, const std::string& group);
std::vector<const CellBlock*> boundary_blocks(const Mesh& m, const std::string& group);

// Throws InputError "'<parameter>' = '<group>': physical group ... not found ...;
// available ... groups: ..." unless the mesh has the named boundary (or volume) group.
void require_group(const Mesh& m, const std::string& group, bool boundary, const std::string& parameter);

// Sorted, unique node ids of all cells of the named boundary group (facets,
// edges or points); throws InputError if the group is missing.
std::vector<GId> boundary_nodes(const Mesh& m, const std::string& group);

// Sorted, unique node ids of all cells of the named volume group; throws if missing.
std::vector<GId> volume_nodes(const Mesh& m, const std::string& group);

// Tributary (lumped) reference area of each node of a boundary group's facets: the row sums
// of the facet mass matrix scaled diagonally (HRZ), so quadratic facets get positive areas
// (contact's per-area c_normal and c_tangent, the artery metrics' malapposed area).
// Axisymmetric: the areas of the revolved facets (dA = 2 pi r ds).
std::map<GId, double> tributary_areas(const Mesh& mesh, const std::string& group, bool axisymmetric = false);

// The same split by facet: classify(the facet's reference centroid) gives the index of the
// class it belongs to (0 .. classes - 1, or -1: left out); one map per class (a node on
// facets of two classes has its share in both).
std::vector<std::map<GId, double>> tributary_areas_by(const Mesh& mesh, const std::string& group, int classes,
                                                      const std::function<int(const double*)>& classify);

// The connected parts of a boundary group: facets that share a node are one part. Each
// node of the group's facets maps to its part's index, 0 .. parts - 1 in the order of the
// parts' smallest node id (the same numbering on every rank, which holds the whole group).
std::map<GId, int> surface_parts(const Mesh& mesh, const std::string& group);

}  // namespace stentor
