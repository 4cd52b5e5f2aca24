// The deck reader (deck/Config.cpp: the XML and schema passes, typed access, read(); the
// sections in ConfigModel.cpp, ConfigLoads.cpp and ConfigStages.cpp) and the helpers its
// parts share. Internal to the deck library: only deck/Config*.cpp include it.
#pragma once
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLObject.hpp>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "deck/Config.hpp"
#include "deck/Schema.hpp"

namespace stentor::deck_reader {

namespace fs = std::filesystem;
using Teuchos::ParameterEntry;
using Teuchos::ParameterList;
using Teuchos::XMLObject;

std::string lower(std::string s);
std::string upper(std::string s);
std::string trim(const std::string& s);
std::string num(double v);  // 15 significant digits
std::string join(const std::vector<std::string>& v, const std::string& sep = ", ");
std::string child_path(const std::string& path, const std::string& name);
std::string quoted(const std::string& path);

// The most steps a procedure may take (all stages together): the run counts steps and
// attempts in int, and caps the attempts at 100 x steps + 1000 (Stepping->max steps).
constexpr long long kMaxTotalSteps = 20000000;

class DeckReader {
 public:
  explicit DeckReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& msg) const { throw InputError(file_ + ": " + msg); }

  Config read();

 private:
  std::string file_;  // as given by the user: every message starts with it
  Config cfg_;

  // ---- pass 0: the raw text (nesting depth, before Teuchos recurses over it) ----
  void check_nesting() const;
  // ---- pass 1: the raw XML tree (before Teuchos converts and merges values) ----
  void check_xml(const XMLObject& x, const std::string& path, bool passthrough) const;

  // ---- pass 2: the ParameterList against the schema ----
  void check_list(const ParameterList& pl, const std::string& path, const std::vector<const ListSpec*>& specs) const;
  void check_param(const ParameterEntry& e, const std::string& path, const ParamSpec& p) const;
  void require(const ParameterList& pl, const std::string& path, const std::vector<const ListSpec*>& specs) const;

  // Typed access (after check_list): the value, or the schema default when absent.
  static const ParamSpec& spec(const ListSpec& ls, const std::string& name) {
    const ParamSpec* p = ls.find(name);
    if (!p) throw std::logic_error("stentor deck: no parameter '" + name + "' in schema list '" + ls.key + "'");
    return *p;
  }
  double get_double(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  int get_int(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  bool get_bool(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  std::string get_string(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;
  std::vector<double> get_array(const ParameterList& pl, const ListSpec& ls, const std::string& name) const;

  void read_problem(const ParameterList& pl);
  void read_mesh(const ParameterList& pl);
  void read_stent(const ParameterList& pl);
  void read_artery(const ParameterList& pl, bool around_stent);
  void read_balloon(const ParameterList& pl);
  void check_stent_plastic() const;
  void read_materials(const ParameterList& pl);
  void read_elastic_constants(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const;
  void read_fibres(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m);
  void read_inelastic(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const;
  void read_hardening(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const;
  void read_bodies(const ParameterList& pl);
  void read_loads(const ParameterList& pl);
  void read_fluid_cavity(const ParameterList& sub, const ListSpec& ls, const std::string& path, LoadConfig& lc);
  void read_stepping(const ParameterList& pl);
  void read_initial(const ParameterList& pl);
  void read_time(const ParameterList& pl);
  void read_newton(const ParameterList& pl);
  void read_linear(const ParameterList& pl);
  void read_output(const ParameterList& pl);
  void resolve_output();  // after Contact and Stages: field names and output times
  void merge_output_interval(OutputConfig& o, double end) const;
  Ramp read_ramp(const ParameterList& pl, const std::string& path, const ListSpec& ls, const std::string& key = "ramp") const;
  void read_contact(const ParameterList& pl);
  void read_stages(const ParameterList& pl, const ParameterList* stepping);
  void read_body_initial_state(const ParameterList& sub, const std::string& path, BodyConfig& b);
  void check_analysis(bool initial_conditions, bool time_integration);
  void read_stage_analysis(const ParameterList& sub, const std::string& path, StageConfig& st);
  std::vector<bool> read_active(const ParameterList& sub, const std::string& path, const std::string& key,
                                const std::vector<std::string>& names, const std::string& what) const;
  void read_stage_ramps(const ParameterList& sub, const std::string& path, std::size_t k);
  void read_contact_obstacle(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c);
  void read_stent_metrics(const ParameterList& sub);
  void read_obstacle_axis(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c);
  // Records a dimension-dependent vector (Config::dim_vectors) and, when Mesh->dimension is
  // set, checks it now. in2d / in3d: the number of values a 2D / 3D problem takes.
  void check_dim_length(const std::vector<double>& v, const std::string& path, int in2d = 2, int in3d = 3);
  void check_step(double step, double end, const std::string& what) const;
  void check_safe_name(const std::string& text, const std::string& path, const std::string& what) const;
  void unit_direction(std::array<double, 3>& v, const std::string& path) const;
};

}  // namespace stentor::deck_reader
