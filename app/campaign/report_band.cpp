#include "report_band.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "commands/propagation_runs.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

std::string number(double value, int digits = 3) {
  if (!std::isfinite(value)) return "n/a";
  std::ostringstream s;
  s << std::setprecision(digits) << value;
  return s.str();
}

bool has_number(const json& o, const char* key) { return o.is_object() && o.contains(key) && o[key].is_number(); }

// The standard's figure for a strip figure key (report_recommendation.hpp names the sources).
std::string standard_of(const std::string& key) {
  if (key == "strength_per_width_kN_per_m") return "50 kN/m";
  if (key == "secant_EA_10_50_kN_per_m") return "about 500 kN/m";
  return "-";
}

// The thesis sets' run's value of a figure, in the figure's unit.
std::string thesis_value(const std::string& key, const std::string& tool, const json& strip, const json& punch) {
  const json& run = tool == "strip_tension" ? strip : punch;
  if (!has_number(run, key.c_str())) return "-";
  const double factor = key == "peak_force_N" ? 1e-3 : 1.0;
  return number(run[key].get<double>() * factor);
}

}  // namespace

std::optional<FigureBand> figure_band(const std::vector<BandEvidence>& bands, const std::string& label,
                                      const std::string& tool, const std::string& key) {
  // Rank of a band by the header's order: 4 converged sampled, 3 converged emulated, 2 sampled, 1 linearised.
  std::optional<FigureBand> found;
  int found_rank = 0;
  const auto offer = [&](FigureBand band, int rank) {
    if (rank > found_rank) found = band, found_rank = rank;
  };
  for (const BandEvidence& b : bands) {
    if (b.label != label || !b.summary.is_object() || b.summary.value("tool", "") != tool) continue;
    for (const json& f : b.summary.value("figures", json::array())) {
      if (f.value("key", "") != key) continue;
      const json sampled = f.value("sampled", json::object());
      const json linearised = f.value("linearised", json::object());
      const json emulated = f.contains("emulated") && f["emulated"].is_object() ? f["emulated"].value("band", json::object()) : json::object();
      if (sampled.value("count", 0) > 0 && has_number(sampled, "q05") && has_number(sampled, "q95"))
        offer(FigureBand{sampled["q05"].get<double>(), sampled["q95"].get<double>(), true, false, true, b.step},
              f.value("converged", false) ? 4 : 2);
      if (f.value("emulator_converged", false) && has_number(emulated, "q05") && has_number(emulated, "q95"))
        offer(FigureBand{emulated["q05"].get<double>(), emulated["q95"].get<double>(), false, true, true, b.step}, 3);
      if (has_number(linearised, "q05") && has_number(linearised, "q95"))
        offer(FigureBand{linearised["q05"].get<double>(), linearised["q95"].get<double>(), false, false,
                         !linearised.contains("not_valid"), b.step},
              1);
    }
  }
  return found;
}

std::vector<std::vector<std::string>> read_sensitivity_rows(const std::string& file) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

