#include "deck/OutputFields.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

#include "deck/Schema.hpp"

namespace stentor {

namespace {
using W = OutputField::Where;
using N = OutputField::Needs;
}  // namespace

const std::vector<OutputField>& output_fields() {
  static const std::vector<OutputField> f = {
      {"displacement", W::Node, 3, "length", N::Nothing, true, "Displacement u (z = 0 in 2D)."},
      {"velocity", W::Node, 3, "velocity", N::Dynamics, false, "Velocity v_{n+1} of the time scheme."},
      {"reaction_force", W::Node, 3, "force", N::Nothing, false,
       "Support reaction: the residual f_int - f_ext (+ inertia) at constrained dofs, 0 at free ones."},
      {"cauchy_stress_nodal", W::Node, 6, "stress", N::Nothing, false,
       "cauchy_stress recovered at the nodes: reference-volume-weighted mean of the cells of the node's body."},
      {"von_mises_nodal", W::Node, 1, "stress", N::Nothing, false, "von_mises recovered at the nodes, as cauchy_stress_nodal."},
      {"cauchy_stress", W::Cell, 6, "stress", N::Nothing, true, "Cauchy stress, mean over the cell's Gauss points."},
      {"von_mises", W::Cell, 1, "stress", N::Nothing, true, "von Mises stress sqrt(3/2 s:s) of the cell's cauchy_stress."},
      {"principal_stress", W::Cell, 3, "stress", N::Nothing, false,
       "Eigenvalues of the cell's cauchy_stress, largest first."},
      {"green_lagrange_strain", W::Cell, 6, "-", N::Nothing, false,
       "Green-Lagrange strain E = (C - I)/2 (tensor components), mean over the Gauss points."},
      {"log_strain", W::Cell, 6, "-", N::Nothing, false,
       "Logarithmic (Hencky) strain ln V = ln(b)/2, b = F F^T (spatial, Abaqus' LE), mean over the Gauss points."},
      {"J", W::Cell, 1, "-", N::Nothing, true, "Volume ratio det F, mean over the cell."},
      {"mpi_rank", W::Cell, 1, "", N::Nothing, true, "MPI rank that owns the cell."},
      {"equivalent_plastic_strain", W::Cell, 1, "-", N::Plasticity, true, "Equivalent plastic strain alpha (plastic bodies)."},
      {"mandel_hill_norm", W::Cell, 1, "stress", N::Plasticity, true, "Norm of the Mandel stress in the yield function."},
      {"yielding", W::Cell, 1, "", N::Plasticity, true, "1 where the last step yielded, else 0."},
      {"plastic_dissipation", W::Cell, 1, "stress", N::Plasticity, true, "Accumulated plastic dissipation per volume [J/m^3 = Pa]."},
      {"damage", W::Cell, 1, "-", N::Damage, true, "Damage d in [0, saturation damage) (neo-Hookean damage bodies)."},
      {"max_virgin_energy", W::Cell, 1, "stress", N::Damage, true,
       "Largest virgin strain-energy density alpha reached, which sets d [J/m^3 = Pa]."},
      {"damage_dissipation", W::Cell, 1, "stress", N::Damage, true, "Accumulated damage dissipation per volume [J/m^3 = Pa]."},
      {"contact_status", W::Node, 1, "", N::Contact, true, "-1 not a slave node, 0 free (not checked), 1 inactive (checked, apart), 2 stick, 3 slip."},
      {"contact_gap", W::Node, 1, "length", N::Contact, true, "Normal gap of slave nodes (NaN on other nodes)."},
      {"contact_lambda_normal", W::Node, 1, "force", N::Contact, true, "Normal contact force of slave nodes."},
      {"contact_pressure", W::Node, 1, "stress", N::Contact, true, "Contact pressure: normal contact force per reference area, recovered on the slave surface."},
      {"contact_lambda_tangent", W::Node, 3, "force", N::Contact, true, "Tangential (friction) force of slave nodes."},
      {"contact_slip", W::Node, 3, "length", N::Contact, true, "Tangential relative displacement of slave nodes over the last step."},
      {"contact_master_traction", W::Node, 3, "stress", N::MasterSurface, true,
       "Reaction on the master surface per reference area, recovered like contact_pressure."},
      {"contact_master_pressure", W::Node, 1, "stress", N::MasterSurface, true,
       "Contact pressure on the master side: the normal force (along the contact normal, compression > 0) per reference area, recovered like contact_pressure; equals it across a pair in equilibrium."},
      {"wall_gap", W::Node, 1, "length", N::StentInArtery, true,
       "The malapposition map: the signed distance of the stent's outer nodes to the lumen (> 0 off the wall, 0 in contact; NaN on other nodes), as the stent_wall_gap_max metric."},
  };
  return f;
}

bool output_field_available(const OutputField& f, const OutputDeckTraits& d) {
  switch (f.needs) {
    case N::Nothing: return true;
    case N::Dynamics: return d.dynamic;
    case N::Contact: return d.contact;
    case N::MasterSurface: return d.master_surface;
    case N::Plasticity: return d.plastic;
    case N::Damage: return d.damage;
    case N::StentInArtery: return d.stent_in_artery;
  }
  return false;
}

std::string output_field_needs_text(OutputField::Needs n) {
  switch (n) {
    case N::Nothing: return "";
    case N::Dynamics: return "needs 'Problem->analysis' = dynamic";
    case N::Contact: return "needs a 'Contact' sublist";
    case N::MasterSurface: return "needs a contact pair with a 'master' surface";
    case N::Plasticity: return "needs a body of model 'Ciarlet-Geymonat plasticity' or 'neo-Hookean plasticity'";
    case N::Damage: return "needs a body of model 'neo-Hookean damage'";
    case N::StentInArtery: return "needs 'Mesh->generator' = stent with 'Mesh->Artery' and 'Output->Stent Metrics'";
  }
  return "";
}

std::vector<std::string> resolve_output_fields(const std::string& list, const OutputDeckTraits& d) {
  const auto& all = output_fields();
  std::vector<char> chosen(all.size(), 0), given(all.size(), 0);
  std::string tokens = list;
  std::replace(tokens.begin(), tokens.end(), ',', ' ');
  std::istringstream is(tokens);
  std::string tok;
  bool any = false;
  std::vector<std::string> names{"default", "all"};
  for (const auto& f : all) names.push_back(f.name);
  while (is >> tok) {
    any = true;
    std::string t = tok;
    for (auto& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (t == "default" || t == "all") {
      for (std::size_t i = 0; i < all.size(); ++i)
        if ((t == "all" || all[i].standard) && output_field_available(all[i], d)) chosen[i] = 1;
      continue;
    }
    std::size_t i = 0;  // case-insensitive, as other deck names
    while (i < all.size() && edit_distance_ci(all[i].name, tok) != 0) ++i;
    if (i == all.size()) {
      std::string valid;
      for (const auto& n : names) valid += (valid.empty() ? "" : ", ") + n;
      const std::string near = nearest_name(tok, names);
      throw std::invalid_argument("'" + tok + "' is not a field" + (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                                  "; valid names: " + valid);
    }
    if (given[i]) throw std::invalid_argument("lists '" + tok + "' twice");
    given[i] = 1;
    if (!output_field_available(all[i], d))
      throw std::invalid_argument("'" + tok + "' " + output_field_needs_text(all[i].needs));
    chosen[i] = 1;
  }
  if (!any) throw std::invalid_argument("names no field (set 'Output->fields' = false to write none)");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (chosen[i]) out.push_back(all[i].name);
  return out;
}

}  // namespace stentor
