// `dtwire dem propagate RUN.toml --params-fit TAG=FIT.json ...`: a fit's uncertainty carried to
// the mesh (docs/dem_engine.md, "Propagating a fit's uncertainty"). The parameter sets come from
// calibrate's ParameterSampler (propagation.hpp), the statistics from band_statistics.hpp; the
// DEM runs are `dtwire dem run` subprocesses (propagation_runs.hpp).
#include "dem_propagate_command.hpp"

#include <CLI/CLI.hpp>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <fstream>
#include <future>
#include <iostream>
#include <memory>
#include <sstream>

#include "../cli.hpp"
#include "../plotting.hpp"
#include "dtwire/calibrate/band_statistics.hpp"
#include "dtwire/calibrate/propagation.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/dem/run.hpp"
#include "propagation_emulator.hpp"
#include "propagation_outputs.hpp"
#include "propagation_runs.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

struct PropagateOptions {
  std::string file;
  std::vector<std::string> params_fit;
  std::vector<std::string> set_entries;
  std::string samples = "auto";
  std::size_t max_samples = 200;
  std::size_t batch = 10;
  double tolerance = 0.1;
  bool linearised = false;
  bool emulator = false;
  std::size_t emulated_sets = 10000;
  std::uint64_t seed = 1;
  unsigned jobs = 1;
  std::string cache;
  std::string out;
  std::string label;
  bool no_plot = false;
};

// One fit whose parameters feed one link set of the run.
struct TagFit {
  std::string tag;
  std::filesystem::path file;
  nlohmann::json root;
  calibrate::FitUncertainty fit;
  std::string prefix;  // "dt." of a joint fit's DT set; "" for a fit of one set
  std::unique_ptr<calibrate::ParameterSampler> sampler;
  std::size_t offset = 0;  // its first parameter in the propagation's list
};

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The fit's parameters.json with `values` in place of its fitted values (what `dem run
// --set-params` reads; law, wire type and fixed parameters as the fit wrote them).
std::string parameter_file_text(const TagFit& t, const std::vector<double>& values) {
  nlohmann::json out = {{"law", t.root.value("law", "")}, {"wire_type", t.root.value("wire_type", "")},
                        {"title", t.root.value("title", "")}, {"parameters", t.root["parameters"]}};
  for (nlohmann::json& p : out["parameters"])
    for (std::size_t i = 0; i < t.fit.parameters.size(); ++i)
      if (p["name"] == t.fit.parameters[i].name && p.value("fitted", false)) p["value"] = values[i];
  return out.dump(1) + "\n";
}

// Whether `dem run` would take the set (the same check as --set-params: names and the law's
// own value checks).
bool law_accepts(const dem::RunInput& input, const TagFit& t, const std::string& text, const std::filesystem::path& scratch) {
  {
    std::ofstream(scratch) << text;
  }
  dem::RunInput copy = input;
  try {
    dem::override_link_set(copy, t.tag, scratch, "--params-fit");
  } catch (const InputError&) {
    return false;
  }
  return true;
}

std::vector<TagFit> read_fits(const PropagateOptions& o) {
  std::vector<TagFit> fits;
  std::size_t offset = 0;
  for (const std::string& entry : o.params_fit) {
    const auto equals = entry.find('=');
    if (equals == std::string::npos) throw InputError("--params-fit", "expected TAG=FILE, found '" + entry + "'");
    TagFit t;
    t.tag = entry.substr(0, equals);
    t.file = entry.substr(equals + 1);
    if (t.tag != "sw" && t.tag != "dt" && t.tag != "selvedge")
      throw InputError("--params-fit", "expected sw, dt or selvedge before '=', found '" + t.tag + "'");
    for (const TagFit& other : fits)
      if (other.tag == t.tag) throw InputError("--params-fit", "two fits for " + t.tag);
    if (!std::filesystem::is_regular_file(t.file)) throw InputError(t.file.string(), "cannot open the fit's parameters.json (--params-fit)");
    std::ifstream in(t.file);
    try {
      t.root = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(t.file.string(), std::string("not JSON: ") + e.what());
    }
    // A joint SW + DT fit (calibrate's dem_specimen) names its parameters sw.* and dt.*: the
    // tag's set is the one the run takes from it.
    bool joint = t.root.contains("parameters") && t.root["parameters"].is_array() && !t.root["parameters"].empty();
    if (joint)
      for (const nlohmann::json& p : t.root["parameters"]) {
        if (!p.is_object() || !p.value("fitted", false)) continue;
        const std::string name = p.value("name", "");
        joint = joint && (name.rfind("sw.", 0) == 0 || name.rfind("dt.", 0) == 0);
      }
    t.prefix = joint ? t.tag + "." : "";
    t.fit = calibrate::read_fit_uncertainty(t.file, t.prefix);
    try {
      t.sampler = std::make_unique<calibrate::ParameterSampler>(t.fit, o.seed + fits.size());
    } catch (const std::invalid_argument& e) {
      throw InputError(t.file.string(), e.what());
    }
    t.offset = offset;
    offset += t.fit.parameters.size();
    fits.push_back(std::move(t));
  }
  if (fits.empty()) throw InputError("--params-fit", "give at least one fit (TAG=FILE)");
  return fits;
}

