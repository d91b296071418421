#include "propagation_outputs.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "../cli.hpp"
#include "../plotting.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

std::string fixed(double x, int significant = 4) {
  if (!std::isfinite(x)) return "-";
  std::ostringstream s;
  s << std::setprecision(significant) << x;
  return s.str();
}

// The coordinate of parameter i in sample s (ln v for a log coordinate).
double coordinate(const PropagationResult& r, std::size_t s, std::size_t i) {
  const double v = r.sample_values[s][i];
  return r.parameters[i].logarithmic ? std::log(v) : v;
}

// Figure f and the coordinate of parameter i over the successful sets where f is defined.
void paired(const PropagationResult& r, std::size_t f, std::size_t i, std::vector<double>& x, std::vector<double>& y) {
  for (std::size_t s = 0; s < r.sample_figures.size(); ++s)
    if (r.sample_status[s] == "ok" && std::isfinite(r.sample_figures[s][f])) {
      x.push_back(coordinate(r, s, i));
      y.push_back(r.sample_figures[s][f]);
    }
}

json statistics_json(const calibrate::BandStatistics& s) {
  return {{"count", s.count}, {"mean", s.mean}, {"sd", s.sd}, {"q05", s.q05}, {"q95", s.q95},
          {"q05_standard_error", s.q05_standard_error}, {"q95_standard_error", s.q95_standard_error}};
}

json emulated_json(const PropagationResult& r, const EmulatedFigure& e) {
  json scales = json::object();
  for (std::size_t i = 0; i < r.parameters.size() && i < e.length_scales.size(); ++i) scales[r.parameters[i].name] = e.length_scales[i];
  return {{"training_runs", e.training}, {"band", statistics_json(e.band.with_error)},
          {"band_of_means", statistics_json(e.band.of_means)}, {"loo_q_squared", e.q_squared},
          {"loo_share_within_2sd", e.share_within_two_sd}, {"noise_sd", e.noise_sd},
          {"emulated_quantity", e.logarithmic ? "ln figure (Q^2 and noise_sd of ln f)" : "figure"},
          {"length_scales_in_sampled_spreads", scales}};
}

// The band of the whole curve: every successful set's y interpolated on a common x grid (0 to the
// smallest final x of the sets), then the 5, 50 and 95 % quantiles point by point.
Curve curve_band(const PropagationResult& r) {
  const CurveAxes axes = band_curve_axes(r.tool);
  Curve band;
  if (r.sample_curves.empty() || !r.base_curve.has(axes.x) || !r.base_curve.has(axes.y)) return band;
  const Channel& bx = r.base_curve.channel(axes.x);
  const Channel& by = r.base_curve.channel(axes.y);
  double end = bx.values.empty() ? 0.0 : *std::max_element(bx.values.begin(), bx.values.end());
  for (const Curve& c : r.sample_curves)
    if (c.has(axes.x)) end = std::min(end, *std::max_element(c.channel(axes.x).values.begin(), c.channel(axes.x).values.end()));
  constexpr int kPoints = 101;
  std::vector<double> grid(kPoints);
  for (int k = 0; k < kPoints; ++k) grid[k] = end * k / (kPoints - 1);
  const auto at = [](const Channel& x, const Channel& y, double g) {
    // The first crossing of g along the curve (x grows with the tool's travel).
    for (std::size_t k = 1; k < x.values.size(); ++k)
      if (x.values[k] >= g) {
        const double dx = x.values[k] - x.values[k - 1];
        const double t = dx > 0.0 ? (g - x.values[k - 1]) / dx : 1.0;
        return y.values[k - 1] + t * (y.values[k] - y.values[k - 1]);
      }
    return y.values.empty() ? std::nan("") : y.values.back();
  };
  std::vector<double> fitted(kPoints), q05(kPoints), q50(kPoints), q95(kPoints);
  for (int k = 0; k < kPoints; ++k) {
    std::vector<double> values;
    for (const Curve& c : r.sample_curves)
      if (c.has(axes.x) && c.has(axes.y)) values.push_back(at(c.channel(axes.x), c.channel(axes.y), grid[k]));
    fitted[k] = at(bx, by, grid[k]);
    q05[k] = calibrate::sample_quantile(values, 0.05);
    q50[k] = calibrate::sample_quantile(values, 0.5);
    q95[k] = calibrate::sample_quantile(values, 0.95);
  }
  band.add_channel(axes.x, bx.unit, grid);
  band.add_channel(axes.y + "_fitted", by.unit, fitted);
  band.add_channel(axes.y + "_q05", by.unit, q05);
  band.add_channel(axes.y + "_q50", by.unit, q50);
  band.add_channel(axes.y + "_q95", by.unit, q95);
  band.set_metadata("label", r.label);
  band.set_metadata("sets", std::to_string(r.sample_curves.size()));
  return band;
}

