// The strip tension test of `dtwire dem run` (strip_tension.hpp): clamps, the quasi-static pull,
// the history, the strip figures and their files.
#include "dtwire/dem/strip_tension.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>

#include <nlohmann/json.hpp>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/run.hpp"
#include "run_outputs.hpp"
#include "settle.hpp"

namespace dtwire::dem {
namespace {

// The run stops once the strip has torn through: force below this fraction of its peak after a
// link broke (the rest of the travel would only pull the torn halves apart).
constexpr double kTornFraction = 0.02;

struct Column {
  const char* quantity;
  const char* unit;
};
// curve.csv, in this order (docs/dem_engine.md, "Strip tension").
const std::vector<Column>& strip_columns() {
  static const std::vector<Column> columns = {
      {"time", "s"}, {"elongation", "mm"}, {"strain", "1"}, {"force", "N"}, {"force_per_width", "Npm"},
      {"fixed_bar_force", "N"}, {"reaction_imbalance", "N"}, {"force_instant", "N"}, {"mid_width", "mm"},
      {"kinetic_energy", "J"}, {"link_elastic_energy", "J"}, {"plastic_work", "J"}, {"damage_work", "J"},
      {"damping_work", "J"}, {"gravity_work", "J"}, {"boundary_work", "J"}, {"balance_error", "J"},
      {"broken_links", "1"}, {"largest_link_force", "N"}};
  return columns;
}
enum ColumnIndex { kTime, kElongation, kStrain, kForce, kForcePerWidth, kFixedForce, kImbalance, kInstant, kMidWidth,
                   kKinetic, kElastic, kPlastic, kDamage, kDamping, kGravity, kBoundary, kBalance, kBroken, kLargest };

// Clamps, free length and width from the generated nodes.
struct StripGeometry {
  int axis = 1, across = 0;  // coordinate along the pull, in-plane across it
  Vector3 pull = Vector3::UnitY();
  double fixed_face = 0.0, moving_face = 0.0;  // clamp faces along the pull [m]
  double free_length = 0.0, width = 0.0;
  std::vector<std::size_t> fixed, moving, middle;  // held nodes; nodes of the mid-length band
};

StripGeometry strip_geometry(const RunInput& in, std::vector<NetNode>& nodes) {
  StripGeometry g;
  const bool along = in.strip.direction == PullDirection::AlongTwists;
  g.axis = along ? 1 : 0;
  g.across = along ? 0 : 1;
  g.pull = along ? Vector3(Vector3::UnitY()) : Vector3(Vector3::UnitX());
  double low = std::numeric_limits<double>::max(), high = -low, left = low, right = -low;
  for (const NetNode& node : nodes) {
    low = std::min(low, node.position[g.axis]);
    high = std::max(high, node.position[g.axis]);
    left = std::min(left, node.position[g.across]);
    right = std::max(right, node.position[g.across]);
  }
  const double eps = 1e-9;
  g.fixed_face = low + in.strip.clamp_depth;
  g.moving_face = high - in.strip.clamp_depth;
  g.free_length = g.moving_face - g.fixed_face;
  g.width = right - left;
  if (!(g.free_length > 0.0))
    throw InputError(in.file.string(), "tool.clamp_depth_m: the clamps (" + std::to_string(in.strip.clamp_depth) +
                                           " m each) cover the whole generated strip (" + std::to_string(high - low) +
                                           " m of nodes along the pull)");
  // A band one mesh period long (along the twists) or one opening wide (across) at mid-length.
  const double band = 0.5 * (along ? in.mesh.opening_height + in.mesh.twist_length : in.mesh.opening_width);
  const double middle = 0.5 * (low + high);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double c = nodes[i].position[g.axis];
    if (c <= g.fixed_face + eps) {
      nodes[i].fixity = NodeFixity::Pinned;
      g.fixed.push_back(i);
    } else if (c >= g.moving_face - eps) {
      nodes[i].fixity = NodeFixity::Guided;  // at rest while settling
      g.moving.push_back(i);
    } else if (std::abs(c - middle) <= band) {
      g.middle.push_back(i);
    }
  }
  return g;  // each clamp holds at least the outermost node: free_length > 0 put the faces inside
}

// The force of the held nodes' clamp on the net along the pull: minus the links' (and gravity's)
// pull on those nodes.
double clamp_force(const Engine& engine, const std::vector<std::size_t>& held, const Vector3& pull) {
  double sum = 0.0;
  for (std::size_t i : held) sum -= engine.unbalanced_force(i).dot(pull);
  return sum;
}

double extent_across(const Engine& engine, const std::vector<std::size_t>& nodes, int across) {
  if (nodes.empty()) return 0.0;
  double low = std::numeric_limits<double>::max(), high = -low;
  for (std::size_t i : nodes) {
    low = std::min(low, engine.position(i)[across]);
    high = std::max(high, engine.position(i)[across]);
  }
  return high - low;
}

// Strain where the force first reaches `level` (before the peak index), interpolated.
bool first_crossing(const std::vector<double>& strain, const std::vector<double>& force, std::size_t peak, double level,
                    double& at) {
  for (std::size_t r = 0; r <= peak; ++r) {
    if (force[r] < level) continue;
    if (r == 0) {
      at = strain[0];
      return true;
    }
    const double f0 = force[r - 1], f1 = force[r];
    const double s = f1 > f0 ? (level - f0) / (f1 - f0) : 1.0;
    at = strain[r - 1] + s * (strain[r] - strain[r - 1]);
    return true;
  }
  return false;
}

}  // namespace

