#include "dtwire/calibrate/fit_output.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/core/units.hpp"

namespace dtwire::calibrate {
namespace {

using nlohmann::json;

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json matrix(const Eigen::MatrixXd& m) {
  json rows = json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(finite_or_null(m(i, j)));
    rows.push_back(row);
  }
  return rows;
}

// SI unit symbol from a name suffix ("N0_N" -> "N"), "1" if none is recognised.
std::string unit_from_name(const std::string& name) {
  try {
    return parse_column_name(name).unit.symbol;
  } catch (const std::invalid_argument&) {
    return "1";
  }
}

std::string file_stem(const std::string& experiment) {
  std::string s = experiment;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  return s;
}

json provenance_json(const Provenance& p) {
  json inputs = json::object();
  for (const auto& [path, sha] : p.input_sha256) inputs[path] = sha;
  return {{"tool_version", p.tool_version}, {"git_hash", p.git_hash}, {"created_utc", p.created_utc},
          {"command", p.command}, {"run_id", p.run_id}, {"inputs", inputs}};
}

std::string number(double v, int precision = 4) {
  std::ostringstream out;
  out << std::setprecision(precision) << v;
  return out.str();
}

void write_all_outputs(const FitDefinition& definition, const FitResult& result,
                       const Provenance& provenance, const std::filesystem::path& out) {
  std::filesystem::create_directories(out / "curves");
  const std::size_t n = result.parameters.size();

  // Curves: targets and fitted channels at the target points.
  json quality = json::array();
  Results store;
  for (std::size_t e = 0; e < definition.experiments.size(); ++e) {
    const auto& experiment = definition.experiments[e];
    const std::string stem = file_stem(experiment.name);
    const auto target_csv = std::filesystem::path("curves") / (stem + "_target.csv");
    const auto fitted_csv = std::filesystem::path("curves") / (stem + "_fitted.csv");
    write_csv(experiment.target, out / target_csv);
    write_csv(result.fitted[e], out / fitted_csv);
    store.curves.emplace_back("target_" + stem, experiment.target);
    store.curves.emplace_back("fitted_" + stem, result.fitted[e]);
    for (const auto& q : result.quality)
      if (q.experiment == experiment.name)
        quality.push_back({{"experiment", q.experiment}, {"quantity", q.quantity}, {"unit", q.unit},
                           {"abscissa", experiment.abscissa}, {"points", q.points},
                           {"rmse", q.rmse}, {"nrmse", q.nrmse}, {"r_squared", q.r_squared},
                           {"weight", experiment.weight}, {"target_csv", target_csv.string()},
                           {"fitted_csv", fitted_csv.string()}});
  }

  // Parameters: the fitted ones with sigma and bounds, then the fixed ones (so the file holds a
  // complete law parameter set for `dtwire export`). Values, sigma, bounds, initial and
  // reference are the parameters' own (offsets resolved: the range the box gives them); an
  // offset parameter's own numbers follow under "offset".
  const std::vector<double> lower = resolved_lower(result.parameters), upper = resolved_upper(result.parameters);
  std::vector<double> initial;
  for (const auto& p : result.parameters) initial.push_back(p.initial);
  initial = resolve_offsets(result.parameters, initial);
  const std::vector<std::optional<double>> references = resolved_references(result.parameters);
  json parameters = json::array();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = result.parameters[i];
    json entry = {{"name", p.name}, {"value", result.values[i]}, {"unit", p.unit},
                  {"sigma", result.sigma.empty() ? json(nullptr) : finite_or_null(result.sigma[i])},
                  {"lower", lower[i]}, {"upper", upper[i]}, {"initial", initial[i]}, {"fitted", true},
                  // the optimiser's coordinate (value / scale or its log): `dem propagate` samples in it
                  {"coordinate", p.logarithmic ? "log" : "linear"}};
    if (i < result.secant_sigma.size()) entry["secant_sigma"] = finite_or_null(result.secant_sigma[i]);
    if (i < result.identification.size()) {
      entry["identified"] = result.identification[i].identified;
      entry["relative_sigma"] = finite_or_null(result.identification[i].relative_sigma);
      if (!result.identification[i].identified) entry["not_identified_because"] = result.identification[i].reason;
    }
    if (references[i]) entry["reference"] = *references[i];
    if (!p.offset_from.empty()) {
      entry["offset_from"] = p.offset_from;
      json offset = {{"value", i < result.fitted_values.size() ? json(result.fitted_values[i]) : json(nullptr)},
                     {"sigma", i < result.fitted_sigma.size() ? finite_or_null(result.fitted_sigma[i]) : json(nullptr)},
                     {"lower", p.lower}, {"upper", p.upper}, {"initial", p.initial}};
      if (p.reference) offset["reference"] = *p.reference;
      entry["offset"] = offset;
    }
    parameters.push_back(entry);
    store.parameters.push_back({p.name, result.values[i], p.unit,
                                result.sigma.empty() ? std::nullopt : std::optional<double>(result.sigma[i])});
  }
  for (const auto& [name, value] : definition.fixed) {
    const bool fitted = std::any_of(result.parameters.begin(), result.parameters.end(),
                                    [&](const ParameterDefinition& p) { return p.name == name; });
    if (fitted) continue;
    parameters.push_back({{"name", name}, {"value", value}, {"unit", unit_from_name(name)},
                          {"sigma", nullptr}, {"fitted", false}});
    store.parameters.push_back({name, value, unit_from_name(name), std::nullopt});
  }