std::map<std::string, std::string> files_for(const std::vector<TagFit>& fits, const std::vector<double>& all) {
  std::map<std::string, std::string> files;
  for (const TagFit& t : fits) {
    const std::vector<double> own(all.begin() + static_cast<long>(t.offset),
                                  all.begin() + static_cast<long>(t.offset + t.fit.parameters.size()));
    files[t.tag] = parameter_file_text(t, own);
  }
  return files;
}

// The linearised pass: one run per parameter, its coordinate moved by the sampled spread
// (sigma, or the uniform's (upper - lower) / sqrt(12)), back instead where the move leaves the
// admissible region, halved up to four times where neither side is admissible.
void linearise(PropagationResult& r, const std::vector<TagFit>& fits, const dem::RunInput& input,
               PropagationRunner& runner, unsigned jobs, const std::filesystem::path& scratch) {
  const std::size_t n = r.parameters.size();
  std::vector<double> base(n);
  for (std::size_t i = 0; i < n; ++i) base[i] = r.parameters[i].value;
  std::vector<std::map<std::string, std::string>> sets;
  std::vector<std::string> labels;
  std::vector<std::size_t> moved;
  std::vector<double> steps(n, std::nan(""));
  for (const TagFit& t : fits)
    for (std::size_t k = 0; k < t.fit.parameters.size(); ++k) {
      const std::size_t i = t.offset + k;
      const double y0 = t.sampler->to_coordinate(k, base[i]);
      const double h = t.sampler->coordinate_sd(k);
      std::vector<double> own(base.begin() + static_cast<long>(t.offset),
                              base.begin() + static_cast<long>(t.offset + t.fit.parameters.size()));
      for (int halving = 0; halving < 5 && std::isnan(steps[i]) && h > 0.0; ++halving)
        for (const double sign : {1.0, -1.0}) {
          const double step = sign * h / std::pow(2.0, halving);
          own[k] = t.sampler->from_coordinate(k, y0 + step);
          if (t.sampler->within_constraints(own) && law_accepts(input, t, parameter_file_text(t, own), scratch)) {
            steps[i] = step;
            break;
          }
        }
      if (std::isnan(steps[i])) {
        r.notes.push_back(r.parameters[i].name + ": no admissible step within sigma/16 of the fitted value; left out of the linearised band");
        continue;
      }
      std::vector<double> all = base;
      all[i] = t.sampler->from_coordinate(k, y0 + steps[i]);
      sets.push_back(files_for(fits, all));
      labels.push_back("linearised " + r.parameters[i].name);
      moved.push_back(i);
    }
  const std::vector<RunOutcome> outcomes = runner.run_all(sets, labels, jobs);
  std::vector<LinearisedFigure> lin(r.figures.size());
  for (std::size_t f = 0; f < r.figures.size(); ++f) {
    lin[f].gradient.assign(n, std::nan(""));
    lin[f].step = steps;
    for (std::size_t m = 0; m < moved.size(); ++m) {
      const std::size_t i = moved[m];
      if (!outcomes[m].ok) {
        if (f == 0)
          r.notes.push_back("linearised run of " + r.parameters[i].name + " failed (" + outcomes[m].status +
                            "): the parameter is left out of the linearised band");
        continue;
      }
      lin[f].gradient[i] = (outcomes[m].figures[f] - r.base_figures[f]) / steps[i];
    }
    std::vector<double> g = lin[f].gradient;
    for (double& x : g)
      if (!std::isfinite(x)) x = 0.0;
    lin[f].sd = calibrate::linearised_sd(g, r.coordinate_covariance);
    const double variance = lin[f].sd * lin[f].sd;
    lin[f].share.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      lin[f].share[i] = variance > 0.0 ? g[i] * g[i] * r.coordinate_covariance[i][i] / variance : 0.0;
  }
  r.linearised = lin;
}