ChordStiffness chord_stiffness(const std::vector<double>& strain, const std::vector<double>& force_per_width, double low,
                               double high) {
  ChordStiffness chord;
  if (strain.size() != force_per_width.size() || strain.size() < 2 || !(low < high)) return chord;
  const std::size_t peak =
      static_cast<std::size_t>(std::max_element(force_per_width.begin(), force_per_width.end()) - force_per_width.begin());
  const double top = force_per_width[peak];
  if (!(top > 0.0)) return chord;
  if (!first_crossing(strain, force_per_width, peak, low * top, chord.strain_low) ||
      !first_crossing(strain, force_per_width, peak, high * top, chord.strain_high))
    return chord;
  if (!(chord.strain_high > chord.strain_low)) return chord;
  chord.value = (high - low) * top / (chord.strain_high - chord.strain_low);
  chord.defined = true;
  return chord;
}

RunSummary run_strip_tension(const RunInput& in, const RunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  BuiltNet built = build_net(in);
  const StripGeometry g = strip_geometry(in, built.mesh.net.nodes);
  EngineOptions engine_options = in.engine;
  if (options.threads > 0) engine_options.threads = options.threads;
  if (options.parallel_threshold >= 0) engine_options.parallel_threshold = static_cast<std::size_t>(options.parallel_threshold);
  std::unique_ptr<Engine> engine;
  try {
    engine = std::make_unique<Engine>(built.mesh.net.nodes, std::move(built.links), engine_options);
  } catch (const std::invalid_argument& e) {
    throw InputError(in.file.string(), std::string(in.engine.time_step > 0.0 ? "dynamics.time_step_s: " : "") + e.what());
  }
  RunRecorder frames(in, built.mesh, options);  // clears the folder's old results; writes the frames

  RunSummary summary;
  summary.nodes = engine->node_count();
  summary.links = engine->link_count();
  summary.time_step = engine->time_step();
  summary.settle_time_step = summary.time_step;  // no tool to park: one step throughout
  summary.critical_time_step = engine->critical_time_step();
  StripFigures& strip = summary.strip;
  strip.width = g.width;
  strip.free_length = g.free_length;
  strip.fixed_nodes = g.fixed.size();
  strip.moving_nodes = g.moving.size();

  // Settling (gravity, if any) with both clamps at rest, then the moving clamp starts.
  WaitingWall no_wall;
  record_settle(settle(*engine, in, no_wall), summary);
  const std::size_t marker = g.moving.front();
  const double start = engine->position(marker).dot(g.pull);
  for (std::size_t i : g.moving) engine->set_guided_velocity(i, in.speed * g.pull);

  std::vector<std::vector<double>> columns(strip_columns().size());
  const double t0 = engine->time();
  const double expected = in.travel / in.speed;
  const double frame_interval = in.frames > 0 ? expected / in.frames : 0.0;
  double next_output = t0, next_frame = t0, moving_sum = 0.0, fixed_sum = 0.0, elongation_sum = 0.0, peak = 0.0;
  long steps_in_interval = 0;
  RunGuard guard(in.checks, true);  // the strip is pulled quasi-statically
  auto last_progress = std::chrono::steady_clock::now();
  for (;;) {
    const double elongation = engine->position(marker).dot(g.pull) - start;
    const bool travelled = elongation >= in.travel * (1.0 - 1e-12);
    const double elapsed = engine->time() - t0;
    const bool output_due = engine->time() >= next_output;
    bool done = travelled;
    if (output_due || travelled) {
      // Interval means: the instantaneous clamp force carries the nodes' vibration; the
      // elongation is averaged with it (the end of the interval would lead the mean force by
      // half an interval).
      const double mean_elongation = steps_in_interval > 0 ? elongation_sum / steps_in_interval : elongation;
      const double moving = steps_in_interval > 0 ? moving_sum / steps_in_interval : clamp_force(*engine, g.moving, g.pull);
      const double fixed = steps_in_interval > 0 ? fixed_sum / steps_in_interval : clamp_force(*engine, g.fixed, g.pull);
      const EnergySplit& e = engine->energy();
      // A non-finite state stays non-finite: checked once per output interval, and not recorded.
      summary.failed = guard.check(e, elapsed, engine->steps_taken(), moving);
      if (summary.failed && summary.failed->check == "finite_state") break;
      double largest = 0.0;
      for (std::size_t l = 0; l < engine->link_count(); ++l)
        if (!engine->link(l).law->broken()) largest = std::max(largest, std::abs(engine->link(l).law->forces()[0]));
      const std::vector<double> row = {
          elapsed, 1000.0 * mean_elongation, mean_elongation / g.free_length, moving, moving / g.width, fixed, moving + fixed,
          clamp_force(*engine, g.moving, g.pull), 1000.0 * extent_across(*engine, g.middle, g.across), e.kinetic,
          e.link_elastic, e.link_plastic, e.link_damage, e.damping, e.gravity_work, e.boundary_work, e.balance_error(),
          static_cast<double>(engine->broken_links()), largest};
      for (std::size_t c = 0; c < row.size(); ++c) columns[c].push_back(row[c]);
      moving_sum = fixed_sum = elongation_sum = 0.0;
      steps_in_interval = 0;
      if (output_due) next_output += in.output_interval;
      peak = std::max(peak, moving);
      if (engine->broken_links() > 0 && moving < kTornFraction * peak) {
        strip.torn = true;
        done = true;
      }
      if (summary.failed) break;
    }
    if (options.write_frames && frame_interval > 0.0 && (engine->time() >= next_frame || done)) {
      frames.frame(*engine, elapsed);
      next_frame += frame_interval;
    }
    if (done) break;
    elongation_sum += elongation;  // the positions whose link forces this step computes
    engine->step();
    moving_sum += clamp_force(*engine, g.moving, g.pull);
    fixed_sum += clamp_force(*engine, g.fixed, g.pull);
    ++steps_in_interval;
    const auto now = std::chrono::steady_clock::now();
    if (!options.quiet && now - last_progress > std::chrono::seconds(2)) {
      last_progress = now;
      std::cerr << "\r[dem run] strip " << 1000.0 * elongation << " of " << 1000.0 * in.travel << " mm, "
                << clamp_force(*engine, g.moving, g.pull) / g.width / 1000.0 << " kN/m, broken " << engine->broken_links()
                << ", " << static_cast<int>(100.0 * std::min(1.0, elapsed / expected)) << " %   " << std::flush;
    }
  }
  if (!options.quiet) std::cerr << "\n";
  summary.steps = engine->steps_taken();
  summary.broken_links = engine->broken_links();

  // Figures (none when the first row was already non-finite).
  const auto& force = columns[kForce];
  if (!force.empty()) {
    const std::size_t at_peak = static_cast<std::size_t>(std::max_element(force.begin(), force.end()) - force.begin());
    summary.peak_force = force[at_peak];
    summary.displacement_at_peak = columns[kElongation][at_peak] / 1000.0;
    strip.strength_per_width = summary.peak_force / g.width;
    strip.strain_at_peak = columns[kStrain][at_peak];
    strip.secant = chord_stiffness(columns[kStrain], columns[kForcePerWidth], 0.1, 0.5);
    if (strip.secant.defined) strip.origin_secant = 0.5 * strip.strength_per_width / strip.secant.strain_high;
    for (std::size_t r = 1; r < force.size(); ++r)
      if (columns[kBroken][r] > 0.0) {
        strip.force_at_first_break = force[r - 1];
        break;
      }
    strip.end_force = force.back();
    strip.end_reaction_imbalance = columns[kImbalance].back();
  }
  // Largest balance error against the work on the mesh, rows past 5 % of the final work.
  const auto work = [&](std::size_t r) { return std::abs(columns[kGravity][r]) + std::abs(columns[kBoundary][r]); };
  const double final_work = force.empty() ? 0.0 : work(force.size() - 1);
  for (std::size_t r = 0; r < force.size(); ++r)
    if (work(r) > 0.05 * final_work && work(r) > 0.0)
      summary.largest_balance_error = std::max(summary.largest_balance_error, std::abs(columns[kBalance][r]) / work(r));
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  // Files.
  std::vector<std::filesystem::path> inputs{in.file};
  for (const auto& [tag, set] : in.link_sets)
    for (const auto& file : set.files)
      if (std::find(inputs.begin(), inputs.end(), file) == inputs.end()) inputs.push_back(file);
  const Provenance provenance = make_provenance(options.command_line, inputs);
  const std::string direction = in.strip.direction == PullDirection::AlongTwists ? "along_twists" : "across_twists";
  Curve history;
  for (std::size_t c = 0; c < columns.size(); ++c)
    history.add_channel(strip_columns()[c].quantity, *find_unit(strip_columns()[c].unit), columns[c]);
  history.set_metadata("source", "dtwire dem run " + in.file.filename().string());
  history.set_metadata("title", in.title);
  const std::string label = options.label.empty() ? in.title : options.label;
  history.set_metadata("label", label);
  history.set_metadata("tool", in.tool);
  history.set_metadata("direction", direction);
  history.set_metadata("strip_width_m", format_number(g.width));
  history.set_metadata("free_length_m", format_number(g.free_length));
  history.set_metadata("time_step_s", format_number(summary.time_step));
  history.set_metadata("run_id", provenance.run_id);
  history.set_metadata("status", run_status(summary));
  summary.history = history;
  write_csv(history, options.out / "curve.csv");
  frames.write_frame_index();

  Results results;
  results.curves = {{"history", history}};
  add_engine_parameters(results, in, summary);
  auto parameter = [&](const std::string& name, double value, const std::string& unit) {
    results.parameters.push_back({name, value, unit, std::nullopt});
  };
  parameter("strip_width_m", g.width, "m");
  parameter("free_length_m", g.free_length, "m");
  parameter("clamp_depth_m", in.strip.clamp_depth, "m");
  parameter("peak_force_N", summary.peak_force, "N");
  parameter("strength_per_width_N_per_m", strip.strength_per_width, "N/m");
  parameter("displacement_at_peak_m", summary.displacement_at_peak, "m");
  parameter("strain_at_peak_1", strip.strain_at_peak, "1");
  if (strip.secant.defined) {
    parameter("secant_EA_10_50_N_per_m", strip.secant.value, "N/m");
    parameter("secant_strain_at_10pct_1", strip.secant.strain_low, "1");
    parameter("secant_strain_at_50pct_1", strip.secant.strain_high, "1");
    parameter("origin_secant_EA_50_N_per_m", strip.origin_secant, "N/m");
  }
  parameter("force_at_first_break_N", strip.force_at_first_break, "N");
  parameter("end_reaction_imbalance_N", strip.end_reaction_imbalance, "N");
  parameter("largest_balance_error_1", summary.largest_balance_error, "1");
  parameter("broken_links", static_cast<double>(summary.broken_links), "1");
  results.fields.emplace_back("frames", options.write_frames ? "net.pvd (frames/net_<k>.vtu)" : "none");
  results.fields.emplace_back("title", in.title);
  results.fields.emplace_back("direction", direction);
  results.fields.emplace_back("secant", "chord of force per width against strain between 10 % and 50 % of the peak");
  results.fields.emplace_back("status", run_status(summary));
  results.provenance = provenance;
  write_results(results, options.out / "results.h5");

  // The campaign report reads peak_force_N, displacement_at_peak_mm, broken_links, links and
  // largest_balance_error_percent from every DEM run's summary.
  nlohmann::json headline = {
      {"title", in.title},
      {"label", label},
      {"tool", in.tool},
      {"direction", direction},
      {"strip_width_m", g.width},
      {"free_length_m", g.free_length},
      {"peak_force_N", summary.peak_force},
      {"strength_per_width_kN_per_m", strip.strength_per_width / 1000.0},
      {"displacement_at_peak_mm", 1000.0 * summary.displacement_at_peak},
      {"strain_at_peak_percent", 100.0 * strip.strain_at_peak},
      {"secant_EA_10_50_kN_per_m", nullptr},
      {"origin_secant_EA_50_kN_per_m", nullptr},
      {"force_at_first_break_N", strip.force_at_first_break},
      {"torn", strip.torn},
      {"end_reaction_imbalance_N", strip.end_reaction_imbalance},
      {"broken_links", summary.broken_links},
      {"links", summary.links},
      {"largest_balance_error_percent", 100.0 * summary.largest_balance_error},
      {"time_step_s", summary.time_step},
      {"steps", summary.steps},
      {"wall_seconds", summary.wall_seconds},
      {"command", options.command_line},
      {"run_id", provenance.run_id}};
  if (strip.secant.defined) {
    headline["secant_EA_10_50_kN_per_m"] = strip.secant.value / 1000.0;
    headline["origin_secant_EA_50_kN_per_m"] = strip.origin_secant / 1000.0;
  }
  add_status(headline, summary);
  write_file_atomically(options.out / "summary.json", [&](std::ostream& os) { os << headline.dump(2) << "\n"; });
  return summary;
}

}  // namespace dtwire::dem