void write_summary(const PropagationResult& r, const std::filesystem::path& out) {
  json figures = json::array();
  for (std::size_t f = 0; f < r.figures.size(); ++f) {
    json entry = {{"key", r.figures[f].key}, {"label", r.figures[f].label}, {"unit", r.figures[f].unit},
                  {"fitted_set", finite_or_null(r.base_figures[f])}};
    if (f < r.band.size()) {
      entry["sampled"] = statistics_json(r.band[f]);
      entry["converged"] = static_cast<bool>(r.converged[f]);
    }
    if (r.emulator) {
      entry["emulated"] = f < r.emulated.size() && r.emulated[f] ? emulated_json(r, *r.emulated[f]) : json(nullptr);
      entry["emulator_converged"] = f < r.emulator_converged.size() && r.emulator_converged[f];
    }
    if (r.linearised) {
      const double sd = (*r.linearised)[f].sd;
      const double q05 = r.base_figures[f] - calibrate::kNormal95 * sd;
      entry["linearised"] = {{"sd", sd}, {"q05", q05}, {"q95", r.base_figures[f] + calibrate::kNormal95 * sd}};
      // Every mesh figure is a magnitude, positive at the fitted set: a first-order band that
      // reaches 0 says the expansion does not hold over the parameters' spread (a NOT IDENTIFIED
      // parameter's whole range), not that the figure could vanish.
      if (r.base_figures[f] > 0 && q05 <= 0)
        entry["linearised"]["not_valid"] =
            "the first-order band reaches 0 or below for a figure positive at the fitted set: the linearisation does "
            "not hold over the parameters' spread; sample it (--samples)";
    }
    figures.push_back(entry);
  }
  json parameters = json::array();
  for (const PropagatedParameter& p : r.parameters)
    parameters.push_back({{"name", p.name}, {"unit", p.unit}, {"value", p.value}, {"lower", p.lower}, {"upper", p.upper},
                          {"identified", p.identified}, {"sampled_as", p.normal ? "normal" : "uniform"},
                          {"coordinate", p.logarithmic ? "log" : "linear"}, {"coordinate_sd", p.coordinate_sd},
                          {"fit", p.fit_file}});
  json convergence = json::array();
  for (const ConvergenceRow& row : r.convergence) {
    json by_figure = json::object();
    for (std::size_t f = 0; f < r.figures.size(); ++f) {
      by_figure[r.figures[f].key] = statistics_json(row.figures[f]);
      if (f < row.emulated.size() && row.emulated[f]) by_figure[r.figures[f].key]["emulated"] = statistics_json(row.emulated[f]->band.with_error);
    }
    convergence.push_back({{"sets_drawn", row.count}, {"figures", by_figure}});
  }
  std::size_t failed = 0;
  json failures = json::array();
  for (std::size_t s = 0; s < r.sample_status.size(); ++s)
    if (r.sample_status[s] != "ok") ++failed, failures.push_back({{"sample", s + 1}, {"status", r.sample_status[s]}});
  const bool all_converged = !r.converged.empty() && std::all_of(r.converged.begin(), r.converged.end(), [](bool c) { return c; });
  json root = {{"run_file", r.run_file.string()}, {"tool", r.tool}, {"label", r.label}, {"mode", r.mode},
               {"seed", r.seed}, {"band_tolerance", r.tolerance},
               {"convergence_rule", "2 x bootstrap SE of each 5/95 % end <= band_tolerance x (q95 - q05), from 21 sets (JCGM 101:2008 7.9)"},
               {"figures", figures}, {"parameters", parameters},
               {"samples", {{"requested", r.requested == 0 ? json("auto") : json(r.requested)}, {"cap", r.max_samples},
                            {"drawn", r.sample_values.size()}, {"failed", failed}, {"failures", failures},
                            {"converged", all_converged}, {"draws_accepted", r.accepted}, {"draws_refused", r.refused}}},
               {"convergence", convergence}, {"notes", r.notes},
               {"emulator", r.emulator ? json{{"emulated_sets", r.emulated_sets}, {"minimum_training_runs", r.emulator_minimum_training},
                                              {"convergence_rule", "each end of the emulated band moved by <= band_tolerance x its width over each of the last two batches"},
                                              {"method", "Gaussian process, Matern 5/2 per parameter, nugget; hyperparameters by leave-one-out cross-validation"}}
                                       : json(nullptr)},
               {"runs", {{"dem_runs", r.runs_done}, {"cache_hits", r.cache_hits}}}, {"wall_seconds", r.wall_seconds},
               {"tool_version", version_string()}};
  write_file_atomically(out / "summary.json", [&](std::ostream& os) { os << root.dump(2) << "\n"; });
}

