#include "report_summary.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "campaign_graph.hpp"
#include "report_band.hpp"
#include "report_mesh_scale.hpp"
#include "report_recommendation.hpp"
#include "step_process.hpp"
#include "dtwire/core/csv.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

// Above this NRMSE a fitted curve is listed under "what to distrust" as a model-form gap: the
// law cannot follow the curve whatever its parameters (docs/calibrate.md).
constexpr double kModelFormNrmse = 0.10;

enum class Kind { Fit, Gap, Validation, Band, Other };

Kind kind_of(const CampaignStep& step) {
  const auto& c = step.command;
  if (c.front() == "fit") return Kind::Fit;
  if (c.front() == "gap") return c.size() > 1 && c[1] == "selfcheck" ? Kind::Other : Kind::Gap;
  if (c.front() == "dem" && c.size() > 1 && (c[1] == "run" || c[1] == "plot-punch")) return Kind::Validation;
  if (c.front() == "dem" && c.size() > 1 && c[1] == "propagate") return Kind::Band;
  return Kind::Other;
}

std::string number(double value, int digits = 4) {
  if (!std::isfinite(value)) return "n/a";
  std::ostringstream s;
  s << std::setprecision(digits) << value;
  return s.str();
}

// A fraction as a whole percentage ("100", never "1e+02").
std::string percent(double fraction) {
  if (!std::isfinite(fraction)) return "n/a";
  std::ostringstream s;
  s << std::fixed << std::setprecision(0) << 100.0 * fraction;
  return s.str();
}

std::string number_of(const json& value, int digits = 4) {
  return value.is_number() ? number(value.get<double>(), digits) : std::string("n/a");
}

std::string text_of(const json& object, const std::string& key) {
  return object.is_object() && object.contains(key) && object[key].is_string() ? object[key].get<std::string>()
                                                                                 : std::string();
}

json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  try {
    return json::parse(in);
  } catch (const json::exception&) {
    return json();
  }
}

std::string link(const std::string& text, const std::string& step) { return "[" + text + "](#" + heading_anchor(step) + ")"; }

struct StepFiles {
  const CampaignStep* step;
  const StepOutcome* outcome;
  std::vector<std::filesystem::path> files;    // existing, expanded
  std::vector<std::filesystem::path> figures;  // the images among its report items
};

// The summary files of a step: declared, or those of its outputs and report the summary reads.
std::vector<std::filesystem::path> summary_files(const CampaignStep& step, const std::filesystem::path& out,
                                                 const std::filesystem::path& campaign_dir) {
  std::vector<std::string> candidates = step.summary;
  if (candidates.empty()) {
    candidates = step.outputs;
    candidates.insert(candidates.end(), step.report.begin(), step.report.end());
  }
  std::vector<std::filesystem::path> files;
  for (const auto& c : candidates) {
    const std::filesystem::path file = expand(c, out, campaign_dir);
    const std::string ext = file.extension().string();
    const Kind kind = kind_of(step);
    const bool wanted = !step.summary.empty() ||
                        (kind == Kind::Fit && file.filename() == "parameters.json") ||
                        (kind == Kind::Gap && ext == ".json") ||
                        (kind == Kind::Validation && (ext == ".png" || ext == ".svg" || ext == ".csv" || ext == ".json"));
    if (wanted && std::filesystem::is_regular_file(file) &&
        std::find(files.begin(), files.end(), file) == files.end())
      files.push_back(file);
  }
  return files;
}

std::string wire_type_name(const std::string& wire_type) {
  if (wire_type == "single_wire") return "Single wire (SW)";
  if (wire_type == "double_twist") return "Double twist (DT)";
  return wire_type.empty() ? "Parameter set" : wire_type;
}

void figure(std::ostream& md, const std::filesystem::path& file, const std::filesystem::path& out) {
  const std::string relative = std::filesystem::relative(file, out).string();
  const std::string ext = file.extension().string();
  if (ext == ".png" || ext == ".svg") md << "![" << file.stem().string() << "](" << relative << ")\n\n";
  else md << "- [`" << relative << "`](" << relative << ")\n";
}

// The figures a step shows in its report (fit overlays, gap shading), side by side in the summary.
void step_figures(std::ostream& md, const StepFiles& s, const std::filesystem::path& out) {
  for (const auto& file : s.figures)
    md << "![" << s.step->name << ": " << file.stem().string() << "](" << std::filesystem::relative(file, out).string() << ") ";
  if (!s.figures.empty()) md << "\n\n";
}