int run_propagate(const PropagateOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (!o.no_plot) require_plotting("plot_band.py", "band.png (dem propagate draws it; --no-plot skips it)");
  check_output_folders({{"-o", o.out}, {"--cache", o.cache}});
  dem::RunInput input = dem::read_run_input(o.file, o.set_entries);
  if (input.tool != "platter" && input.tool != "strip_tension")
    throw InputError(o.file, "dem propagate needs a punch (tool.kind = \"platter\") or a strip tension "
                             "(\"strip_tension\") run, found tool.kind = \"" + input.tool + "\"");
  std::vector<TagFit> fits = read_fits(o);
  for (const TagFit& t : fits) dem::override_link_set(input, t.tag, t.file, "--params-fit");  // the fitted set as dem run reads it
  std::size_t requested = 0;
  if (o.samples != "auto") {
    try {
      std::size_t used = 0;
      const long value = std::stol(o.samples, &used);
      if (used != o.samples.size() || value < 0) throw std::invalid_argument("");
      requested = static_cast<std::size_t>(value);
    } catch (const std::exception&) {
      throw InputError("--samples", "expected auto or a count >= 0, found '" + o.samples + "'");
    }
  }
  if (requested == 0 && o.samples != "auto" && !o.linearised)
    throw InputError("--samples", "0 samples and no --linearised: nothing to propagate");
  if (o.emulator && requested == 0 && o.samples != "auto")
    throw InputError("--emulator", "the emulator learns from sampled runs: give --samples auto or a count of at least twice the parameter count");
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0)) throw InputError("--band-tolerance", "expected a fraction in (0, 1)");

  PropagationResult r;
  r.run_file = o.file;
  r.tool = input.tool;
  r.label = o.label.empty() ? input.title : o.label;
  r.seed = o.seed;
  r.tolerance = o.tolerance;
  r.requested = requested;
  r.max_samples = o.samples == "auto" ? o.max_samples : requested;
  r.mode = o.samples == "auto" ? (o.emulator ? "sampled until the emulated band converges" : "sampled until the band converges") : requested > 0 ? "fixed sample count" : "linearised only";
  r.figures = headline_figures(input.tool);
  for (const TagFit& t : fits) {
    if (!t.fit.coordinates_recorded)
      r.notes.push_back(t.file.string() + " does not record the fit's coordinates (written before `coordinate`): every parameter sampled in its own value");
    for (std::size_t k = 0; k < t.fit.parameters.size(); ++k) {
      const calibrate::UncertainParameter& p = t.fit.parameters[k];
      PropagatedParameter q;
      q.name = t.prefix.empty() ? t.tag + "." + p.name : p.name;
      q.unit = p.unit;
      q.fit_file = t.file.string();
      q.value = p.value, q.lower = p.lower, q.upper = p.upper;
      q.identified = p.identified;
      q.normal = t.sampler->sampled_normal(k);
      q.logarithmic = p.logarithmic;
      q.coordinate_sd = t.sampler->coordinate_sd(k);
      r.parameters.push_back(q);
    }
  }
  const std::size_t n = r.parameters.size();
  if (o.emulator && requested > 0 && requested < 2 * n)
    throw InputError("--samples", "--emulator learns from at least twice the parameter count of runs (" + std::to_string(2 * n) +
                                      " for these " + std::to_string(n) + " parameters), found " + std::to_string(requested));
  r.coordinate_covariance.assign(n, std::vector<double>(n, 0.0));
  for (const TagFit& t : fits)
    for (std::size_t a = 0; a < t.fit.parameters.size(); ++a)
      for (std::size_t b = 0; b < t.fit.parameters.size(); ++b)
        r.coordinate_covariance[t.offset + a][t.offset + b] = t.sampler->coordinate_covariance()[a][b];

  const std::filesystem::path out = o.out;
  const std::filesystem::path cache = o.cache.empty() ? out / "runs" : std::filesystem::path(o.cache);
  std::filesystem::create_directories(cache);
  const std::filesystem::path scratch = cache / ("draw_check." + std::to_string(::getpid()) + ".json");
  std::string identity = version_string() + "\n" + file_text(o.file) + "\n";
  std::vector<std::string> base_arguments = {"dem", "run", std::filesystem::absolute(o.file).string(), "--no-frames", "-q", "--threads", "1"};
  for (const std::string& entry : o.set_entries) base_arguments.insert(base_arguments.end(), {"--set", entry});
  PropagationRunner runner(cache, base_arguments, identity, r.figures);

  std::vector<double> base(n);
  for (std::size_t i = 0; i < n; ++i) base[i] = r.parameters[i].value;
  std::cout << "dem propagate: " << n << " parameters from " << fits.size() << " fit(s); the fitted set first\n" << std::flush;
  const RunOutcome base_run = runner.run(files_for(fits, base), "fitted set");
  if (!base_run.ok)
    throw ComputationError("the fitted set's run gives no figures to band (" + base_run.status + "), see " + base_run.folder.string());
  r.base_figures = base_run.figures;
  r.base_curve = base_run.curve;
  if (o.linearised) {
    std::cout << "dem propagate: linearised band, one run per parameter\n" << std::flush;
    linearise(r, fits, input, runner, o.jobs, scratch);
  }
  // The emulator's sets: drawn once from samplers of their own (the runs' draws stay those of a
  // call without --emulator), the same for every batch so that the band's moves are the
  // emulator's, not the draws'.
  std::vector<std::vector<double>> emulated_points;
  if (o.emulator) {
    r.emulator = true;
    r.emulated_sets = o.emulated_sets;
    r.emulator_minimum_training = emulator_minimum_training(r);
    std::cout << "dem propagate: drawing the emulator's " << o.emulated_sets << " sets\n" << std::flush;
    std::vector<std::unique_ptr<calibrate::ParameterSampler>> samplers;
    for (const TagFit& t : fits) samplers.push_back(std::make_unique<calibrate::ParameterSampler>(t.fit, o.seed + 1000 + samplers.size()));
    for (std::size_t s = 0; s < o.emulated_sets; ++s) {
      std::vector<double> all(n);
      for (std::size_t k = 0; k < fits.size(); ++k) {
        const TagFit& t = fits[k];
        const auto check = [&](const std::vector<double>& v) { return law_accepts(input, t, parameter_file_text(t, v), scratch); };
        const std::vector<double> own = samplers[k]->draw(check);
        std::copy(own.begin(), own.end(), all.begin() + static_cast<long>(t.offset));
      }
      emulated_points.push_back(emulator_coordinates(r, all));
    }
  }

  // Sampling in batches; after each, the band's convergence (band_statistics.hpp).
  const std::size_t limit = r.max_samples;
  while (r.sample_values.size() < limit) {
    const std::size_t count = std::min(o.batch, limit - r.sample_values.size());
    std::vector<std::map<std::string, std::string>> sets;
    std::vector<std::string> labels;
    for (std::size_t s = 0; s < count; ++s) {
      std::vector<double> all(n);
      for (const TagFit& t : fits) {
        const auto check = [&](const std::vector<double>& v) { return law_accepts(input, t, parameter_file_text(t, v), scratch); };
        const std::vector<double> own = t.sampler->draw(check);
        std::copy(own.begin(), own.end(), all.begin() + static_cast<long>(t.offset));
      }
      sets.push_back(files_for(fits, all));
      labels.push_back("sample " + std::to_string(r.sample_values.size() + 1));
      r.sample_values.push_back(all);
    }
    const std::vector<RunOutcome> outcomes = runner.run_all(sets, labels, o.jobs);
    for (const RunOutcome& outcome : outcomes) {
      r.sample_figures.push_back(outcome.figures);
      r.sample_status.push_back(outcome.status);
      if (outcome.ok) r.sample_curves.push_back(outcome.curve);
    }
    ConvergenceRow row;
    row.count = r.sample_values.size();
    bool all_converged = true;
    r.converged.assign(r.figures.size(), false);
    for (std::size_t f = 0; f < r.figures.size(); ++f) {
      const std::vector<double> values = figure_values(r, f);
      row.figures.push_back(values.empty() ? calibrate::BandStatistics{} : calibrate::band_statistics(values, o.seed));
      r.converged[f] = !values.empty() && calibrate::band_converged(row.figures.back(), o.tolerance);
      all_converged = all_converged && (values.empty() || r.converged[f]);
    }
    if (o.emulator) {
      // One emulator per figure, side by side with --jobs (each reads r only).
      std::vector<std::future<std::optional<EmulatedFigure>>> emulators;
      for (std::size_t f = 0; f < r.figures.size(); ++f)
        emulators.push_back(std::async(o.jobs > 1 ? std::launch::async : std::launch::deferred,
                                       [&r, &emulated_points, &o, f] { return emulate_figure(r, f, emulated_points, o.seed); }));
      for (std::size_t f = 0; f < r.figures.size(); ++f) {
        try {
          row.emulated.push_back(emulators[f].get());
        } catch (const ComputationError& e) {
          row.emulated.emplace_back();
          r.notes.push_back(std::to_string(row.count) + " sets: no emulator of " + r.figures[f].key + " (" + e.what() + ")");
        }
      }
    }
    r.convergence.push_back(row);
    std::cout << "dem propagate: " << row.count << " sets drawn";
    for (std::size_t f = 0; f < r.figures.size(); ++f) {
      std::cout << "; " << r.figures[f].key << " 5-95 % [" << row.figures[f].q05 << ", " << row.figures[f].q95 << "]";
      if (o.emulator && row.emulated[f])
        std::cout << " emulated [" << row.emulated[f]->band.with_error.q05 << ", " << row.emulated[f]->band.with_error.q95
                  << "] (Q2 " << row.emulated[f]->q_squared << ")";
    }
    std::cout << "\n" << std::flush;
    if (o.emulator) {
      r.emulator_converged = emulator_converged(r, o.tolerance);
      all_converged = true;
      for (std::size_t f = 0; f < r.figures.size(); ++f)
        all_converged = all_converged && (figure_values(r, f).empty() || r.emulator_converged[f]);
    }
    if (o.samples == "auto" && all_converged) break;
  }
  if (!r.convergence.empty()) r.band = r.convergence.back().figures;
  if (o.emulator && !r.convergence.empty()) {
    r.emulated = r.convergence.back().emulated;
    r.emulator_converged = emulator_converged(r, o.tolerance);
  }
  for (const TagFit& t : fits) r.accepted += t.sampler->accepted(), r.refused += t.sampler->refused();
  std::error_code ignored;
  std::filesystem::remove(scratch, ignored);
  r.runs_done = runner.runs_done();
  r.cache_hits = runner.cache_hits();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_propagation_outputs(r, out, !o.no_plot);
  std::cout << "dem propagate: " << r.runs_done << " DEM runs, " << r.cache_hits << " from the cache, " << r.wall_seconds
            << " s -> " << (out / "summary.json").string() << ", " << (out / "report.md").string() << "\n";
  return 0;
}

}  // namespace

