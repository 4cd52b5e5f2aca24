// Loads and constraints resolved against the mesh: deck names -> node and facet lists.
// Trilinos-free; the assembler turns these into local index arrays.
#pragma once
#include <array>
#include <utility>
#include <string>
#include <vector>

#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

struct DirichletSet {
  std::string name, group;
  std::vector<GId> nodes;            // sorted, unique
  std::array<bool, 3> components{};
  std::array<double, 3> values{};      // full value, multiplied by ramp(t)
  std::function<std::array<double, 3>(const double*)> field;  // if set: value at X instead of `values`
  Ramp ramp;
  // `components` = normal: the displacement along the unit normal n of the (planar) group is
  // normal_value times the ramp; the other directions are free (a roller or symmetry plane
  // at any angle). n points out of the body (the side of the cells that touch the group).
  // `components` is then all (the reaction is a vector along n) and `values` zeros.
  bool normal = false;
  std::array<double, 3> n{};
  double normal_value = 0.0;
};

// Traction (dead load on the reference area) or follower pressure on boundary facets.
struct FacetLoad {
  LoadConfig::Type type = LoadConfig::Type::Traction;
  std::string name, group;
  CellType facet_type = CellType::Invalid;
  int nodes_per_facet = 0;
  std::vector<GId> conn;             // facet nodes, gmsh order
  std::vector<double> orientation;     // +1 if the reference normal (see fem/Geometry.hpp) points out of the body, else -1
  std::vector<GId> adjacent_cell;    // global id of the volume cell the facet bounds (decides which rank integrates it)
  std::array<double, 3> traction{};    // Traction: force per reference area
  double pressure = 0.0;               // Pressure: acts along -n (current configuration)
  int cavity = -1;                     // FluidCavity: index into Loads::cavities (its pressure is the cavity's)
  Ramp ramp;
  std::size_t num_facets() const { return nodes_per_facet ? conn.size() / nodes_per_facet : 0; }
};

struct BodyForce {
  std::string name;
  std::vector<int> volume_blocks;      // indices into Mesh::volumes
  std::array<double, 3> force{};       // per unit reference volume
  std::function<std::array<double, 3>(const double*)> field;  // if set: force density at X instead of `force`
  Ramp ramp;
};

// A fluid cavity's law (LoadConfig::FluidCavity); its wall is the FacetLoads with `cavity` = its index.
struct FluidCavitySpec {
  std::string name, group;
  double volume_ratio = 1.0, bulk_modulus = 0.0;
  std::array<double, 3> point{}, axis{0.0, 0.0, 1.0};
  Ramp ramp;
};

struct Loads {
  std::vector<DirichletSet> dirichlet;
  std::vector<FluidCavitySpec> cavities;
  std::vector<FacetLoad> facet_loads;
  std::vector<BodyForce> body_forces;
};

// The facets of a boundary group, one entry per cell type, each oriented outward.
struct OrientedFacets {
  CellType type = CellType::Invalid;
  int nodes_per_facet = 0;
  std::vector<GId> conn;             // facet nodes, gmsh order
  std::vector<double> orientation;   // +1 if the reference normal (fem/Geometry.hpp) points out of the body, else -1
  std::vector<GId> adjacent_cell;    // global id of the volume cell the facet bounds
  std::size_t num_facets() const { return nodes_per_facet ? conn.size() / nodes_per_facet : 0; }
};
// Throws InputError (prefixed by `where`) when the group is missing, has cells of the
// wrong dimension, or a facet bounds no volume cell.
std::vector<OrientedFacets> oriented_facets(const Mesh& mesh, const std::string& group, const std::string& where);

// Throws InputError naming the load and the missing/unsuitable physical group.
Loads resolve_loads(const Config& cfg, const Mesh& mesh);

// Material of each volume block (index into cfg.materials), from the deck's bodies.
// Throws InputError when a body names no group of the mesh or a volume group has no body.
std::vector<int> block_materials(const Config& cfg, const Mesh& mesh);

}  // namespace stentor
