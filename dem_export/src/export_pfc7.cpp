// Thesis macro-element sets as the PFC7 commands of the public plugin
// (marcoprevitali/macroelement-doubletwist-PFC7, example_cases/*/load_properties.dat): one
// `contact cmat add` per set, with the plugin's property names. Our thesis keys hold the same
// numbers in the same units as the plugin's properties (the published sets were read from those
// files), so values are written unchanged; rotations stay in the plugin's degree convention.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "dtwire/dem/export.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::dem {
namespace {

struct Pfc7Property {
  const char* property;  // the plugin's name
  const char* key;       // ours
};

// Order and names as the plugin's load_properties.dat.
constexpr Pfc7Property kProperties[] = {
    {"me_ea", "EA_N"},      {"me_ei", "EI_Nm2_per_deg_convention"}, {"me_nzero", "N0_N"},
    {"me_nult", "Nult_N"},  {"me_ntens", "Nc_N"},                   {"me_mff", "m_f"},
    {"me_betaf", "beta_f"}, {"me_kf", "k_F"},                       {"me_km", "k_M"},
    {"me_wpl1", "W1_J"},    {"me_wpl2", "W2_J"},                    {"me_dalpha", "alpha_d"},
    {"me_mfg", "m_g"},      {"me_alphag", "alpha_g"},               {"me_betag", "beta_g"},
    {"me_rata", "slide_a"}, {"me_ratb", "slide_b"},                 {"me_ref_l", "reference_length_m"},
    {"me_d", "D_m"}};

// The plugin example's contact groups: balls carry group slots dt0/dt1; SW contacts join two
// balls of group 1, DT contacts a ball of group 2.
struct Pfc7Group {
  int cmat;
  const char* name;
  const char* range;
};

Pfc7Group group_of(const std::string& wire_type) {
  if (wire_type == "single_wire") return {1, "SW", "group 'dt0' matches 1 group 'dt1' matches 1"};
  if (wire_type == "double_twist") return {2, "DT", "group 'dt0' matches 2 union group 'dt1' matches 2"};
  throw std::invalid_argument("wire type '" + wire_type + "': the PFC7 plugin's groups are single_wire (SW) and double_twist (DT)");
}

// The shortest of 15 or 17 significant digits that reads back to the same double.
std::string number(double value) {
  for (const int digits : {15, 17}) {
    std::ostringstream s;
    s << std::setprecision(digits) << value;
    // strtod, not stod: a subnormal reads back without the out-of-range exception stod throws.
    if (std::strtod(s.str().c_str(), nullptr) == value || digits == 17) return s.str();
  }
  return {};
}

}  // namespace

bool is_pfc7_macroelement_set(const ParameterSet& set) {
  if (set.law != "thesis" && !set.law.empty()) return false;
  for (const Pfc7Property& p : kProperties)
    if (!set.has(p.key)) return false;
  return set.wire_type == "single_wire" || set.wire_type == "double_twist";
}

std::string pfc7_macroelement_commands(const std::vector<ParameterSet>& sets, const Provenance& provenance) {
  std::ostringstream s;
  s << "; Thesis macro-element sets for the PFC7 plugin macroelement-doubletwist-PFC7, written by dtwire "
    << tool_version() << " (" << git_hash() << ") on " << provenance.created_utc << ", run "
    << provenance.run_id << "\n"
    << "; from: " << provenance.command << "\n"
    << "; Load with `program call 'this_file'` after the balls exist; SI units, rotations in degrees\n"
    << "; (the plugin's convention). Groups as the plugin's punch example: SW contacts join two balls of\n"
    << "; group 1 (slots dt0/dt1), DT contacts a ball of group 2.\n";
  int written = 0;
  for (const ParameterSet& set : sets) {
    if (!is_pfc7_macroelement_set(set)) continue;
    const Pfc7Group group = group_of(set.wire_type);
    const ParameterMap values = set.map();
    const double gap = values.at("reference_length_m") - values.at("D_m");
    if (!(gap > 0.0)) throw std::invalid_argument("wire type '" + set.wire_type + "': reference_length_m must exceed D_m");
    s << "\n; " << set.wire_type << "\n"
      << "contact cmat add " << group.cmat << " model macroelement property pb_ten 1e99 ...\n"
      << "  pb_coh 1e99 ...\n"
      << "  rgap " << number(gap) << " ... ; contact detection gap: depends on your ball radii (here reference length - D)\n";
    for (const Pfc7Property& p : kProperties) {
      const double value = values.at(p.key);
      if (!std::isfinite(value)) throw std::invalid_argument("wire type '" + set.wire_type + "': " + p.key + " is not finite");
      s << "  " << p.property << " " << number(value) << " ...\n";
    }
    s << "  range " << group.range << "\n"
      << "contact group '" << group.name << "' range " << group.range << "\n";
    // The plugin's shear spring is k_EA / 2.6 whatever the set says (docs/dem_laws.md, "Shear spring").
    const bool beam_shear = values.count("beam_shear") && values.at("beam_shear") == 1.0;
    if (beam_shear || values.count("shear_stiffness_N_per_m"))
      s << "; NOTE: this set asks for " << (beam_shear ? "the slender beam's shear spring (beam_shear = 1)"
                                                      : "shear_stiffness_N_per_m " + number(values.at("shear_stiffness_N_per_m")))
        << "; the plugin has no such property and uses me_ea / 2.6, so PFC7 runs this set with the plugin's spring\n";
    ++written;
  }
  if (written == 0) throw std::invalid_argument("no thesis macro-element set (single_wire or double_twist with every plugin property)");
  return s.str();
}

std::map<int, std::map<std::string, double>> read_pfc7_macroelement_commands(const std::string& text) {
  std::map<int, std::map<std::string, double>> sets;
  std::istringstream lines(text);
  std::string line;
  int current = -1;
  while (std::getline(lines, line)) {
    const auto comment = line.find(';');
    if (comment != std::string::npos) line.erase(comment);
    std::istringstream words(line);
    std::string word;
    std::vector<std::string> tokens;
    while (words >> word) tokens.push_back(word);
    if (tokens.empty()) continue;
    if (tokens.size() >= 4 && tokens[0] == "contact" && tokens[1] == "cmat" && tokens[2] == "add") {
      current = std::stoi(tokens[3]);
      const auto property = std::find(tokens.begin(), tokens.end(), "property");
      if (property == tokens.end() || property + 2 >= tokens.end()) throw std::invalid_argument("cmat add without a property: " + line);
      sets[current][*(property + 1)] = std::stod(*(property + 2));
    } else if (current >= 0 && tokens.size() >= 2 && tokens[0] != "range" && tokens[0] != "contact") {
      sets[current][tokens[0]] = std::stod(tokens[1]);
    } else {
      current = tokens[0] == "range" ? current : -1;
    }
  }
  return sets;
}

}  // namespace dtwire::dem
