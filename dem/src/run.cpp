// `dtwire dem run`: builds the net and the tool from the input, runs the phases (settle under
// gravity, then the punch, the cyclic punch or the impact), records the history.
#include "dtwire/dem/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>

#include "dtwire/core/error.hpp"
#include "dtwire/dem/length_rescaling.hpp"
#include "dtwire/dem/wirepm.hpp"
#include "run_outputs.hpp"
#include "settle.hpp"
#include "supports.hpp"

namespace dtwire::dem {
namespace {

Vector3 panel_centre(const HexMesh& mesh) {
  Vector3 low = Vector3::Constant(1e300), high = Vector3::Constant(-1e300);
  for (const NetNode& node : mesh.net.nodes) {
    low = low.cwiseMin(node.position);
    high = high.cwiseMax(node.position);
  }
  return 0.5 * (low + high);
}

// The tool placed so that its surface is `gap` below (platter) or above (boulder) the nodes.
std::unique_ptr<Tool> make_tool(const RunInput& in, const Vector3& centre, double lowest_z, double highest_z) {
  const double r = in.mesh.node_radius;
  std::unique_ptr<Tool> tool;
  if (in.tool == "platter") {
    tool = std::make_unique<SemiSpheroidPlatter>(in.platter_base_radius, in.platter_height);
    tool->position = Vector3(centre.x(), centre.y(), lowest_z - r - in.start_gap - in.platter_height);
  } else {
    tool = std::make_unique<TruncatedCube>(in.boulder_side, in.boulder_corner_plane);
    tool->position = Vector3(centre.x(), centre.y(), highest_z + r + in.start_gap + 0.5 * in.boulder_side);
    tool->mass = in.boulder_mass;
    tool->rotational_inertia = in.boulder_mass * in.boulder_side * in.boulder_side / 6.0;  // cube, isotropic
    tool->velocity = Vector3(0.0, 0.0, -in.speed);
  }
  tool->contact = in.contact;
  return tool;
}

void check_tool_clear(const RunInput& in, const Tool& tool, const Engine& engine) {
  std::size_t inside = 0;
  for (std::size_t i = 0; i < engine.node_count(); ++i) {
    SurfacePoint surface;
    if (tool.nearest(engine.position(i), engine.node(i).radius, surface) && surface.distance < engine.node(i).radius) ++inside;
  }
  if (inside > 0)
    throw InputError(in.file.string(), "tool: the " + tool.kind() + " overlaps " + std::to_string(inside) +
                                           " mesh nodes at the start; expected it clear of the mesh (tool.gap_m)");
}

}  // namespace

BuiltNet build_net(const RunInput& in) {
  BuiltNet built;
  try {
    built.mesh = generate_hex_mesh(in.mesh);
  } catch (const std::invalid_argument& e) {
    throw InputError(in.file.string(), std::string("mesh.") + e.what());
  }
  apply_supports(built.mesh, in, in.wall_below > 0.0);
  for (std::size_t l = 0; l < built.mesh.net.links.size(); ++l) {
    const NetLink& link = built.mesh.net.links[l];
    const std::string tag = link_tag_name(link.tag);
    const auto set = in.link_sets.find(link.tag);
    if (set == in.link_sets.end()) throw InputError(in.file.string(), "links." + tag + ": missing: no law set for the " + tag + " links");
    ParameterMap parameters = set->second.parameters;
    const double link_length = (built.mesh.net.nodes[link.b].position - built.mesh.net.nodes[link.a].position).norm();
    // A part of a split wire takes the whole wire's set (as the two-node mesh would give it),
    // then the share that makes the parts in series reproduce it (length_rescaling.hpp).
    const double wire_length = link.parts * link_length;
    const std::size_t wire = link.wire >= 0 ? static_cast<std::size_t>(link.wire) : l;
    if (set->second.length == "link") parameters = rescale_to_link_length(parameters, wire_length);
    if (set->second.law == "wirepm") {
      // As YADE: the reference length is the link's own length; each link its own seed.
      parameters["reference_length_m"] = wire_length;
      if (!parameters.count("seed")) parameters["seed"] = static_cast<double>(wire + 1);
    }
    // Thoeni et al. 2013: slack lambda_u l0 r of link l; WirePM as YADE's type 2 (seed -1: its
    // lambda_u is this link's lambda_u r), the other laws shifted by DistortedLaw. The parts of
    // a split wire share the wire's draw, so each takes its share of the wire's slack.
    const Distortion& distortion = set->second.distortion;
    const double variate = distortion_variate(distortion, wire);
    const bool distorted = distortion.mode != DistortionMode::None && distortion.lambda_u > 0.0;
    if (distorted && set->second.law == "wirepm") {
      parameters["lambda_u"] = distortion.lambda_u * variate;
      parameters["seed"] = -1.0;
    }
    try {
      if (link.parts > 1) parameters = split_in_series(set->second.law, parameters, link.parts);
      std::unique_ptr<ContactLaw> law = make_contact_law(set->second.law, parameters);
      if (distorted && set->second.law != "wirepm")
        law = std::make_unique<DistortedLaw>(std::move(law), distortion.lambda_u * link_length * variate);
      built.links.push_back({link, std::move(law)});
    } catch (const std::invalid_argument& e) {
      throw InputError(in.file.string(), "links." + tag + ": " + e.what());
    }
  }
  return built;
}

std::vector<Vector3> pretensioned_positions(const RunInput& in, const HexMesh& mesh) {
  const Vector3 centre = panel_centre(mesh);
  std::vector<Vector3> positions;
  for (const NetNode& node : mesh.net.nodes) {
    Vector3 p = node.position;
    p.head<2>() = centre.head<2>() + (1.0 + in.pretension_strain) * (p - centre).head<2>();
    positions.push_back(p);
  }
  return positions;
}

namespace {

// The lowest node after settling under gravity with the input's pre-tension [m below z = 0].
double settled_sag(const RunInput& in, const RunOptions& options) {
  BuiltNet built = build_net(in);
  EngineOptions engine_options = in.engine;
  if (options.threads > 0) engine_options.threads = options.threads;
  const HexMesh mesh = built.mesh;
  Engine engine(built.mesh.net.nodes, std::move(built.links), engine_options);
  if (in.pretension_strain > 0.0) engine.impose_positions(pretensioned_positions(in, mesh));
  WaitingWall no_wall;  // the pre-load and the slack state's wall exclude each other
  settle(engine, in, no_wall);
  double lowest = 0.0;
  for (std::size_t i = 0; i < engine.node_count(); ++i) lowest = std::min(lowest, engine.position(i).z());
  return -lowest;
}

// Thesis pre-load (Previtali ch. 3.4): the edges pulled apart until the centre sags `presag`.
// The settled sag falls with the stretch roughly as 1/sag grows linearly with it (a membrane's
// tension), so a secant on 1/sag finds it in a few settles; each try is logged.
RunInput with_preload(const RunInput& input, const RunOptions& options) {
  RunInput in = input;
  if (!(input.presag > 0.0)) return in;
  const double target = input.presag, tolerance = 0.02 * target;
  auto log = [&](double strain, double sag) {
    if (!options.quiet)
      std::cerr << "[dem run] pre-load: stretch " << strain << " -> sag " << 1000.0 * sag << " mm (target "
                << 1000.0 * target << " mm)\n";
  };
  double e0 = 0.0;
  in.pretension_strain = e0;
  double s0 = settled_sag(in, options);
  log(e0, s0);
  if (s0 <= target + tolerance) return in;  // already as taut as asked without any stretch
  double e1 = 2e-4;
  in.pretension_strain = e1;
  double s1 = settled_sag(in, options);
  log(e1, s1);
  for (int attempt = 0; attempt < 6 && std::abs(s1 - target) > tolerance; ++attempt) {
    const double slope = (1.0 / s1 - 1.0 / s0) / (e1 - e0);
    double next = slope > 0.0 ? e1 + (1.0 / target - 1.0 / s1) / slope : 2.0 * e1;
    next = std::clamp(next, 0.0, 0.05);
    e0 = e1, s0 = s1, e1 = next;
    in.pretension_strain = e1;
    s1 = settled_sag(in, options);
    log(e1, s1);
  }
  if (std::abs(s1 - target) > tolerance)
    throw ComputationError("dem run: the pre-load found no stretch that sags the net " + std::to_string(1000.0 * target) +
                           " mm (last: stretch " + std::to_string(e1) + ", sag " + std::to_string(1000.0 * s1) + " mm)");
  return in;
}

}  // namespace

RunSummary run_simulation(const RunInput& input, const RunOptions& options) {
  if (input.tool == "strip_tension") return run_strip_tension(input, options);
  const auto wall_start = std::chrono::steady_clock::now();
  const RunInput in = with_preload(input, options);
  BuiltNet built = build_net(in);
  EngineOptions engine_options = in.engine;
  if (options.threads > 0) engine_options.threads = options.threads;
  if (options.parallel_threshold >= 0) engine_options.parallel_threshold = static_cast<std::size_t>(options.parallel_threshold);
  const std::size_t node_count = built.mesh.net.nodes.size();
  const HexMesh mesh_copy = [&] { HexMesh m = built.mesh; return m; }();
  std::unique_ptr<Engine> engine;
  const Vector3 centre = panel_centre(built.mesh);
  WaitingWall wall;
  try {
    engine = std::make_unique<Engine>(built.mesh.net.nodes, std::move(built.links), engine_options);
    if (in.tool != "none") {
      // Parked far from the net while it settles (out of the settling's stability bound); placed
      // after settling.
      std::unique_ptr<Tool> tool = make_tool(in, centre, 0.0, 0.0);
      tool->position.z() += in.tool == "platter" ? -10.0 : 10.0;
      tool->velocity.setZero();
      engine->add_tool(std::move(tool), /*parked=*/true);
    }
    if (in.wall_below > 0.0) {
      // The slack state's wall (tool 1): its surface wall_below under the nodes' lowest surface,
      // parked until the net comes near it (settle.hpp).
      const double surface_z = -in.mesh.node_radius - in.wall_below;
      auto plane = std::make_unique<PlaneWall>(Vector3::UnitZ());
      plane->position = Vector3(centre.x(), centre.y(), surface_z - 10.0);
      plane->contact = in.contact;
      wall = WaitingWall(engine->add_tool(std::move(plane), /*parked=*/true), surface_z);
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(in.file.string(), std::string(in.engine.time_step > 0.0 ? "dynamics.time_step_s: " : "") + e.what());
  }
  if (in.pretension_strain > 0.0) engine->impose_positions(pretensioned_positions(in, mesh_copy));

  RunRecorder recorder(in, mesh_copy, options);
  RunSummary summary;
  summary.nodes = node_count;
  summary.links = engine->link_count();
  summary.settle_time_step = engine->time_step();

  // Phase 1: settle under gravity (and the pre-tension), to rest if the input asks.
  record_settle(settle(*engine, in, wall), summary);
  double lowest = std::numeric_limits<double>::max(), highest = -lowest;
  for (std::size_t i = 0; i < node_count; ++i) {
    lowest = std::min(lowest, engine->position(i).z());
    highest = std::max(highest, engine->position(i).z());
  }
  summary.sag = -lowest;
  summary.pretension_strain = in.pretension_strain;
  summary.kinetic_after_settling = engine->energy().kinetic;
  wall.enter(*engine);
  if (in.wall_below > 0.0) hold_supports_in_place(*engine, mesh_copy, in);

  // Phase 2: the tool.
  Vector3 start = Vector3::Zero(), direction = Vector3::UnitZ();
  if (in.tool != "none") {
    std::unique_ptr<Tool> placed = make_tool(in, centre, lowest, highest);
    engine->place_tool(0, placed->position, in.tool == "platter" ? Vector3(0.0, 0.0, in.speed) : placed->velocity);
    check_tool_clear(in, engine->tool(0), *engine);  // placed: the step now has its contact
    start = engine->tool(0).position;
    direction = in.tool == "platter" ? Vector3(Vector3::UnitZ()) : Vector3(-Vector3::UnitZ());
  }
  summary.time_step = engine->time_step();
  summary.critical_time_step = engine->critical_time_step();
  const double t0 = engine->time();
  const double expected = in.tool == "boulder" || in.tool == "none" ? in.duration : in.travel / in.speed;
  std::size_t level = 0;
  bool unloading = false;
  // The cyclic punch reverses on the force averaged over about one output interval
  // (exponential moving average): the instantaneous node-platter force chatters far above its mean.
  double smoothed_force = 0.0;
  double next_output = t0, next_frame = t0;
  double recorded_peak = 0.0;  // the largest recorded (interval-mean) force, as the summary's peak
  Vector3 impulse = Vector3::Zero();  // sum over the steps of the interval of the tool's force on the net
  long steps_in_interval = 0;
  const double frame_interval = in.frames > 0 ? expected / in.frames : 0.0;
  // Quasi-static: the platter punches; an impact or a free net is dynamic by design.
  RunGuard guard(in.checks, in.tool == "platter");
  auto last_progress = std::chrono::steady_clock::now();
  for (;;) {
    double displacement = 0.0, force = 0.0;
    Vector3 tool_velocity = Vector3::Zero();
    if (in.tool != "none") {
      displacement = (engine->tool(0).position - start).dot(direction);
      force = engine->tool_force(0).norm();
      tool_velocity = engine->tool(0).velocity;
    }
    const double elapsed = engine->time() - t0;
    const bool done = in.tool == "platter" ? (displacement >= in.travel || (!in.force_levels.empty() && level >= in.force_levels.size()))
                                            : elapsed >= in.duration;
    if (engine->time() >= next_output || done) {
      // A non-finite state stays non-finite: checked once per output interval, and not recorded.
      summary.failed = guard.check(engine->energy(), elapsed, engine->steps_taken(), force);
      if (summary.failed && summary.failed->check == "finite_state") break;
      // The mean over the interval: node-platter impacts make the instantaneous force chatter.
      const Vector3 mean = steps_in_interval > 0 ? Vector3(impulse / steps_in_interval) : (in.tool == "none" ? Vector3(Vector3::Zero()) : Vector3(-engine->tool_force(0)));
      recorder.record(*engine, elapsed, displacement, tool_velocity.dot(direction), mean);
      impulse.setZero();
      steps_in_interval = 0;
      next_output += in.output_interval;
      if (summary.failed) break;
      // The net has failed: links broke and the recorded force fell below the stated fraction
      // of its peak; the rest of the travel would only push the platter through the hole.
      recorded_peak = std::max(recorded_peak, mean.norm());
      if (in.stop_below_peak_fraction > 0.0 && engine->broken_links() > 0 &&
          mean.norm() < in.stop_below_peak_fraction * recorded_peak)
        summary.stopped_at_failure = true;
    }
    if (options.write_frames && frame_interval > 0.0 && (engine->time() >= next_frame || done || summary.stopped_at_failure)) {
      recorder.frame(*engine, elapsed);
      next_frame += frame_interval;
    }
    if (done || summary.stopped_at_failure) break;
    // Cyclic punch: reverse at each force level, reload near zero force.
    if (in.tool == "platter" && !in.force_levels.empty()) {
      smoothed_force += std::min(1.0, engine->time_step() / in.output_interval) * (force - smoothed_force);
      if (!unloading && smoothed_force >= in.force_levels[level]) unloading = true;
      else if (unloading && smoothed_force <= in.unload_force) {
        unloading = false;
        ++level;
      }
      engine->tool(0).velocity = Vector3(0.0, 0.0, unloading ? -in.speed : in.speed);
    }
    engine->step();
    if (in.tool != "none") {
      impulse -= engine->tool_force(0);
      ++steps_in_interval;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!options.quiet && now - last_progress > std::chrono::seconds(2)) {
      last_progress = now;
      std::cerr << "\r[dem run] t " << elapsed << " s of " << expected << ", tool " << 1000.0 * displacement << " mm, "
                << force / 1000.0 << " kN, broken " << engine->broken_links() << ", "
                << static_cast<int>(100.0 * std::min(1.0, elapsed / expected)) << " %   " << std::flush;
    }
  }
  if (!options.quiet) std::cerr << "\n";
  summary.steps = engine->steps_taken();
  summary.wall_entered_at = wall.entered_at();
  summary.broken_links = engine->broken_links();
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  recorder.finish(*engine, summary);
  return summary;
}

}  // namespace dtwire::dem