  json starts = json::array();
  const auto resolved = [&](const std::vector<double>& fitted) {
    return fitted.size() == n ? resolve_offsets(result.parameters, fitted) : fitted;
  };
  for (const auto& s : result.starts)
    starts.push_back({{"start", resolved(s.start)}, {"end", resolved(s.end)}, {"cost", finite_or_null(s.cost)},
                      {"iterations", s.iterations}, {"state", s.state}, {"message", s.message}});

  json root;
  root["law"] = definition.law;
  root["wire_type"] = definition.wire_type;
  root["title"] = definition.title;
  root["parameters"] = parameters;
  root["covariance"] = result.covariance ? matrix(*result.covariance) : json(nullptr);
  root["correlation"] = result.correlation ? matrix(*result.correlation) : json(nullptr);
  root["covariance_status"] = result.covariance_status;
  root["covariance_parameters"] = json::array();
  for (const auto& p : result.parameters) root["covariance_parameters"].push_back(p.name);
  root["fit_quality"] = quality;
  json peaks = json::array();
  for (const auto& q : result.peaks)
    peaks.push_back({{"experiment", q.experiment}, {"quantity", q.quantity}, {"unit", q.unit}, {"target", q.target},
                     {"fitted", q.simulated}, {"target_at", q.target_abscissa}, {"fitted_at", q.simulated_abscissa}});
  if (!peaks.empty()) root["fit_peaks"] = peaks;
  root["singular_values"] = result.singular_values;
  root["not_identified"] = json::array();
  for (std::size_t i = 0; i < result.identification.size(); ++i)
    if (!result.identification[i].identified) root["not_identified"].push_back(result.parameters[i].name);
  root["warnings"] = result.warnings;
  root["cost"] = result.cost;
  root["residual_variance"] = result.residual_variance;
  root["residual_count"] = result.residual_count;
  root["best_start"] = result.best_start;
  root["starts"] = starts;
  if (result.polish.run) {
    const auto& p = result.polish;
    root["polish"] = {{"relative_step", p.relative_step}, {"cost_before", p.cost_before},
                      {"cost_after", std::isfinite(p.cost_after) ? json(p.cost_after) : json(nullptr)},
                      {"iterations", p.iterations}, {"taken", p.taken}, {"message", p.message}};
  }
  root["statistics"] = {{"simulations", result.statistics.simulations},
                        {"cache_hits", result.statistics.cache_hits},
                        {"failed_simulations", result.statistics.failures},
                        {"failure_kinds", result.statistics.failure_kinds},
                        {"wall_seconds", result.wall_seconds}};
  root["provenance"] = provenance_json(provenance);
  store.provenance = provenance;
  write_results(store, out / "parameters.h5");