void write_samples(const PropagationResult& r, const std::filesystem::path& out) {
  write_file_atomically(out / "samples.csv", [&](std::ostream& os) {
    os << "# parameter sets drawn (own values, units in the header) and the headline figures of their runs\n";
    os << "# seed: " << r.seed << "\nsample_1";
    for (const PropagatedParameter& p : r.parameters) os << "," << p.name << "_" << (p.unit == "1" ? "1" : p.unit);
    for (const HeadlineFigure& f : r.figures) os << "," << f.column;
    os << ",status\n" << std::setprecision(10);
    for (std::size_t s = 0; s < r.sample_values.size(); ++s) {
      os << s + 1;
      for (double v : r.sample_values[s]) os << "," << v;
      for (double v : r.sample_figures[s]) os << "," << (std::isfinite(v) ? fixed(v, 10) : "");
      os << ",\"" << r.sample_status[s] << "\"\n";
    }
  });
}

void write_convergence(const PropagationResult& r, const std::filesystem::path& out) {
  write_file_atomically(out / "convergence.csv", [&](std::ostream& os) {
    os << "sets_drawn_1";
    for (const HeadlineFigure& f : r.figures)
      for (const char* s : {"mean", "sd", "q05", "q95", "q05_se", "q95_se"}) os << "," << f.key << "__" << s;
    if (r.emulator)
      for (const HeadlineFigure& f : r.figures)
        for (const char* s : {"emulated_q05", "emulated_q95", "emulator_q2"}) os << "," << f.key << "__" << s;
    os << "\n" << std::setprecision(8);
    for (const ConvergenceRow& row : r.convergence) {
      os << row.count;
      for (const calibrate::BandStatistics& b : row.figures)
        os << "," << b.mean << "," << b.sd << "," << b.q05 << "," << b.q95 << "," << b.q05_standard_error << "," << b.q95_standard_error;
      if (r.emulator)
        for (std::size_t f = 0; f < r.figures.size(); ++f) {
          if (f < row.emulated.size() && row.emulated[f])
            os << "," << row.emulated[f]->band.with_error.q05 << "," << row.emulated[f]->band.with_error.q95 << "," << row.emulated[f]->q_squared;
          else
            os << ",,,";
        }
      os << "\n";
    }
  });
}

