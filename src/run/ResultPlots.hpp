// The PNG plots of a finished run (Reporter::finish), made from its CSV files with gnuplot
// (io/Plot.hpp; each PNG has its script <name>.gp beside it, data inline). Axis labels carry
// the deck's units (Problem->units, io/Units.hpp; per unit thickness in 2D), legends say
// what each curve is. A plot is made only for data the run produced:
//   <b>_reactions.png          reaction force of each Dirichlet set vs time
//   <b>_reaction_<set>.png     reaction vs the set's prescribed displacement, for each set
//                              with a non-zero prescribed value (not for clamps)
//   <b>_probes.png             probe displacements vs time (Output->Probes)
//   <b>_contact.png            normal contact force of each pair vs time (Contact)
//   <b>_energy.png             dynamics only: every term of the energy balance,
//                              kinetic, strain, their sum, external and support work,
//                              viscous and plastic dissipation, contact work, frictional
//                              dissipation, and the balance error
//                              E - E_0 - (W_ext + W_sup + W_contact - D - D_friction)
//   <b>_balance.png            dynamics only: that balance per step
//   <b>_radii.png, _stresses.png   Output->Stent Metrics of a stent in an artery
//   <b>_diameters.png          Output->Stent Metrics of a generated stent: outer diameters
//                              (stent, each ring and its crowns, the links) vs time, the
//                              stages' ends and the peak of the expansion marked
// Time axes start at t = 0. The history CSV begins with the first step; its plots get the
// initial state as their first point: probes their displacement at t = 0, reactions and
// contact forces 0 when the initial state is at rest and unloaded (InitialState), else
// their curves begin at the first step.
#pragma once
#include <string>
#include <vector>

namespace stentor {

struct Model;

// What the plots know of t = 0 besides the CSV files (Reporter captures it at t = 0; a
// restarted run does not know it).
struct InitialState {
  bool known = false;                // captured at t = 0 (false after --restart)
  std::vector<double> probes;        // displacement of each probe, 3 values each
  bool at_rest_unloaded = false;     // no initial displacement or velocity, every load 0 at t = 0,
                                     // no initial penetration: reactions and contact forces are 0
};

// True when the deck's initial state is at rest and unloaded, before contact is looked at
// (InitialState::at_rest_unloaded also needs no initial penetration).
bool deck_at_rest_unloaded(const Model& m);

// Rank 0, after the CSV files are closed. `stem`: <folder>/<basename>; `radius_columns`,
// `stress_columns`, `diameter_columns`: the Stent Metrics columns worth a plot (empty
// without them).
// Returns the names of the PNG files written (no path).
std::vector<std::string> write_result_plots(const Model& m, const std::string& stem, const InitialState& init,
                                            const std::vector<std::string>& radius_columns,
                                            const std::vector<std::string>& stress_columns,
                                            const std::vector<std::string>& diameter_columns = {});

}  // namespace stentor