  // A short human-readable report (inlined by the campaign report).
  write_file_atomically(out / "fit_report.md", [&](std::ostream& s) {
    s << "### Fit: " << (definition.title.empty() ? definition.file.filename().string() : definition.title)
      << "\n\n";
    s << "Law `" << definition.law << "`, " << definition.experiments.size() << " curves, "
      << result.residual_count << " residuals; best of " << result.starts.size() << " start(s) (start "
      << result.best_start + 1 << "); " << result.statistics.simulations << " simulation runs ("
      << result.statistics.cache_hits << " cache hits, " << result.statistics.failures
      << " failed), wall time " << number(result.wall_seconds, 3) << " s; run " << provenance.run_id << ".\n\n";
    if (result.polish.run)
      s << "Polish (finite-difference step " << number(result.polish.relative_step) << " from the best start's end): cost "
        << number(result.polish.cost_before, 4) << " -> "
        << (std::isfinite(result.polish.cost_after) ? number(result.polish.cost_after, 4) : std::string("failed")) << " in "
        << result.polish.iterations << " iterations, "
        << (result.polish.taken ? "taken" : "not taken (no lower cost)") << ".\n\n";
    if (!result.covariance_status.empty() && result.covariance_status != "positive definite")
      s << "**Covariance " << result.covariance_status << ": the sigma below are not standard errors.**\n\n";
    s << "| parameter | value | sigma | unit | bounds | reference | identified |\n|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = result.parameters[i];
      s << "| " << p.name << " | " << number(result.values[i], 5) << " | "
        << (result.sigma.empty() ? std::string("n/a") : number(result.sigma[i], 2)) << " | " << p.unit << " | "
        << (p.offset_from.empty() ? "" : p.offset_from + " + ") << "[" << number(p.lower) << ", " << number(p.upper)
        << "] | " << (references[i] ? number(*references[i], 5) : std::string("")) << " | "
        << (i >= result.identification.size() ? std::string("") : result.identification[i].identified ? "yes" : "**NO**")
        << " |\n";
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = result.parameters[i];
      if (p.offset_from.empty() || i >= result.fitted_values.size()) continue;
      s << "\n" << p.name << " was fitted as its offset from " << p.offset_from << ": " << coordinate_name(p) << " = "
        << number(result.fitted_values[i], 5)
        << (i < result.fitted_sigma.size() ? " +- " + number(result.fitted_sigma[i], 2) : std::string()) << " " << p.unit
        << " within [" << number(p.lower) << ", " << number(p.upper) << "]"
        << (p.reference ? ", reference " + number(*p.reference, 5) : std::string()) << ".";
    }
    if (std::any_of(result.parameters.begin(), result.parameters.end(),
                    [](const ParameterDefinition& p) { return !p.offset_from.empty(); }))
      s << "\n";
    s << "\n| curve | channel | points | RMSE | NRMSE | R^2 |\n|---|---|---|---|---|---|\n";
    for (const auto& q : result.quality)
      s << "| " << q.experiment << " | " << q.quantity << " | " << q.points << " | " << number(q.rmse, 3)
        << " " << q.unit << " | " << number(q.nrmse, 3) << " | " << number(q.r_squared, 4) << " |\n";
    if (!result.peaks.empty()) {
      s << "\nPeaks (the target's value of largest magnitude against the fitted run's over its whole path):\n\n"
        << "| curve | channel | target | fitted | difference | target at | fitted at |\n|---|---|---|---|---|---|---|\n";
      for (const auto& q : result.peaks)
        s << "| " << q.experiment << " | " << q.quantity << " | " << number(q.target, 4) << " " << q.unit << " | "
          << number(q.simulated, 4) << " " << q.unit << " | "
          << (q.target != 0 ? number(100.0 * (q.simulated - q.target) / std::abs(q.target), 3) + " %"
                            : number(q.simulated - q.target, 4) + " " + q.unit)
          << " | " << number(q.target_abscissa, 4)
          << " | " << number(q.simulated_abscissa, 4) << " |\n";
    }
    if (result.correlation) {
      s << "\nCorrelation matrix:\n\n|   |";
      for (const auto& p : result.parameters) s << " " << p.name << " |";
      s << "\n|---|";
      for (std::size_t j = 0; j < n; ++j) s << "---|";
      s << "\n";
      for (std::size_t i = 0; i < n; ++i) {
        s << "| " << result.parameters[i].name << " |";
        for (std::size_t j = 0; j < n; ++j) s << " " << number((*result.correlation)(i, j), 2) << " |";
        s << "\n";
      }
    }
    if (!result.warnings.empty()) {
      s << "\nWarnings:\n\n";
      for (const auto& w : result.warnings) s << "- " << w << "\n";
    }
  });
  // Last: parameters.json is what later steps read, so it exists only beside complete outputs.
  write_file_atomically(out / "parameters.json", [&](std::ostream& s) { s << root.dump(2) << "\n"; });
}

}  // namespace

void write_fit_outputs(const FitDefinition& definition, const FitResult& result,
                       const Provenance& provenance, const std::filesystem::path& out) {
  try {
    write_all_outputs(definition, result, provenance, out);
  } catch (...) {
    std::error_code ignored;
    for (const auto& e : definition.experiments)
      for (const char* kind : {"_target.csv", "_fitted.csv"})
        std::filesystem::remove(out / "curves" / (file_stem(e.name) + kind), ignored);
    for (const char* written : {"parameters.h5", "fit_report.md", "parameters.json"})
      std::filesystem::remove(out / written, ignored);
    throw;
  }
}

}  // namespace dtwire::calibrate
