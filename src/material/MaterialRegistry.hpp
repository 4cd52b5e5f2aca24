// The registration point of the material laws (docs/plasticity.md, "Adding a material").
//
// Material is the law of a mesh block: one of the types listed in the variant below.
// ElasticLaw stands for every stateless hyperelastic law (one device-side switch over
// them, ElasticLaw.hpp, so one kernel serves them all); each law with Gauss-point history
// (the interface of MaterialState.hpp) is a type of its own. The Assembler takes the held
// type on the host once per block (std::visit) and runs kernels compiled for that type:
// no virtual call and no per-point branch on the law on the device, history views only
// for blocks whose law has history, and the kernels, history views and cell output are
// written once for all laws (src/assembly never names a law).
//
// make_material maps the deck's model name and constants (deck/Config.cpp validates them)
// to the law: `Ciarlet-Geymonat plasticity`, `neo-Hookean plasticity`, `neo-Hookean damage`
// and the stateless laws of elastic_law. A caller may also build any law itself and hand
// it to the Assembler's constructor that takes the laws (tests/system/test_material_dispatch.cpp).
#pragma once
#include <type_traits>
#include <variant>

#include "deck/Config.hpp"
#include "material/Damage.hpp"
#include "material/ElasticConstants.hpp"
#include "material/ElasticLaw.hpp"
#include "material/MaterialState.hpp"
#include "material/NeoHookean.hpp"
#include "material/Plasticity.hpp"

namespace stentor {

// Miehe's discontinuous damage over the neo-Hookean law (Damage.hpp).
using NeoHookeanDamage = IsotropicDamage<NeoHookean>;

// Every law a block can have. A new law with history is added here (and, when a deck may
// name it, in make_material below).
using Material = std::variant<ElasticLaw, CiarletGeymonatPlasticity, NeoHookeanPlasticity, NeoHookeanDamage>;

// The stateless law of a material; a new hyperelastic law also goes into ElasticLaw's switch.
inline ElasticLaw elastic_law(const MaterialConfig& m) {
  if (m.model == "neo-Hookean") return ElasticLaw::neo_hookean(NeoHookean{m.mu, m.lambda});
  if (m.model == "Mooney-Rivlin") {
    const MooneyRivlinCoefficients c = mooney_rivlin_from_lame(Lame{m.mu, m.lambda}, m.C2);
    return ElasticLaw::mooney_rivlin(MooneyRivlin{c.C1, c.C2, c.lam});
  }
  if (m.model == "Holzapfel-Gasser-Ogden") {
    const HolzapfelGasserOgden h{NeoHookean{m.mu, m.lambda}, m.k1, m.k2, {1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, m.kappa, m.anisotropy};
    const FibreFrame f{{m.axis_point[0], m.axis_point[1], m.axis_point[2]},
                       {m.axis[0], m.axis[1], m.axis[2]},
                       m.fibre_angle * 3.14159265358979323846 / 180.0,
                       m.centreline_radius,
                       {m.bend_direction[0], m.bend_direction[1], m.bend_direction[2]}};
    return ElasticLaw::holzapfel_gasser_ogden(h, f);
  }
  return ElasticLaw::ciarlet_geymonat(CiarletGeymonat{m.C1, m.C2, m.D});
}

// The nonlinear part of a plastic material's hardening (`hardening law`, IsotropicHardening.hpp).
inline NonlinearHardening nonlinear_hardening(const MaterialConfig& m) {
  if (m.hardening_law == "Voce") return NonlinearHardening::voce(m.yield_stress, m.saturation_stress, m.saturation_rate);
  if (m.hardening_law == "table")
    return NonlinearHardening::table(m.table_strains.data(), m.table_stresses.data(),
                                     static_cast<int>(m.table_strains.size()));
  return NonlinearHardening{};
}

// The deck's `plastic dynamic step`.
inline PlasticDynamicStep plastic_dynamic_step(const MaterialConfig& m) {
  if (m.plastic_dynamic_step == "lagged") return PlasticDynamicStep::kLagged;
  if (m.plastic_dynamic_step == "mean value") return PlasticDynamicStep::kMeanValue;
  return PlasticDynamicStep::kIncrementalPotential;
}

// The law of a deck material.
inline Material make_material(const MaterialConfig& m) {
  if (m.model == "Ciarlet-Geymonat plasticity")
    return CiarletGeymonatPlasticity{CiarletGeymonat{m.C1, m.C2, m.D}, m.yield_stress, m.hardening,
                                     plastic_dynamic_step(m), nonlinear_hardening(m)};
  if (m.model == "neo-Hookean plasticity")
    return NeoHookeanPlasticity{NeoHookean{m.mu, m.lambda}, m.yield_stress, m.hardening, plastic_dynamic_step(m),
                                nonlinear_hardening(m)};
  if (m.model == "neo-Hookean damage")
    return NeoHookeanDamage{NeoHookean{m.mu, m.lambda}, m.saturation_damage, m.damage_energy_scale};
  return elastic_law(m);
}

// ---- Generic over the list (nothing below changes when a law is added).

// The history a law declares: kNumHist doubles per Gauss point described by vars
// (size 0, vars nullptr for a stateless law).
struct HistoryLayout {
  int size = 0;
  const HistoryVar* vars = nullptr;
};
inline HistoryLayout history_layout(const Material& m) {
  return std::visit(
      [](const auto& law) {
        using Law = std::decay_t<decltype(law)>;
        if constexpr (kHasHistory<Law>)
          return HistoryLayout{Law::kNumHist, Law::kHistory};
        else
          return HistoryLayout{};
      },
      m);
}

// The sum of kNumHist over the listed laws: a compile-time bound on the history columns
// of any deck (kernel-local arrays).
template <class V>
struct TotalHistorySize;
template <class... Laws>
struct TotalHistorySize<std::variant<Laws...>> : std::integral_constant<int, (LawHistorySize<Laws>::value + ... + 0)> {};
inline constexpr int kMaxHistoryColumns = TotalHistorySize<Material>::value;

}  // namespace stentor
