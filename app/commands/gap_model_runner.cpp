#include "gap_model_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <mutex>

#include "../cli.hpp"
#include "dtwire/calibrate/command_simulator.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/gap/effects.hpp"
#ifdef DTWIRE_HAVE_FEM
#include "dtwire/fem/run.hpp"
#endif

namespace dtwire::app {

PrmDocument solver_declarations() {
  if (const char* program = std::getenv("DTWIRE_FE_EXECUTABLE"); program && *program) {
    if (auto declared = calibrate::program_parameters(program)) return *declared;
    throw InputError(program, "`" + std::string(program) +
                                  " parameters` did not list the FE parameters (a dtwire built with fem?)");
  }
#ifdef DTWIRE_HAVE_FEM
  return PrmDocument::parse(fem::parameter_listing(false), "dtwire parameters");
#else
  throw InputError("DTWIRE_FE_EXECUTABLE", "this dtwire has no FE solver: set it to a dtwire built with fem");
#endif
}

PrmDocument edit_prm(const PrmDocument& model, const PrmDocument& declared,
                     const std::vector<gap::AppliedEffect>& effects, const std::filesystem::path& prm_directory,
                     const GripBond& grip) {
  PrmDocument edited = model;
  edited.set("Output/Fields", "false");  // no VTU output in fits
  // The edited copy is run from elsewhere: the files the model names, relative to its folder.
  for (const char* entry : {"Geometry/Mesh file", "As made/Axis file", "As made/State file", "As made/Twisted pair state"})
    if (const auto file = model.get(entry); file && !file->empty() && std::filesystem::path(*file).is_relative())
      edited.set(entry, (prm_directory / *file).string());
  const ModelContext context{model, declared, prm_directory, grip};
  for (const gap::AppliedEffect& a : effects) {
    const ModelEffect* effect = find_model_effect(a.effect->name);
    if (!effect) throw ComputationError("gap --model: effect " + a.effect->name + " cannot be switched on in a .prm");
    effect->apply(a.params.at(0), context, edited);
  }
  return edited;
}

namespace {

// The model's .prm with `settings` ("Section/Entry=value") put in; InputError naming --model-set
// for a setting without '=' or an entry the solver does not declare.
PrmDocument with_settings(PrmDocument model, const PrmDocument& declared, const std::vector<std::string>& settings) {
  for (const std::string& setting : settings) {
    const auto equals = setting.find('=');
    if (equals == std::string::npos || equals == 0)
      throw InputError("--model-set", "'" + setting + "': expected Section/Entry=value");
    const std::string path = setting.substr(0, equals);
    if (!declared.find(path))
      throw InputError("--model-set", "'" + path + "' is no entry of the FE solver (`dtwire parameters` lists them)");
    model.set(path, setting.substr(equals + 1));
  }
  return model;
}

}  // namespace

SimulationModel make_fe_model(const std::filesystem::path& prm, std::filesystem::path work,
                              const std::vector<std::string>& settings, const std::filesystem::path& cache_directory) {
  const PrmDocument declared = solver_declarations();
  const PrmDocument model_prm = with_settings(PrmDocument::read(prm), declared, settings);
  check_declared(model_prm, declared);
  const std::filesystem::path directory = std::filesystem::absolute(prm).parent_path();

  SimulationModel model;
  GripBond grip;
  const ModelContext context{model_prm, declared, directory, grip};
  for (const auto& effect : model_effects())
    if (const std::string reason = effect->unsupported(context); !reason.empty())
      model.unsupported[effect->name()] = reason;
  // A panel's effects have no .prm form: named here so that no search or `gap features` runs them.
  for (const gap::EffectSpec& effect : gap::effect_catalogue())
    if (effect.needs_model && !find_model_effect(effect.name))
      model.unsupported[effect.name] = "a " + effect.test + "-test effect: it acts on a DEM panel model (--model F.toml), not on an FE .prm";
  if (!model.unsupported.count("coating_slip")) grip.top_area = top_grip_area(context);

  if (work.empty())
    work = std::filesystem::temp_directory_path() / ("dtwire_gap_model_" + std::to_string(::getpid()));
  std::filesystem::create_directories(work);
  if (!cache_directory.empty()) std::filesystem::create_directories(cache_directory);
  auto cache = std::make_shared<std::map<std::string, Curve>>();
  auto runs = std::make_shared<int>(0);
  const std::string source = prm.string();
  model.runs = runs.get();
  model.work = work;
  // One FE run of an edited .prm (cached by its text).
  // `gap --jobs N` calls the runner from several threads: the cache, the counter and the console
  // lines are shared (each FE run has its own folder).
  auto shared = std::make_shared<std::mutex>();
  // $DTWIRE_FE_EXECUTABLE: a dtwire built with fem, when this one was built without it.
  const char* fe_executable = std::getenv("DTWIRE_FE_EXECUTABLE");
  const std::filesystem::path program = fe_executable ? std::filesystem::path(fe_executable) : calibrate::dtwire_executable();
  // What makes a run besides its .prm text, for the cache on disk: the solver and the mesh.
  std::string identity = program.string() + "\n" + version_string() + "\n";
  if (const auto mesh = model_prm.get("Geometry/Mesh file"); mesh && !mesh->empty())
    if (const auto file = directory / *mesh; std::filesystem::is_regular_file(file)) identity += sha256_file(file) + "\n";
  const auto run = [=, keep = runs](const std::string& edited, const std::string& label) {
    const std::string key = sha256_text(edited);
    const std::filesystem::path stored = cache_directory.empty() ? std::filesystem::path()
                                                                 : cache_directory / (sha256_text(identity + edited).substr(0, 24) + ".csv");
    {
      const std::lock_guard<std::mutex> lock(*shared);
      if (const auto hit = cache->find(key); hit != cache->end()) return hit->second;
      if (!stored.empty() && std::filesystem::is_regular_file(stored)) {
        std::cout << "  FE run: " << label << " (from " << stored.string() << ")\n" << std::flush;
        return (*cache)[key] = read_csv(stored);
      }
      std::cout << "  FE run: " << label << "\n" << std::flush;
    }
    calibrate::CommandSpecification spec;
    spec.program = program;
    spec.arguments = {"run", "{input}", "--out", "{output}", "--quiet"};
    spec.input_template = edited;
    spec.work_directory = work;
    const Curve curve = calibrate::CommandSimulator(spec).simulate({});
    if (!stored.empty()) write_csv(curve, stored);  // atomic: a run cut short leaves no entry
    const std::lock_guard<std::mutex> lock(*shared);
    ++*keep;
    std::cout << "  FE run: " << label << " done\n" << std::flush;
    (*cache)[key] = curve;
    return curve;
  };
  const auto force_curve = [](const Curve& curve, const std::string& label) {
    gap::ForceCurve c;
    c.u = curve.si("displacement");
    c.f = curve.si("force");
    c.source = label;
    return c;
  };
  model.run_curve = [=](const std::vector<gap::AppliedEffect>& effects) {
    std::string label = source;
    GripBond bond = grip;
    for (const gap::AppliedEffect& a : effects) {
      label += " " + a.effect->name + "=" + number_text(a.params[0]);
      if (a.effect->name == "coating_slip") {  // capacity relative to the clamped model's peak force
        for (const double f : run(edit_prm(model_prm, declared, {}, directory).text(), source).si("force"))
          bond.reference_force = std::max(bond.reference_force, std::abs(f));
      }
    }
    return run(edit_prm(model_prm, declared, effects, directory, bond).text(), label);
  };
  model.run = [=, full = model.run_curve](const std::vector<gap::AppliedEffect>& effects) {
    std::string label = source;
    for (const gap::AppliedEffect& a : effects) label += " " + a.effect->name + "=" + number_text(a.params[0]);
    return force_curve(full(effects), label);
  };
  return model;
}

}  // namespace dtwire::app