// One row per figure and parameter (units in their own columns: the derivative is in
// figure_unit per parameter_unit).
void write_sensitivity(const PropagationResult& r, const std::filesystem::path& out) {
  write_file_atomically(out / "sensitivity.csv", [&](std::ostream& os) {
    os << "figure,figure_unit,parameter,parameter_unit,identified,sampled_as,coordinate,linearised_step_in_coordinate,"
          "derivative_figure_unit_per_parameter_unit,linearised_share_1,first_order_index_1,first_order_index_floor_1\n"
       << std::setprecision(6);
    for (std::size_t f = 0; f < r.figures.size(); ++f)
      for (std::size_t i = 0; i < r.parameters.size(); ++i) {
        const PropagatedParameter& p = r.parameters[i];
        os << r.figures[f].key << "," << r.figures[f].unit << "," << p.name << "," << p.unit << "," << (p.identified ? "yes" : "no")
           << "," << (p.normal ? "normal" : "uniform") << "," << (p.logarithmic ? "log" : "linear") << ",";
        if (r.linearised) {
          const double g = (*r.linearised)[f].gradient[i];
          // d f / d v = (d f / d y) / (d v / d y), d v / d y = v on a log coordinate.
          const double derivative = p.logarithmic ? g / p.value : g;
          const double step = (*r.linearised)[f].step[i];
          os << (std::isfinite(step) ? fixed(step, 6) : "") << "," << (std::isfinite(derivative) ? fixed(derivative, 6) : "") << ","
             << (*r.linearised)[f].share[i];
        } else {
          os << ",,";
        }
        std::vector<double> x, y;
        if (!r.sample_values.empty()) paired(r, f, i, x, y);
        const calibrate::FirstOrderIndex s = calibrate::first_order_index(x, y);
        os << "," << (x.size() >= 4 ? fixed(s.index, 6) : "") << "," << (x.size() >= 4 ? fixed(s.floor, 6) : "") << "\n";
      }
  });
}

