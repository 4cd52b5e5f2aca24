// The fields a run can write to <basename>.h5/.xdmf, and the resolution of
// "Output->field list" against them (docs/deck.md, "Outputs"). Teuchos-free.
//
// The catalogue is the one list of field names: the deck reader validates against it, the
// reporter writes what it resolved to, and a test checks that docs/deck.md's "Outputs"
// table names every entry.
#pragma once
#include <string>
#include <vector>

namespace stentor {

struct OutputField {
  enum class Where { Node, Cell };
  // What the deck must have for the field to exist.
  enum class Needs { Nothing, Dynamics, Contact, MasterSurface, Plasticity, Damage, StentInArtery };
  const char* name;
  Where where;
  int components;        // 1, 3 (vector) or 6 (symmetric tensor xx, yy, zz, xy, yz, xz; stored as 3 x 3)
  const char* quantity;  // unit: "length", "velocity", "stress", "force", "-" (dimensionless), "" (an index)
  Needs needs;
  bool standard;         // in the default set (the fields every run wrote before field lists)
  const char* doc;       // one line
};

// Every field, in the order they are written.
const std::vector<OutputField>& output_fields();

// What a deck has, for OutputField::Needs.
struct OutputDeckTraits {
  bool dynamic = false, contact = false, master_surface = false, plastic = false, damage = false;
  bool stent_in_artery = false;  // a generated stent in a generated artery with Output->Stent Metrics
};
bool output_field_available(const OutputField& f, const OutputDeckTraits& d);
// Why a field is not available ("needs ..."), for the error message.
std::string output_field_needs_text(OutputField::Needs n);

// Resolves "Output->field list": names separated by commas and/or spaces, plus `default`
// (the standard set, those of them the deck has) and `all` (every field the deck has).
// Returns the names in catalogue order. Throws std::invalid_argument with the reason
// (unknown name and the valid ones, a field the deck cannot have, a name twice, empty).
std::vector<std::string> resolve_output_fields(const std::string& list, const OutputDeckTraits& d);

}  // namespace stentor