// The fitted set and its NRMSE per loading mode (rows) and channel (columns); returns the line
// for the summary's "at a glance".
std::string fit_section(std::ostream& md, const StepFiles& s, const std::filesystem::path& file,
                        const std::filesystem::path& out, std::vector<std::string>& distrust) {
  const json fit = read_json(file);
  if (!fit.is_object() || !fit.contains("parameters")) return {};
  const std::string wire_type = text_of(fit, "wire_type");
  const std::string law = text_of(fit, "law");
  md << "**" << wire_type_name(wire_type) << "**, law `" << law << "`, from step " << link(s.step->name, s.step->name)
     << " (`" << std::filesystem::relative(file, out).string() << "`):\n\n| parameter | value | sigma | unit |\n|---|---|---|---|\n";
  std::size_t fitted = 0;
  for (const json& p : fit["parameters"])
    if (p.value("fitted", false)) {
      ++fitted;
      md << "| " << text_of(p, "name") << " | " << number_of(p["value"], 5) << " | " << number_of(p["sigma"], 2)
         << " | " << text_of(p, "unit") << " |\n";
    }
  std::vector<std::string> modes, channels;
  std::map<std::pair<std::string, std::string>, double> nrmse;
  for (const json& q : fit.value("fit_quality", json::array())) {
    const std::string mode = text_of(q, "experiment"), channel = text_of(q, "quantity");
    if (std::find(modes.begin(), modes.end(), mode) == modes.end()) modes.push_back(mode);
    if (std::find(channels.begin(), channels.end(), channel) == channels.end()) channels.push_back(channel);
    nrmse[{mode, channel}] = q.value("nrmse", std::nan(""));
  }
  md << "\nFit quality, NRMSE (RMSE over the target's range; ⚠ above " << number(kModelFormNrmse)
     << "):\n\n| loading mode |";
  for (const auto& c : channels) md << " " << c << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < channels.size(); ++i) md << "---|";
  md << "\n";
  std::string missed;  // curves beyond kModelFormNrmse
  double low = std::numeric_limits<double>::infinity(), high = 0.0;
  for (const auto& mode : modes) {
    md << "| " << mode << " |";
    for (const auto& channel : channels) {
      const auto value = nrmse.find({mode, channel});
      if (value == nrmse.end()) {
        md << " |";
        continue;
      }
      const double v = value->second;
      low = std::min(low, v);
      high = std::max(high, v);
      md << " " << number(v, 2) << (v > kModelFormNrmse ? " ⚠" : "") << " |";
      if (v > kModelFormNrmse)
        missed += std::string(missed.empty() ? "" : ", ") + "`" + mode + "` (" + channel + " " + number(v, 2) + ")";
    }
    md << "\n";
  }
  if (!missed.empty())
    distrust.push_back("Model-form gap: the " + wire_type_name(wire_type) + " law `" + law + "` cannot follow " + missed +
                       " (NRMSE > " + number(kModelFormNrmse) + ") whatever its parameters; see " +
                       link(s.step->name, s.step->name) + ".");
  md << "\n";
  step_figures(md, s, out);
  for (const json& w : fit.value("warnings", json::array()))
    if (w.is_string()) distrust.push_back("Fit " + link(s.step->name, s.step->name) + ": " + w.get<std::string>());
  return "**" + wire_type_name(wire_type) + " set** (law `" + law + "`, " + std::to_string(fitted) +
         " fitted parameters with sigma): NRMSE " + number(low, 2) + "-" + number(high, 2) + " over " +
         std::to_string(modes.size()) + " loading modes" +
         (missed.empty() ? std::string() : ", some beyond the law's reach") + " ([set](#calibrated-parameter-sets)).";
}

// The region with the largest share of the gap, "post_peak (12-30 mm, 64 %)".
std::string main_region(const json& where) {
  const json* best = nullptr;
  for (const json& w : where)
    if (w.is_object() && (!best || w.value("share", 0.0) > best->value("share", 0.0))) best = &w;
  if (!best) return "n/a";
  std::vector<std::string> details;
  if (best->contains("feature")) details.push_back(text_of(*best, "feature"));
  else if (best->contains("from_mm"))
    details.push_back(number_of((*best)["from_mm"], 3) + "-" + number_of((*best)["to_mm"], 3) + " mm");
  if (best->contains("share")) details.push_back(percent(best->value("share", 0.0)) + " % of the gap");
  std::string text = text_of(*best, "region");
  for (std::size_t i = 0; i < details.size(); ++i) text += (i == 0 ? " (" : ", ") + details[i];
  return details.empty() ? text : text + ")";
}