void write_report(const PropagationResult& r, const std::filesystem::path& out, bool have_plot) {
  std::ostringstream md;
  md << "# Mesh-scale band: " << r.label << "\n\n"
     << "Run file `" << r.run_file.string() << "` (" << r.tool << "); " << r.mode << "; seed " << r.seed << ".\n\n";
  md << "| figure | fitted set | sampled mean +- sd | sampled 5-95 % | sets | converged | linearised 5-95 % |\n|---|---|---|---|---|---|---|\n";
  for (std::size_t f = 0; f < r.figures.size(); ++f) {
    md << "| " << r.figures[f].label << " (" << r.figures[f].unit << ") | " << fixed(r.base_figures[f]) << " | ";
    if (f < r.band.size() && r.band[f].count > 0)
      md << fixed(r.band[f].mean) << " +- " << fixed(r.band[f].sd, 3) << " | " << fixed(r.band[f].q05) << " - " << fixed(r.band[f].q95)
         << " | " << r.band[f].count << " | " << (r.converged[f] ? "yes" : "no") << " | ";
    else
      md << "- | - | 0 | - | ";
    if (r.linearised) {
      const double sd = (*r.linearised)[f].sd;
      md << fixed(r.base_figures[f] - calibrate::kNormal95 * sd) << " - " << fixed(r.base_figures[f] + calibrate::kNormal95 * sd);
    } else {
      md << "-";
    }
    md << " |\n";
  }
  if (r.linearised && !r.band.empty()) {
    md << "\nLinearised against sampled (width of the 5-95 % band, and the centre's shift):\n\n";
    for (std::size_t f = 0; f < r.figures.size(); ++f) {
      if (r.band[f].count == 0) continue;
      const double lin_width = 2.0 * calibrate::kNormal95 * (*r.linearised)[f].sd;
      const double width = r.band[f].q95 - r.band[f].q05;
      md << "- " << r.figures[f].label << ": linearised " << fixed(lin_width, 3) << " " << r.figures[f].unit << ", sampled "
         << fixed(width, 3) << " (ratio " << fixed(width > 0 ? lin_width / width : std::nan(""), 3) << "); centre of the sampled band "
         << fixed(0.5 * (r.band[f].q05 + r.band[f].q95)) << " against the fitted set's " << fixed(r.base_figures[f]) << "\n";
    }
  }
  if (r.emulator) {
    md << "\n## Emulated band\n\nA Gaussian-process emulator of each figure (Matern 5/2 per parameter with a nugget for the "
          "run-to-run scatter; hyperparameters by leave-one-out cross-validation) trained on the sets run, predicting the "
          "figure on " << r.emulated_sets << " sets drawn from the same distribution; the band includes the emulator's own "
          "error. A figure positive in every run is emulated as its logarithm (its band stays positive). Q^2: leave-one-out coefficient of determination (1: exact; 0: no better than the mean); within 2 sd: share "
          "of the runs the emulator trained without predicts within twice its sd (about 0.95 when its error is right). "
          "Converged: each end moved by at most " << r.tolerance << " x the width over each of the last two batches, from "
       << r.emulator_minimum_training << " runs on.\n\n"
       << "The last column reads the emulator as a sensitivity: the parameters with the shortest length scales (in "
          "sampled spreads; a figure changes markedly within one length scale, and hardly over the spread beyond about "
          "3).\n\n"
       << "| figure | emulated 5-95 % | mean +- sd | of the means alone | runs | Q^2 | within 2 sd | noise sd | converged | shortest length scales |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t f = 0; f < r.figures.size(); ++f) {
      md << "| " << r.figures[f].label << " (" << r.figures[f].unit << ") | ";
      if (f < r.emulated.size() && r.emulated[f]) {
        const EmulatedFigure& e = *r.emulated[f];
        md << fixed(e.band.with_error.q05) << " - " << fixed(e.band.with_error.q95) << " | " << fixed(e.band.with_error.mean) << " +- "
           << fixed(e.band.with_error.sd, 3) << " | " << fixed(e.band.of_means.q05) << " - " << fixed(e.band.of_means.q95) << " | "
           << e.training << " | " << fixed(e.q_squared, 3) << " | " << fixed(e.share_within_two_sd, 2) << " | " << fixed(e.noise_sd, 3)
           << (e.logarithmic ? " (of ln f)" : "") << " | " << (f < r.emulator_converged.size() && r.emulator_converged[f] ? "yes" : "no")
           << " | ";
        std::vector<std::size_t> order(std::min(e.length_scales.size(), r.parameters.size()));
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return e.length_scales[a] < e.length_scales[b]; });
        for (std::size_t k = 0; k < std::min<std::size_t>(3, order.size()); ++k)
          md << (k ? ", " : "") << r.parameters[order[k]].name << " " << fixed(e.length_scales[order[k]], 2);
        md << " |\n";
      } else {
        md << "- (fewer than " << r.emulator_minimum_training << " runs with the figure) | - | - | - | - | - | - | - | - |\n";
      }
    }
  }
  md << "\nConvergence rule: after each batch, twice the bootstrap standard error of each band end (5 % and 95 %) "
     << "within " << r.tolerance << " x the band's width, from 21 sets on (JCGM 101:2008 7.9); cap " << r.max_samples << " sets.\n\n";
  if (!r.convergence.empty()) {
    md << "| sets drawn |";
    for (const HeadlineFigure& f : r.figures) md << " " << f.key << " 5-95 % (SE of the ends) |";
    md << "\n|---|";
    for (std::size_t f = 0; f < r.figures.size(); ++f) md << "---|";
    md << "\n";
    for (const ConvergenceRow& row : r.convergence) {
      md << "| " << row.count << " |";
      for (const calibrate::BandStatistics& b : row.figures)
        md << " " << fixed(b.q05) << " - " << fixed(b.q95) << " (" << fixed(b.q05_standard_error, 2) << ", "
           << fixed(b.q95_standard_error, 2) << ") |";
      md << "\n";
    }
  }
  md << "\n## Sensitivities\n\nPer figure and parameter: the derivative at the fitted set (finite difference over the "
        "sampled spread, in the figure's unit per the parameter's), its share of the linearised variance "
        "(g_i^2 C_ii / g^T C g), and the first-order index from the samples (Plischke et al. 2013; a parameter the "
        "figure does not depend on scores about the floor).\n\n"
     << "| figure | parameter | identified | sampled as | derivative | linearised share | first-order index (floor) |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (std::size_t f = 0; f < r.figures.size(); ++f)
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
      const PropagatedParameter& p = r.parameters[i];
      md << "| " << r.figures[f].key << " | " << p.name << " | " << (p.identified ? "yes" : "**no**") << " | "
         << (p.normal ? "normal" : "uniform [" + fixed(p.lower) + ", " + fixed(p.upper) + "]") << (p.logarithmic ? " (log)" : "") << " | ";
      if (r.linearised) {
        const double g = (*r.linearised)[f].gradient[i];
        md << fixed(p.logarithmic ? g / p.value : g, 3) << " " << r.figures[f].unit << "/" << p.unit << " | "
           << fixed(100.0 * (*r.linearised)[f].share[i], 3) << " % | ";
      } else {
        md << "- | - | ";
      }
      std::vector<double> x, y;
      if (!r.sample_values.empty()) paired(r, f, i, x, y);
      const calibrate::FirstOrderIndex s = calibrate::first_order_index(x, y);
      md << (x.size() >= 4 ? fixed(s.index, 2) + " (" + fixed(s.floor, 2) + ")" : "-") << " |\n";
    }
  std::size_t failed = 0;
  for (const std::string& s : r.sample_status) failed += s != "ok";
  md << "\nDraws, summed over the fits (one per fit and set): " << r.accepted << " accepted, " << r.refused
     << " refused (outside a bound or an offset's order, or refused by the contact law: the truncated distribution by "
     << "rejection). " << failed << " of " << r.sample_status.size()
     << " sets failed in their run (stopped by its checks, the law gave up, or a punch that does not load the net to "
        "failure within the travel; reasons in samples.csv), left out of the "
     << "band. DEM runs: " << r.runs_done << " ("
     << r.cache_hits << " from the cache), " << fixed(r.wall_seconds, 4) << " s.\n";
  for (const std::string& note : r.notes) md << "\n- " << note;
  if (have_plot) md << "\n\n![band of the curve](band.png)\n";
  write_file_atomically(out / "report.md", [&](std::ostream& os) { os << md.str(); });
}

}  // namespace

std::vector<double> figure_values(const PropagationResult& r, std::size_t f) {
  std::vector<double> values;
  for (std::size_t s = 0; s < r.sample_figures.size(); ++s)
    if (r.sample_status[s] == "ok" && std::isfinite(r.sample_figures[s][f])) values.push_back(r.sample_figures[s][f]);
  return values;
}

void write_propagation_outputs(const PropagationResult& r, const std::filesystem::path& out, bool plot) {
  std::filesystem::create_directories(out);
  remove_stale_temporaries(out);
  write_summary(r, out);
  if (!r.sample_values.empty()) {
    write_samples(r, out);
    write_convergence(r, out);
  }
  write_sensitivity(r, out);
  const Curve band = curve_band(r);
  bool have_plot = false;
  if (band.size() > 0) {
    write_csv(band, out / "band_curve.csv");
    if (plot) {
      run_plot_script("plot_band.py", {(out / "band.png").string(), (out / "band_curve.csv").string(), r.label});
      have_plot = true;
    }
  }
  write_report(r, out, have_plot);
}

}  // namespace dtwire::app
