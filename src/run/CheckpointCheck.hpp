// A checkpoint read for a restart is untrusted input (any HDF5 file can be edited): before
// any of it is used, every scalar and table the restart reads is checked against the
// deck and the mesh. io/Checkpoint.cpp has already checked the file's form (types,
// shapes, finite values, ids unique and not negative, the payload checksum); this checks
// what the values mean:
// - scalars: each in its range (rules in scalar_rules(): counters within int, times
//   within the procedure, steps positive); the stage's interval holds the time;
// - node tables (u, u_before_last, the time scheme's vectors): dim columns, ids mesh
//   nodes; Gauss-point tables: ids mesh cells; contact tables: ids mesh nodes, the state
//   a contact state, the master facets facets of the pair's master surface (-1: none),
//   the flags 0 or 1.
// A field added to the checkpoint gets its rule in scalar_rules() (or table_kind()).
#pragma once
#include <string>

#include "io/Checkpoint.hpp"

namespace stentor {

struct Model;

// The first problem found on this rank ("" when none), naming `path` and the dataset
// (/ints/step, /tables/u/values, ...) and what was expected.
std::string checkpoint_problem(const Model& m, const CheckpointData& d, const std::string& path);

}  // namespace stentor