// One verdict row; returns "case: cause (shrink)" for the summary's "at a glance".
std::string gap_row(std::ostream& md, const StepFiles& s, const json& gap, const std::string& label,
                    std::vector<std::string>& distrust) {
  const std::string cause = text_of(gap, "cause");
  const double before = gap.value("gap_before", std::nan(""));
  const double floor = gap.value("noise_floor", std::nan(""));
  double shrink = 0.0;
  for (const json& r : gap.value("ranking", json::array()))
    if (text_of(r, "effect") == cause) {
      shrink = r.value("shrink", 0.0);
      break;
    }
  const bool explained = cause != "none" && !cause.empty();
  md << "| " << link(label, s.step->name) << " | " << (cause.empty() ? "n/a" : "**" + cause + "**") << " | "
     << (explained ? percent(shrink) + " %" : "n/a") << " | " << main_region(gap.value("where", json::array()))
     << " | " << number(before, 3) << " (" << number(floor, 3) << ") | " << text_of(gap, "cause_reason") << " |\n";
  // What is left of the gap after the cause (all of it if there is none) against the noise floor.
  const double left = before * (1.0 - shrink);
  if (std::isfinite(left) && std::isfinite(floor) && left > floor)
    distrust.push_back("Gap " + link(label, s.step->name) + ": " +
                       (explained ? "after `" + cause + "` a gap of " + number(left, 3)
                                  : "an unexplained gap of " + number(left, 3)) +
                       " is left, above the noise floor " + number(floor, 3) + ".");
  return label + ": " + (explained ? "`" + cause + "` (gap " + percent(shrink) + " % smaller)"
                                   : before <= floor ? "within the noise" : "unexplained");
}

// Whether a punch run applies to its set-up, from its curve.csv (nothing if it has none: a run
// whose curve is unknown is taken as it reports itself).
std::optional<std::string> punch_applicability(const StepFiles& s) {
  for (const auto& file : s.files) {
    if (file.filename() != "summary.json") continue;
    try {
      std::ifstream in(file);
      if (const auto why = punch_not_at_rest(nlohmann::json::parse(in))) return why;
    } catch (const std::exception&) {
    }
  }
  for (const auto& file : s.files) {
    if (file.filename() != "curve.csv") continue;
    try {
      const Curve curve = read_csv(file);
      if (!curve.has("tool_displacement") || !curve.has("tool_force")) return std::nullopt;
      return punch_not_applicable(curve.si("tool_displacement"), curve.si("tool_force"));
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }
  return std::nullopt;
}

// The fit steps upstream of step `index` (through the campaign's graph), in the file's order.
std::vector<std::size_t> fits_behind(const Campaign& campaign, const std::vector<std::vector<std::size_t>>& waits,
                                     std::size_t index) {
  std::vector<bool> upstream(campaign.steps.size(), false);
  std::vector<std::size_t> todo{index};
  while (!todo.empty()) {
    const std::size_t i = todo.back();
    todo.pop_back();
    for (const std::size_t j : waits[i])
      if (!upstream[j]) {
        upstream[j] = true;
        todo.push_back(j);
      }
  }
  std::vector<std::size_t> fits;
  for (std::size_t j = 0; j < campaign.steps.size(); ++j)
    if (upstream[j] && kind_of(campaign.steps[j]) == Kind::Fit) fits.push_back(j);
  return fits;
}

// The parameter files a dem run reads through --set-params TAG=FILE, relative to `out`.
std::vector<std::string> set_params_files(const CampaignStep& step, const std::filesystem::path& out,
                                          const std::filesystem::path& campaign_dir) {
  std::vector<std::string> files;
  for (std::size_t i = 0; i + 1 < step.command.size(); ++i)
    if (step.command[i] == "--set-params") {
      const std::string& value = step.command[i + 1];
      const auto equals = value.find('=');
      const std::filesystem::path file = expand(equals == std::string::npos ? value : value.substr(equals + 1), out, campaign_dir);
      files.push_back(std::filesystem::relative(file, out).string());
    }
  return files;
}

// The sets the campaign's labelled DEM runs judge, with the fits behind them (rule 1 of
// report_recommendation.hpp), in the order their runs first appear.
std::vector<SetEvidence> set_evidence(const Campaign& campaign, const std::vector<StepFiles>& runs,
                                      const std::filesystem::path& out, const std::filesystem::path& campaign_dir) {
  const auto waits = step_dependencies(campaign);
  std::vector<SetEvidence> sets;
  for (const StepFiles& s : runs) {
    const std::string label = label_of_command(s.step->command);
    if (label.empty()) continue;
    auto set = std::find_if(sets.begin(), sets.end(), [&](const SetEvidence& e) { return e.label == label; });
    if (set == sets.end()) set = sets.insert(sets.end(), SetEvidence{label, {}, {}, json(), json(), "", "", "", "", std::nullopt});
    const std::size_t index = static_cast<std::size_t>(s.step - &campaign.steps.front());
    for (const std::size_t f : fits_behind(campaign, waits, index)) {
      const std::string& name = campaign.steps[f].name;
      if (std::any_of(set->fits.begin(), set->fits.end(), [&](const FitEvidence& e) { return e.step == name; })) continue;
      FitEvidence fit{name, json()};
      for (const auto& output : campaign.steps[f].outputs) {
        const std::filesystem::path file = expand(output, out, campaign_dir);
        if (file.filename() == "parameters.json" && std::filesystem::is_regular_file(file)) fit.parameters = read_json(file);
      }
      set->fits.push_back(fit);
    }
    for (const auto& file : set_params_files(*s.step, out, campaign_dir))
      if (std::find(set->files.begin(), set->files.end(), file) == set->files.end()) set->files.push_back(file);
    json summary;
    for (const auto& file : s.files)
      if (file.filename() == "summary.json") summary = read_json(file);
    // The tool the run says it used, else the one its run file's name suggests (a step without results).
    std::string tool = summary.is_object() ? summary.value("tool", "") : "";
    if (tool.empty()) {
      const std::string file = s.step->command.size() > 2 ? s.step->command[2] : "";
      tool = file.find("strip") != std::string::npos ? "strip_tension" : file.find("punch") != std::string::npos ? "platter" : "";
    }
    if (tool == "platter") {
      set->punch = summary;
      set->punch_step = s.step->name;
      set->punch_status = status_name(s.outcome->status);
      set->punch_not_applicable = punch_applicability(s);
    } else if (tool == "strip_tension") {
      set->strip = summary;
      set->strip_step = s.step->name;
      set->strip_status = status_name(s.outcome->status);
    }
  }
  return sets;
}

}  // namespace

