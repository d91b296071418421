#include "gap_dem_model.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>

#include "../campaign/step_process.hpp"
#include "../cli.hpp"
#include "dtwire/calibrate/command_simulator.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "gap_model/model_effect.hpp"

namespace dtwire::app {
namespace {

// Settling time of the slack state: the net drapes onto the wall (docs/dem_engine.md, set-up study).
constexpr double kSlackSettleSeconds = 40.0;

bool strength_law(const std::string& law) { return law == "thesis" || law == "macro3d"; }

const dem::LinkSetInput* link_set(const dem::RunInput& base, dem::LinkTag tag) {
  const auto found = base.link_sets.find(tag);
  return found == base.link_sets.end() ? nullptr : &found->second;
}

// `links.TAG.scale.NAME=f` composed with the input's own factor on NAME.
std::string scale_entry(const dem::LinkSetInput& set, dem::LinkTag tag, const std::string& name, double factor) {
  const auto own = set.scales.find(name);
  return "links." + dem::link_tag_name(tag) + ".scale." + name + "=" +
         number_text(factor * (own == set.scales.end() ? 1.0 : own->second));
}

// The SW set's bending stiffness values that the run input can scale (a scale must name a value
// of the set).
std::vector<std::string> sw_bending_values(const dem::LinkSetInput& set) {
  std::vector<std::string> values;
  for (const char* name : {"EI_Nm2_per_deg_convention", "bending_stiffness_Nm_per_rad"})
    if (set.parameters.count(name)) values.push_back(name);
  return values;
}

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

dem::RunInput read_dem_model(const std::filesystem::path& toml, const DemModelOptions& options) {
  dem::RunInput input = dem::read_run_input(toml, options.set);
  for (const std::string& entry : options.set_params) {
    const auto equals = entry.find('=');
    if (equals == std::string::npos) throw InputError("--model-set-params", "expected TAG=FILE, found '" + entry + "'");
    dem::override_link_set(input, entry.substr(0, equals), entry.substr(equals + 1), "--model-set-params");
  }
  if (input.tool != "platter" && input.tool != "strip_tension")
    throw InputError(toml.string(), "gap --model needs a punch (tool.kind = \"platter\") or a strip tension "
                                    "(\"strip_tension\") run, found tool.kind = \"" + input.tool + "\"");
  return input;
}

std::string dem_effect_unsupported(const std::string& effect, const dem::RunInput& base) {
  const bool strip = base.tool == "strip_tension";
  if (effect == "mesh_distortion") {
    for (const auto& [tag, set] : base.link_sets)
      if (tag != dem::LinkTag::Selvedge && set.distortion.mode != dem::DistortionMode::None)
        return "the input already distorts its " + dem::link_tag_name(tag) + " links";
    return "";
  }
  if (effect == "edge_sliding") {
    if (strip) return "a strip tension has clamps, not supported edges";
    if (base.support == dem::EdgeSupport::Slider) return "the input's edges already slide (boundary.support = \"slider\")";
    return base.pinned_sides == 0 ? "the input supports no edge" : "";
  }
  if (effect == "slack_state") {
    if (strip) return "a strip tension has no initial sag";
    return base.wall_below > 0.0 ? "the input already settles slack onto a wall (boundary.wall_below_m)" : "";
  }
  if (effect == "dt_weakening" || effect == "sw_softening" || effect == "sw_bending") {
    const dem::LinkTag tag = effect == "dt_weakening" ? dem::LinkTag::DoubleTwist : dem::LinkTag::SingleWire;
    const dem::LinkSetInput* set = link_set(base, tag);
    if (!set) return "the input has no " + dem::link_tag_name(tag) + " links";
    if (!strength_law(set->law))
      return "scales the thesis/macro3d values (N0_N, Nult_N, EA_N, EI); the " + dem::link_tag_name(tag) +
             " links use the " + set->law + " law";
    if (effect == "sw_bending" && sw_bending_values(*set).empty())
      return "the " + dem::link_tag_name(tag) + " set gives no bending stiffness (EI_Nm2_per_deg_convention, "
             "bending_stiffness_Nm_per_rad)";
    return "";
  }
  if (effect == "beam_shear") {
    bool all_beam = true;
    for (const dem::LinkTag tag : {dem::LinkTag::SingleWire, dem::LinkTag::DoubleTwist}) {
      const dem::LinkSetInput* set = link_set(base, tag);
      if (!set) return "the input has no " + dem::link_tag_name(tag) + " links";
      if (!strength_law(set->law))
        return "sets the macro-element's shear spring (thesis, macro3d); the " + dem::link_tag_name(tag) +
               " links use the " + set->law + " law";
      if (set->parameters.count("shear_stiffness_N_per_m"))
        return "the " + dem::link_tag_name(tag) + " set gives its own shear_stiffness_N_per_m";
      const auto beam = set->parameters.find("beam_shear");
      all_beam = all_beam && beam != set->parameters.end() && beam->second == 1.0;
    }
    return all_beam ? "the input's sets already have the beam's shear spring (beam_shear = 1)" : "";
  }
  if (effect == "discretisation") {
    if (base.mesh.nodes_per_wire == 3) return "the input already has three nodes per wire (mesh.nodes_per_wire = 3)";
    for (const dem::LinkTag tag : {dem::LinkTag::SingleWire, dem::LinkTag::DoubleTwist})
      if (const dem::LinkSetInput* set = link_set(base, tag); set && set->law == "wirepm")
        return "the " + dem::link_tag_name(tag) + " links are wirepm (axial force only): a middle node would be a hinge";
    return "";
  }
  return "not a mesh-level effect";
}

std::vector<std::string> dem_effect_entries(const dem::RunInput& base, const std::vector<gap::AppliedEffect>& effects) {
  std::vector<std::string> entries;
  for (const gap::AppliedEffect& a : effects) {
    const std::string& name = a.effect->name;
    if (const std::string why = dem_effect_unsupported(name, base); !why.empty())
      throw ComputationError("gap --model: effect " + name + " cannot be switched on: " + why);
    const double p = a.params.at(0);
    if (name == "mesh_distortion") {
      // One uniform slack on every wire (Thoeni's type 1); p = 0 is the input as given.
      if (p <= 0.0) continue;
      for (const dem::LinkTag tag : {dem::LinkTag::SingleWire, dem::LinkTag::DoubleTwist}) {
        if (!link_set(base, tag)) continue;
        entries.push_back("links." + dem::link_tag_name(tag) + ".distortion=\"constant\"");
        entries.push_back("links." + dem::link_tag_name(tag) + ".distortion_lambda_u=" + number_text(p));
      }
    } else if (name == "edge_sliding") {
      if (p >= 0.5) entries.push_back("boundary.support=\"slider\"");
    } else if (name == "discretisation") {
      // Searched on {2, 3}: 2 is the input's own two-node mesh.
      if (p >= 2.5) entries.push_back("mesh.nodes_per_wire=3");
    } else if (name == "beam_shear") {
      // Searched on {0, 1}: 0 is the input's own spring.
      if (p >= 0.5)
        for (const dem::LinkTag tag : {dem::LinkTag::SingleWire, dem::LinkTag::DoubleTwist})
          entries.push_back("links." + dem::link_tag_name(tag) + ".parameters.beam_shear=1");
    } else if (name == "slack_state") {
      if (p <= 0.0) continue;
      entries.push_back("boundary.pretension_strain=0.0");
      entries.push_back("boundary.presag_m=0.0");
      entries.push_back("boundary.wall_below_m=" + number_text(p * 1e-3));
      entries.push_back("dynamics.settle_s=" + number_text(std::max(base.settle_time, kSlackSettleSeconds)));
    } else if (p == 1.0) {
      continue;  // the neutral factor: the same run as the input's (and the same cache entry)
    } else if (name == "dt_weakening") {
      // The DT's force-elongation curve scaled in force: its yield and ultimate forces, and the
      // plastic work at damage onset and end (the thesis law's damage runs on plastic work, so a
      // weaker twist that fails at the same elongation has done p times the work; with W1, W2
      // kept it would become more ductile as it weakens).
      const dem::LinkSetInput& set = *link_set(base, dem::LinkTag::DoubleTwist);
      for (const char* value : {"N0_N", "Nult_N", "W1_J", "W2_J"})
        entries.push_back(scale_entry(set, dem::LinkTag::DoubleTwist, value, p));
    } else if (name == "sw_softening") {
      const dem::LinkSetInput& set = *link_set(base, dem::LinkTag::SingleWire);
      entries.push_back(scale_entry(set, dem::LinkTag::SingleWire, "EA_N", p));
      if (set.parameters.count("axial_stiffness_N_per_m"))
        entries.push_back(scale_entry(set, dem::LinkTag::SingleWire, "axial_stiffness_N_per_m", p));
    } else if (name == "sw_bending") {
      // The thesis law's bending stiffness, or a macro3d set's own SI one (sw_bending_values).
      const dem::LinkSetInput& set = *link_set(base, dem::LinkTag::SingleWire);
      for (const std::string& value : sw_bending_values(set))
        entries.push_back(scale_entry(set, dem::LinkTag::SingleWire, value, p));
    }
  }
  return entries;
}

SimulationModel make_dem_model(const std::filesystem::path& toml, const DemModelOptions& options) {
  const dem::RunInput base = read_dem_model(toml, options);
  SimulationModel model;
  for (const gap::EffectSpec& e : gap::effect_catalogue())
    if (e.test == "mesh")
      if (const std::string why = dem_effect_unsupported(e.name, base); !why.empty()) model.unsupported[e.name] = why;

  model.work = options.cache.empty()
                   ? std::filesystem::temp_directory_path() / ("dtwire_gap_dem_" + std::to_string(::getpid()))
                   : options.cache;
  std::filesystem::create_directories(model.work);
  // What makes a run: the input, its parameter files, the base entries and the version.
  std::string identity = version_string() + "\n" + file_text(toml) + "\n";
  for (const auto& [tag, set] : base.link_sets)
    for (const auto& file : set.files) identity += file.string() + "\n" + file_text(file) + "\n";
  const std::filesystem::path input = std::filesystem::absolute(toml);
  std::vector<std::string> base_arguments = {"dem", "run", input.string(), "--no-frames", "-q"};
  for (const std::string& entry : options.set) base_arguments.insert(base_arguments.end(), {"--set", entry});
  for (const std::string& entry : options.set_params) base_arguments.insert(base_arguments.end(), {"--set-params", entry});

  auto runs = std::make_shared<int>(0);
  model.runs = runs.get();
  const std::filesystem::path work = model.work;
  // `gap --jobs N` calls this from several threads: each run has its own folder; the counter
  // and the console lines are shared.
  auto shared = std::make_shared<std::mutex>();
  model.run_curve = [=, keep = runs](const std::vector<gap::AppliedEffect>& effects) {
    std::vector<std::string> arguments = base_arguments;
    std::string label = input.filename().string();
    for (const gap::AppliedEffect& a : effects) label += " " + a.effect->name + "=" + number_text(a.params.at(0));
    for (const std::string& entry : dem_effect_entries(base, effects)) arguments.insert(arguments.end(), {"--set", entry});
    std::string key_text = identity;
    for (const std::string& a : arguments) key_text += a + "\n";
    const std::filesystem::path run = work / sha256_text(key_text).substr(0, 24);
    // `finished` is written after the run succeeded: a run cut short is run again.
    if (!std::filesystem::exists(run / "finished")) {
      std::filesystem::remove_all(run);
      std::filesystem::create_directories(run);
      const unsigned threads = effects.empty() ? std::max(1u, options.base_threads) : 1u;
      arguments.insert(arguments.end(), {"--threads", std::to_string(threads), "-o", (run / "out").string()});
      {
        std::ofstream command(run / "command.txt");
        command << calibrate::dtwire_executable().string();
        for (const std::string& a : arguments) command << " '" << a << "'";
        command << "\n";
      }
      {
        const std::lock_guard<std::mutex> lock(*shared);
        std::cout << "  DEM run: " << label << "\n" << std::flush;
      }
      const int code = run_step_process(calibrate::dtwire_executable(), arguments, run / "command.log", [](double) {});
      // A run stopped by its own checks (exit 1, issue 37) keeps its curve up to the failed check,
      // marked `status: failed ...`: the diagnosis reads that part (a runaway after the peak
      // leaves onset and peak as they were) and says so; any other failure ends the diagnosis.
      const bool stopped = code == 1 && std::filesystem::exists(run / "out" / "curve.csv") &&
                           read_csv(run / "out" / "curve.csv").metadata("status").rfind("failed", 0) == 0;
      if (code != 0 && !stopped)
        throw ComputationError("DEM run (" + label + ") failed (exit " + std::to_string(code) + "), see " +
                               (run / "command.log").string());
      std::ofstream(run / "finished") << label << "\n";
      const std::lock_guard<std::mutex> lock(*shared);
      ++*keep;
      std::cout << "  DEM run: " << label
                << (stopped ? " stopped by its checks: " + read_csv(run / "out" / "curve.csv").metadata("status") +
                                  "; its curve up to there\n"
                            : std::string(" done\n"))
                << std::flush;
    }
    return read_csv(run / "out" / "curve.csv");
  };
  model.run = [full = model.run_curve, label = input.filename().string()](const std::vector<gap::AppliedEffect>& effects) {
    const Curve curve = full(effects);
    gap::ForceCurve c;
    // A punch writes the tool's channels; a strip tension the clamp bar's elongation and force,
    // with its width and free length (the standard's figures are per metre and per strain).
    const bool strip = !curve.find("tool_displacement") && curve.find("elongation");
    c.u = curve.si(strip ? "elongation" : "tool_displacement");
    c.f = curve.si(strip ? "force" : "tool_force");
    gap::read_strip_geometry(curve, c);
    c.source = label;
    return c;
  };
  return model;
}

}  // namespace dtwire::app