void add_dem_propagate_command(CLI::App& dem, CommandSet& commands) {
  auto o = std::make_shared<PropagateOptions>();
  CLI::App* c = dem.add_subcommand("propagate",
                                   "A fit's uncertainty carried to the mesh: strip or punch runs on parameter sets drawn from "
                                   "the fits' covariance, their band, its convergence and the sensitivities");
  c->add_option("file", o->file, "Run input (.toml): a strip tension or a punch")->required()->check(CLI::ExistingFile);
  c->add_option("--params-fit", o->params_fit,
                "TAG=FIT: the parameters.json of the fit whose set the sw, dt or selvedge links take (a joint SW + DT fit gives the tag's set)")
      ->required();
  c->add_option("--set", o->set_entries, "Replace or add an input entry, TABLE.KEY=VALUE (as dem run --set)");
  c->add_option("--samples", o->samples, "auto (batches until the band converges, up to --max-samples), a count, or 0 (with --linearised)");
  c->add_option("--max-samples", o->max_samples, "Cap of --samples auto (default 200)")->check(CLI::Range(1, 100000));
  c->add_option("--batch", o->batch, "Sets per batch between convergence checks (default 10)")->check(CLI::Range(1, 10000));
  c->add_option("--band-tolerance", o->tolerance,
                "Converged when 2 x the bootstrap standard error of each band end <= this fraction of the band's width (default 0.1)");
  c->add_flag("--linearised", o->linearised, "Also the linearised band J C J^T and the derivatives: one run per parameter");
  c->add_flag("--emulator", o->emulator,
              "Also the emulated band: a Gaussian-process emulator of each figure trained on the runs after each batch, "
              "predicting it on --emulated-sets more sets; with --samples auto the sampling stops once the emulated band "
              "converges");
  c->add_option("--emulated-sets", o->emulated_sets, "Sets the emulator predicts (default 10000)")->check(CLI::Range(100, 10000000));
  c->add_option("--seed", o->seed, "Seed of the draws (default 1; recorded)");
  c->add_option("--jobs", o->jobs, "DEM runs side by side (one thread each; default 1)")->check(CLI::Range(1, 256));
  c->add_option("--cache", o->cache, "Run folders, reused by later calls (default OUT/runs)");
  c->add_option("-o,--out", o->out, "Output directory")->required();
  c->add_option("--label", o->label, "Name of the set in the report (default: the input's title)");
  c->add_flag("--no-plot", o->no_plot, "No band.png");
  commands.add(c, [o] { return run_propagate(*o); });
}

}  // namespace dtwire::app