std::string heading_anchor(const std::string& heading) {
  std::string anchor;
  for (unsigned char c : heading) {
    if (std::isalnum(c) || c == '_' || c == '-') anchor += static_cast<char>(std::tolower(c));
    else if (c == ' ') anchor += '-';
    else if (c >= 0x80) anchor += static_cast<char>(c);  // keep UTF-8 letters
  }
  return anchor;
}

std::string summary_markdown(const Campaign& campaign, const std::vector<StepOutcome>& outcomes,
                             const std::filesystem::path& out) {
  const auto campaign_dir = std::filesystem::absolute(campaign.file).parent_path();
  std::map<Kind, std::vector<StepFiles>> by_kind;
  std::vector<std::string> distrust;
  std::vector<std::pair<std::string, std::string>> log_warnings;  // step, line
  for (const StepOutcome& o : outcomes) {
    const auto step = std::find_if(campaign.steps.begin(), campaign.steps.end(),
                                   [&](const CampaignStep& s) { return s.name == o.name; });
    if (step == campaign.steps.end()) continue;
    if (o.status == StepStatus::Failed || o.status == StepStatus::Blocked || o.status == StepStatus::Unavailable)
      distrust.push_back("Step " + link(o.name, o.name) + " " + status_name(o.status) +
                         (o.message.empty() ? "" : ": " + o.message) + "; its results are missing below.");
    std::vector<std::filesystem::path> figures;
    for (const auto& item : step->report) {
      const std::filesystem::path file = expand(item, out, campaign_dir);
      const std::string ext = file.extension().string();
      if ((ext == ".png" || ext == ".svg") && std::filesystem::is_regular_file(file)) figures.push_back(file);
    }
    by_kind[kind_of(*step)].push_back({&*step, &o, summary_files(*step, out, campaign_dir), figures});
    // Warnings the step printed (its console log), at most 5 per step.
    std::ifstream log(step_folder(out, o.name) / "output.log");
    std::set<std::string> seen;
    for (std::string line; std::getline(log, line);)
      if ((line.rfind("warning", 0) == 0 || line.rfind("Warning", 0) == 0) && seen.insert(line).second && seen.size() <= 5)
        log_warnings.emplace_back(o.name, line);
  }

  std::ostringstream md;
  std::vector<std::string> glance, gap_glance;
  md << "### Calibrated parameter sets\n\n";
  std::set<std::string> fitted_types;
  for (const StepFiles& s : by_kind[Kind::Fit])
    for (const auto& file : s.files) {
      const json fit = read_json(file);
      if (fit.is_object()) fitted_types.insert(text_of(fit, "wire_type"));
      if (auto line = fit_section(md, s, file, out, distrust); !line.empty()) glance.push_back(line);
    }
  for (const std::string type : {"single_wire", "double_twist"})
    if (!fitted_types.count(type)) {
      md << "- " << wire_type_name(type) << ": no fit step in this campaign calibrates this set.\n";
      glance.push_back("**" + wire_type_name(type) + " set**: not calibrated in this campaign.");
    }
  md << "\n";

  md << "### Mesh-scale validation\n\n";
  std::string peaks;  // "step: peak at displacement" of each run, for the at-a-glance line
  if (by_kind[Kind::Validation].empty())
    md << "No mesh-scale DEM step (`dtwire dem run`, e.g. the punch test against the thesis figures) in this "
          "campaign yet.\n\n";
  bool table_started = false;
  for (const StepFiles& s : by_kind[Kind::Validation])
    for (const auto& file : s.files) {
      if (file.filename() != "summary.json") continue;
      const json run = read_json(file);
      if (!run.is_object()) continue;
      if (!table_started)
        md << "| step | peak force (kN) | displacement at peak (mm) | sag after settling (mm) | broken links | "
              "largest energy balance error (% of work) |\n|---|---|---|---|---|---|\n";
      table_started = true;
      const auto number = [&](const char* key, double scale, int digits = 1) {
        std::ostringstream o;
        o << std::fixed << std::setprecision(digits) << run.value(key, 0.0) * scale;
        return o.str();
      };
      if (const auto why = run.value("tool", "") == "platter" ? punch_applicability(s) : std::nullopt) {
        md << "| " << link(s.step->name, s.step->name) << " | not applicable: " << *why << " | | | | |\n";
        peaks += std::string(peaks.empty() ? "" : "; ") + s.step->name + " not applicable";
        continue;
      }
      md << "| " << link(s.step->name, s.step->name) << " | " << number("peak_force_N", 1e-3) << " | "
         << number("displacement_at_peak_mm", 1.0) << " | " << number("sag_after_settling_mm", 1.0) << " | "
         << run.value("broken_links", 0) << " of " << run.value("links", 0) << " | "
         << number("largest_balance_error_percent", 1.0, 2) << " |\n";
      peaks += std::string(peaks.empty() ? "" : "; ") + s.step->name + " peak " + number("peak_force_N", 1e-3) +
               " kN at " + number("displacement_at_peak_mm", 1.0, 0) + " mm";
    }
  if (table_started) md << "\n";
  // The sets judged at mesh scale: the labelled runs (dem run --label), run or not.
  std::vector<MeshScaleRun> labelled;
  for (const StepFiles& s : by_kind[Kind::Validation]) {
    const std::string label = label_of_command(s.step->command);
    if (label.empty()) continue;
    MeshScaleRun run{label, s.step->name, status_name(s.outcome->status), json()};
    for (const auto& file : s.files)
      if (file.filename() == "summary.json") run.summary = read_json(file);
    if (run.summary.is_object() && run.summary.value("tool", "") == "platter")
      run.not_applicable = punch_applicability(s).value_or("");
    labelled.push_back(run);
  }
  // The dem propagate steps' bands: beside each set's figures here, and as their own section in
  // the summary for the recommended set.
  std::vector<BandEvidence> bands;
  for (const StepFiles& s : by_kind[Kind::Band]) {
    BandEvidence b{s.step->name, label_of_command(s.step->command), status_name(s.outcome->status), json(), {}};
    for (const auto& output : s.step->outputs) {
      const std::filesystem::path file = expand(output, out, campaign_dir);
      if (file.filename() == "summary.json" && std::filesystem::is_regular_file(file)) b.summary = read_json(file);
      if (file.filename() == "sensitivity.csv") b.sensitivity = read_sensitivity_rows(file.string());
    }
    bands.push_back(b);
  }
  md << mesh_scale_table(labelled, bands);
  if (by_kind[Kind::Validation].empty())
    glance.push_back("**Mesh-scale validation**: no DEM mesh step yet ([validation](#mesh-scale-validation)).");
  else
    glance.push_back("**Mesh-scale validation**: " +
                     (peaks.empty() ? std::to_string(by_kind[Kind::Validation].size()) + " step(s)" : peaks) +
                     " ([validation](#mesh-scale-validation)).");
  for (const StepFiles& s : by_kind[Kind::Validation]) {
    md << "From step " << link(s.step->name, s.step->name) << ": " << s.step->description << "\n\n";
    if (s.files.empty()) md << "(no results: " << status_name(s.outcome->status) << ")\n\n";
    for (const auto& file : s.files) figure(md, file, out);
    md << "\n";
  }

  md << "### Gap verdicts\n\n";
  if (by_kind[Kind::Gap].empty()) md << "No gap step in this campaign.\n\n";
  else {
    md << "| case | cause | gap shrink with the cause | main region | gap before (noise floor) | why |\n"
          "|---|---|---|---|---|---|\n";
    for (const StepFiles& s : by_kind[Kind::Gap]) {
      if (s.files.empty()) md << "| " << link(s.step->name, s.step->name) << " | (no result: " << status_name(s.outcome->status) << ") | | | | |\n";
      for (const auto& file : s.files) {
        const json gap = read_json(file);
        if (!gap.is_object()) continue;
        if (gap.contains("cause")) gap_glance.push_back(gap_row(md, s, gap, s.step->name, distrust));
        if (gap.contains("modes") && gap["modes"].is_object())
          for (const auto& [mode, diagnosis] : gap["modes"].items())
            if (diagnosis.is_object() && diagnosis.contains("cause"))
              gap_glance.push_back(gap_row(md, s, diagnosis, s.step->name + " (" + mode + ")", distrust));
      }
    }
    md << "\n";
    for (const StepFiles& s : by_kind[Kind::Gap]) step_figures(md, s, out);
  }

  for (const StepFiles& s : by_kind[Kind::Other])
    if (!s.step->summary.empty()) {
      md << "### " << s.step->name << "\n\n";
      for (const auto& file : s.files) figure(md, file, out);
      md << "\n";
    }

  for (const auto& [step, line] : log_warnings) {
    const auto colon = line.find(": ");
    const std::string text = colon == std::string::npos ? line : line.substr(colon + 2);
    const bool known = std::any_of(distrust.begin(), distrust.end(),
                                   [&](const std::string& d) { return d.find(text) != std::string::npos; });
    if (!known) distrust.push_back("Step " + link(step, step) + ": " + line);
  }
  if (!gap_glance.empty()) {
    std::string line = "**Gap verdicts**: ";
    for (std::size_t i = 0; i < gap_glance.size(); ++i) line += (i ? "; " : "") + gap_glance[i];
    glance.push_back(line + " ([verdicts](#gap-verdicts)).");
  }
  glance.push_back("**What to distrust**: " + std::to_string(distrust.size()) + " item(s) ([list](#what-to-distrust)).");
  md << "### What to distrust\n\n";
  if (distrust.empty()) md << "Nothing flagged: no failed step, no fit warning, no model-form gap, no step warning.\n";
  for (const auto& d : distrust) md << "- " << d << "\n";
  md << "\n";
  const std::vector<SetEvidence> sets = set_evidence(campaign, by_kind[Kind::Validation], out, campaign_dir);
  const Recommendation recommendation = recommend_set(sets);
  std::ostringstream summary;
  summary << "## Summary\n\n" << recommendation_markdown(recommendation, sets);
  if (recommendation.chosen >= 0) {
    // The chosen set's bands (dem propagate steps with its label), beside the runs of the thesis
    // sets with the same model variant.
    json thesis_strip, thesis_punch;
    const std::string counterpart = published_counterpart(sets[recommendation.chosen].label);
    for (const SetEvidence& e : sets)
      if (e.label == counterpart) thesis_strip = e.strip, thesis_punch = e.punch;
    const SetEvidence& chosen = sets[recommendation.chosen];
    summary << band_markdown(chosen.label, bands, thesis_strip, thesis_punch, chosen.strip, chosen.punch);
    for (const StepFiles& s : by_kind[Kind::Band])
      if (label_of_command(s.step->command) == sets[recommendation.chosen].label)
        for (const auto& file : s.figures) figure(summary, file, out);
  }
  if (!sets.empty()) summary << "### At a glance\n\n";
  for (const auto& line : glance) summary << "- " << line << "\n";
  summary << "\n" << md.str();
  return summary.str();
}

}  // namespace dtwire::app