std::string band_markdown(const std::string& label, const std::vector<BandEvidence>& bands, const json& thesis_strip,
                          const json& thesis_punch, const json& own_strip, const json& own_punch) {
  std::ostringstream md;
  bool any = false;
  for (const BandEvidence& b : bands) any = any || b.label == label;
  if (!any) return {};
  md << "#### The recommended set's mesh figures with their band\n\n"
     << "The fits' uncertainty carried to the mesh by `dtwire dem propagate` (docs/dem_engine.md, \"Propagating a "
        "fit's uncertainty\"): identified parameters drawn from the fit's covariance, NOT IDENTIFIED ones uniform over "
        "their range. Sampled bands are the 5-95 % quantiles of the runs; linearised ones the fitted set's value -+ "
        "1.645 sqrt(J C J^T).\n\n"
     << "| figure | fitted set | 5-95 % band | how | standard | thesis's published sets |\n|---|---|---|---|---|---|\n";
  for (const BandEvidence& b : bands) {
    if (b.label != label) continue;
    if (!b.summary.is_object()) {
      md << "| `" << b.step << "` | (no result: " << b.status << ") | | | | |\n";
      continue;
    }
    const std::string tool = b.summary.value("tool", "");
    const json& samples = b.summary.value("samples", json::object());
    for (const json& f : b.summary.value("figures", json::array())) {
      const std::string key = f.value("key", ""), unit = f.value("unit", "");
      md << "| " << f.value("label", key) << " (" << unit << ") | " << (has_number(f, "fitted_set") ? number(f["fitted_set"].get<double>()) : "n/a")
         << " | ";
      if (f.contains("sampled") && f["sampled"].value("count", 0) > 0) {
        const json& s = f["sampled"];
        md << number(s.value("q05", NAN)) << " - " << number(s.value("q95", NAN)) << " | sampled, " << s.value("count", 0)
           << " runs of " << samples.value("drawn", 0) << " drawn, " << (f.value("converged", false) ? "converged" : "**not converged**");
        if (f.contains("emulated") && f["emulated"].is_object()) {
          const json& e = f["emulated"];
          const json band = e.value("band", json::object());
          md << "; emulated " << number(band.value("q05", NAN)) << " - " << number(band.value("q95", NAN)) << " (Gaussian process on "
             << e.value("training_runs", 0) << " runs, leave-one-out Q^2 " << number(e.value("loo_q_squared", NAN), 2) << ", "
             << (f.value("emulator_converged", false) ? "converged" : "**not converged**") << ")";
        }
        if (f.contains("linearised"))
          md << "; linearised " << number(f["linearised"].value("q05", NAN)) << " - " << number(f["linearised"].value("q95", NAN));
      } else if (f.contains("linearised") && f["linearised"].contains("not_valid")) {
        md << "not valid (" << number(f["linearised"].value("q05", NAN)) << " - " << number(f["linearised"].value("q95", NAN))
           << ") | linearised (J C J^T): " << f["linearised"].value("not_valid", "");
      } else if (f.contains("linearised")) {
        md << number(f["linearised"].value("q05", NAN)) << " - " << number(f["linearised"].value("q95", NAN))
           << " | linearised (J C J^T)";
      } else {
        md << "n/a | ";
      }
      md << " (`" << b.step << "`) | " << standard_of(key) << " | " << thesis_value(key, tool, thesis_strip, thesis_punch) << " |\n";
    }
  }
  // The set's own runs whose figures no step of this campaign bands: shown with their value and
  // said to be unbanded, so that no figure looks as if it had no uncertainty.
  for (const auto& [tool, run] : {std::pair<std::string, const json*>{"strip_tension", &own_strip}, {"platter", &own_punch}}) {
    if (!run->is_object()) continue;
    bool explained = false;
    for (const HeadlineFigure& f : headline_figures(tool)) {
      if (!has_number(*run, f.key.c_str()) || figure_band(bands, label, tool, f.key)) continue;
      md << "| " << f.label << " (" << f.unit << ") | " << number((*run)[f.key].get<double>() * f.factor)
         << " | not banded by this campaign | ";
      if (!explained)
        md << "a linearised band takes one " << (tool == "platter" ? "punch" : "strip")
           << " per fitted parameter (`dtwire dem propagate`, docs/dem_engine.md, \"Propagating a fit's uncertainty\"; "
           << "the study campaign runs it)";
      else
        md << "as above";
      explained = true;
      md << " | " << standard_of(f.key) << " | " << thesis_value(f.key, tool, thesis_strip, thesis_punch) << " |\n";
    }
  }
  // Which parameter each figure hangs on: the largest linearised shares (or first-order indices).
  md << "\n| step | figure | parameter (identified?) | derivative (figure unit / parameter unit) | share of the linearised variance | first-order index from the samples |\n"
        "|---|---|---|---|---|---|\n";
  for (const BandEvidence& b : bands) {
    if (b.label != label || b.sensitivity.size() < 2) continue;
    std::map<std::string, std::size_t> column;
    for (std::size_t k = 0; k < b.sensitivity.front().size(); ++k) column[b.sensitivity.front()[k]] = k;
    const auto cell = [&](const std::vector<std::string>& row, const char* name) {
      const auto c = column.find(name);
      return c == column.end() || c->second >= row.size() ? std::string() : row[c->second];
    };
    for (std::size_t r = 1; r < b.sensitivity.size(); ++r) {
      const auto& row = b.sensitivity[r];
      const std::string share = cell(row, "linearised_share_1"), index = cell(row, "first_order_index_1");
      // Rows that carry at least 5 % of a figure's variance (either measure): the table is for reading.
      const double weight = std::max(share.empty() ? 0.0 : std::atof(share.c_str()), index.empty() ? 0.0 : std::atof(index.c_str()) -
                                                                                           std::atof(cell(row, "first_order_index_floor_1").c_str()));
      if (weight < 0.05) continue;
      md << "| `" << b.step << "` | " << cell(row, "figure") << " | " << cell(row, "parameter") << " ("
         << cell(row, "identified") << ") | " << cell(row, "derivative_figure_unit_per_parameter_unit") << " " << cell(row, "figure_unit")
         << "/" << cell(row, "parameter_unit") << " | " << (share.empty() ? "-" : number(100.0 * std::atof(share.c_str())) + " %")
         << " | " << (index.empty() ? "-" : index + " (floor " + cell(row, "first_order_index_floor_1") + ")") << " |\n";
    }
  }
  md << "\nRows: the parameters that carry at least 5 % of a figure's variance by either measure; every row is in "
        "each step's sensitivity.csv.\n\n";
  return md.str();
}

}  // namespace dtwire::app
