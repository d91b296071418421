// The files of a `dtwire dem run` (see run_outputs.hpp).
#include "run_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>

#include <nlohmann/json.hpp>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/punch_figures.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

const std::vector<std::pair<std::string, std::string>>& history_columns() {
  static const std::vector<std::pair<std::string, std::string>> columns = {
      {"time", "s"}, {"tool_displacement", "mm"}, {"tool_velocity", "mps"}, {"tool_force", "N"},
      {"tool_force_z", "N"}, {"tool_force_instant", "N"}, {"tool_contacts", "1"}, {"kinetic_energy", "J"}, {"link_elastic_energy", "J"},
      {"contact_elastic_energy", "J"}, {"plastic_work", "J"}, {"damage_work", "J"}, {"friction_work", "J"},
      {"damping_work", "J"}, {"gravity_work", "J"}, {"tool_work", "J"}, {"boundary_work", "J"},
      {"balance_error", "J"}, {"broken_links", "1"}, {"largest_link_force", "N"}};
  return columns;
}

Curve histogram(const std::string& quantity, const std::string& unit, double width, const std::vector<double>& at_peak,
                const std::vector<double>& at_end) {
  double top = width;
  for (double v : at_peak) top = std::max(top, v);
  for (double v : at_end) top = std::max(top, v);
  const std::size_t bins = static_cast<std::size_t>(std::ceil(top / width)) + 1;
  std::vector<double> low(bins), high(bins), peak(bins, 0.0), end(bins, 0.0);
  for (std::size_t b = 0; b < bins; ++b) {
    low[b] = b * width;
    high[b] = (b + 1) * width;
  }
  for (double v : at_peak) peak[std::min(bins - 1, static_cast<std::size_t>(v / width))] += 1.0;
  for (double v : at_end) end[std::min(bins - 1, static_cast<std::size_t>(v / width))] += 1.0;
  Curve curve;
  curve.add_channel(quantity + "_low", *find_unit(unit), low);
  curve.add_channel(quantity + "_high", *find_unit(unit), high);
  curve.add_channel("count_at_peak", *find_unit("1"), peak);
  curve.add_channel("count_at_end", *find_unit("1"), end);
  return curve;
}

// The platter's radial sections at the peak (membrane_sections.hpp), one row per radius.
Curve membrane_curve(const std::vector<MembraneSection>& sections) {
  std::vector<double> radius, links, vertical, radial, tension, largest, largest_at, smallest, slope;
  for (const MembraneSection& s : sections) {
    radius.push_back(s.radius);
    links.push_back(static_cast<double>(s.crossing_links));
    vertical.push_back(s.vertical_force);
    radial.push_back(s.radial_force);
    tension.push_back(s.radial_tension);
    largest.push_back(s.largest_sector_tension);
    largest_at.push_back(s.largest_sector_angle * 180.0 / kPi);
    smallest.push_back(s.smallest_sector_tension);
    slope.push_back(s.slope * 180.0 / kPi);
  }
  Curve curve;
  curve.add_channel("radius", *find_unit("m"), radius);
  curve.add_channel("crossing_links", *find_unit("1"), links);
  curve.add_channel("vertical_force", *find_unit("N"), vertical);
  curve.add_channel("radial_force", *find_unit("N"), radial);
  curve.add_channel("radial_tension", *find_unit("Npm"), tension);
  curve.add_channel("largest_sector_tension", *find_unit("Npm"), largest);
  curve.add_channel("largest_sector_direction", *find_unit("deg"), largest_at);
  curve.add_channel("smallest_sector_tension", *find_unit("Npm"), smallest);
  curve.add_channel("slope", *find_unit("deg"), slope);
  return curve;
}

}  // namespace

RunRecorder::RunRecorder(const RunInput& input, const HexMesh& mesh, const RunOptions& options)
    : input_(input), mesh_(mesh), options_(options), columns_(history_columns().size()), links_(mesh) {
  // Every SW link leaving a DT end, paired with that twist.
  std::vector<int> twist_at(mesh.net.nodes.size(), -1);
  for (std::size_t l = 0; l < mesh.net.links.size(); ++l)
    if (mesh.net.links[l].tag == LinkTag::DoubleTwist) {
      twist_at[mesh.net.links[l].a] = static_cast<int>(l);
      twist_at[mesh.net.links[l].b] = static_cast<int>(l);
    }
  for (std::size_t l = 0; l < mesh.net.links.size(); ++l) {
    const NetLink& link = mesh.net.links[l];
    if (link.tag != LinkTag::SingleWire) continue;
    for (int node : {link.a, link.b})
      if (twist_at[node] >= 0) angle_pairs_.push_back({twist_at[node], static_cast<int>(l), node});
  }
  if (input_.tool == "platter") {
    double half_extent = 1e300;
    for (int axis : {0, 1}) {
      double low = 1e300, high = -1e300;
      for (const NetNode& node : mesh.net.nodes) {
        low = std::min(low, node.position[axis]);
        high = std::max(high, node.position[axis]);
      }
      half_extent = std::min(half_extent, 0.5 * (high - low));
    }
    for (int k = 0; input_.platter_base_radius + 0.05 + 0.1 * k < half_extent - 0.1 + 1e-9; ++k)
      section_radii_.push_back(input_.platter_base_radius + 0.05 + 0.1 * k);
  }
  std::filesystem::create_directories(options_.out);
  // An earlier run's results in this folder would sit beside this run's: remove them.
  for (const char* stale : {"curve.csv", "link_force_histogram.csv", "pulling_angle_histogram.csv",
                            "membrane_at_peak.csv", "net.pvd", "results.h5", "summary.json"})
    std::filesystem::remove(options_.out / stale);
  for (const std::string& stale : LinkRecorder::file_names()) std::filesystem::remove(options_.out / stale);
  std::filesystem::remove_all(options_.out / "frames");
  if (options_.write_frames) std::filesystem::create_directories(options_.out / "frames");
}

RunRecorder::Snapshot RunRecorder::snapshot(const Engine& engine) const {
  Snapshot s;
  for (std::size_t l = 0; l < engine.link_count(); ++l)
    if (!engine.link(l).law->broken()) s.link_forces.push_back(std::abs(engine.link(l).law->forces()[0]));
  for (const AnglePair& pair : angle_pairs_) {
    if (engine.link(pair.twist).law->broken() || engine.link(pair.wire).law->broken()) continue;
    const NetLink& twist = engine.link(pair.twist).link;
    const NetLink& wire = engine.link(pair.wire).link;
    // Twist axis pointing out of the twist at the shared node; the wire leaving that node.
    const Vector3 axis = (twist.b == pair.node ? 1.0 : -1.0) * engine.link_direction(pair.twist);
    const Vector3 along = (wire.a == pair.node ? 1.0 : -1.0) * engine.link_direction(pair.wire);
    s.pulling_angles.push_back(std::acos(std::clamp(axis.dot(along), -1.0, 1.0)) * 180.0 / kPi);
  }
  if (!section_radii_.empty() && engine.tool_count()) {
    std::vector<Vector3> positions(engine.node_count());
    for (std::size_t i = 0; i < positions.size(); ++i) positions[i] = engine.position(i);
    std::vector<SectionLink> links(engine.link_count());
    for (std::size_t l = 0; l < links.size(); ++l)
      links[l] = {static_cast<std::size_t>(engine.link(l).link.a), static_cast<std::size_t>(engine.link(l).link.b),
                  engine.link_force_on_a(l)};
    s.sections = membrane_sections(positions, links, engine.tool(0).position, section_radii_);
  }
  return s;
}

void RunRecorder::record(const Engine& engine, double time, double displacement, double velocity, const Vector3& mean_force) {
  const EnergySplit& e = engine.energy();
  const Vector3 instant = engine.tool_count() ? Vector3(-engine.tool_force(0)) : Vector3::Zero();
  double largest = 0.0;
  for (std::size_t l = 0; l < engine.link_count(); ++l)
    if (!engine.link(l).law->broken()) largest = std::max(largest, std::abs(engine.link(l).law->forces()[0]));
  const double contacts = engine.tool_count() ? static_cast<double>(engine.tool_contacts(0)) : 0.0;
  // The force the tool exerts on the net (minus the net's force on the tool), interval mean.
  const std::vector<double> row = {time, 1000.0 * displacement, velocity, mean_force.norm(), mean_force.z(), instant.norm(), contacts,
                                   e.kinetic, e.link_elastic, e.contact_elastic, e.link_plastic, e.link_damage,
                                   e.friction, e.damping, e.gravity_work, e.tool_work, e.boundary_work,
                                   e.balance_error(), static_cast<double>(engine.broken_links()), largest};
  for (std::size_t c = 0; c < row.size(); ++c) columns_[c].push_back(row[c]);
  links_.sample(engine, 1000.0 * displacement);
  if (mean_force.norm() > peak_force_) {
    peak_force_ = mean_force.norm();
    peak_instant_force_ = instant.norm();
    at_peak_ = snapshot(engine);
    links_.mark_peak();
  }
}

void RunRecorder::frame(const Engine& engine, double time) {
  const std::string name = "net_" + std::to_string(frames_.size()) + ".vtu";
  write_file_atomically(options_.out / "frames" / name, [&](std::ostream& os) {
    const std::size_t n = engine.node_count(), m = engine.link_count();
    os << std::setprecision(9);
    os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       << "<UnstructuredGrid><Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << m << "\">\n"
       << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) {
      const Vector3 p = engine.position(i);
      os << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    os << "</DataArray></Points>\n<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t l = 0; l < m; ++l) os << engine.link(l).link.a << ' ' << engine.link(l).link.b << '\n';
    os << "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t l = 0; l < m; ++l) os << 2 * (l + 1) << '\n';
    os << "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t l = 0; l < m; ++l) os << "3\n";
    os << "</DataArray></Cells>\n<PointData><DataArray type=\"Float64\" Name=\"displacement_m\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) {
      const Vector3 d = engine.position(i) - mesh_.net.nodes[i].position;
      os << d.x() << ' ' << d.y() << ' ' << d.z() << '\n';
    }
    os << "</DataArray></PointData>\n<CellData><DataArray type=\"Float64\" Name=\"axial_force_N\" format=\"ascii\">\n";
    for (std::size_t l = 0; l < m; ++l)
      os << (engine.link(l).law->broken() ? 0.0 : engine.link(l).law->forces()[0]) << '\n';
    os << "</DataArray><DataArray type=\"Int32\" Name=\"tag\" format=\"ascii\">\n";
    for (std::size_t l = 0; l < m; ++l) os << static_cast<int>(engine.link(l).link.tag) << '\n';
    os << "</DataArray><DataArray type=\"Int32\" Name=\"broken\" format=\"ascii\">\n";
    for (std::size_t l = 0; l < m; ++l) os << (engine.link(l).law->broken() ? 1 : 0) << '\n';
    os << "</DataArray></CellData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
  });
  frames_.emplace_back(time, name);
}

void RunRecorder::write_frame_index() const {
  if (frames_.empty()) return;
  write_file_atomically(options_.out / "net.pvd", [&](std::ostream& os) {
    os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
    for (const auto& [time, name] : frames_)
      os << "  <DataSet timestep=\"" << format_number(time) << "\" file=\"frames/" << name << "\"/>\n";
    os << "</Collection>\n</VTKFile>\n";
  });
}

void add_engine_parameters(Results& results, const RunInput& input, const RunSummary& summary) {
  auto parameter = [&](const std::string& name, double value, const std::string& unit) {
    results.parameters.push_back({name, value, unit, std::nullopt});
  };
  parameter("time_step_s", summary.time_step, "s");
  parameter("critical_time_step_s", summary.critical_time_step, "s");
  parameter("settle_time_step_s", summary.settle_time_step, "s");
  parameter("settle_s", summary.settle_seconds, "s");
  parameter("settle_rest_ratio", input.settle_rest_ratio, "1");
  if (std::isfinite(summary.settle_unbalanced_ratio))  // infinite while no link carries force
    parameter("settle_unbalanced_force_ratio", summary.settle_unbalanced_ratio, "1");
  parameter("mass_scale", input.engine.mass_scale, "1");
  parameter("rotational_inertia_scale", input.engine.rotational_inertia_scale, "1");
  parameter("local_damping", input.engine.local_damping, "1");
  parameter("nodes", static_cast<double>(summary.nodes), "1");
  parameter("links", static_cast<double>(summary.links), "1");
}

std::string run_status(const RunSummary& summary) {
  return summary.failed ? "failed: " + summary.failed->message() : "ok";
}

void add_status(nlohmann::json& headline, const RunSummary& summary) {
  headline["status"] = summary.failed ? "failed" : "ok";
  if (!summary.failed) return;
  const FailedCheck& f = *summary.failed;
  headline["failed_check"] = {{"check", f.check}, {"bound_key", f.key}, {"time_s", f.time}, {"step", f.step},
                              {"value_percent", 100.0 * f.value}, {"bound_percent", 100.0 * f.bound},
                              {"before_loading", f.before_loading}, {"message", f.message()}};
}

void RunRecorder::finish(const Engine& engine, RunSummary& summary) {
  std::vector<std::filesystem::path> inputs{input_.file};
  for (const auto& [tag, set] : input_.link_sets)
    for (const auto& file : set.files)
      if (std::find(inputs.begin(), inputs.end(), file) == inputs.end()) inputs.push_back(file);  // one entry per file
  const Provenance provenance = make_provenance(options_.command_line, inputs);

  Curve history;
  const auto& names = history_columns();
  for (std::size_t c = 0; c < names.size(); ++c) history.add_channel(names[c].first, *find_unit(names[c].second), columns_[c]);
  history.set_metadata("source", "dtwire dem run " + input_.file.filename().string());
  history.set_metadata("title", input_.title);
  const std::string label = options_.label.empty() ? input_.title : options_.label;
  history.set_metadata("label", label);  // the legend entry of plots
  history.set_metadata("tool", input_.tool);
  history.set_metadata("time_step_s", format_number(summary.time_step));
  history.set_metadata("sag_after_settling_mm", format_number(1000.0 * summary.sag));
  history.set_metadata("run_id", provenance.run_id);
  history.set_metadata("status", run_status(summary));

  // Figures: peak, displacement at the peak, the largest balance error against the work on the
  // mesh (rows after 5 % of the final work, so that round-off on a tiny work does not count).
  const auto& force = columns_[3];
  const auto& displacement = columns_[1];
  std::size_t peak = 0;
  for (std::size_t r = 0; r < force.size(); ++r)
    if (force[r] > force[peak]) peak = r;
  summary.peak_force = force.empty() ? 0.0 : force[peak];
  summary.displacement_at_peak = force.empty() ? 0.0 : displacement[peak] / 1000.0;
  std::vector<double> displacement_m;
  for (double mm : displacement) displacement_m.push_back(mm / 1000.0);
  const PunchFigures figures = punch_figures(displacement_m, force);
  summary.onset = figures.onset;
  summary.force_at_420mm = figures.force_at_probe;
  const auto& gravity = columns_[14];
  const auto& tool = columns_[15];
  const auto& boundary = columns_[16];
  const auto& error = columns_[17];
  auto work = [&](std::size_t r) { return std::abs(gravity[r]) + std::abs(tool[r]) + std::abs(boundary[r]); };
  const double final_work = force.empty() ? 0.0 : work(force.size() - 1);
  for (std::size_t r = 0; r < force.size(); ++r)
    if (work(r) > 0.05 * final_work && work(r) > 0.0)
      summary.largest_balance_error = std::max(summary.largest_balance_error, std::abs(error[r]) / work(r));
  // How much of the work done on the net from the settled state (first row) to the peak the local
  // damping took: where it grows, damping forces (not the links) carry part of the tool's force
  // (docs/dem_engine.md, "Where the punch's force goes").
  const auto& damping = columns_[13];
  const double work_to_peak = force.empty() ? 0.0 : work(peak) - work(0);
  const double damping_share_to_peak = work_to_peak > 0.0 ? (damping[peak] - damping[0]) / work_to_peak : 0.0;
  summary.history = history;

  write_csv(history, options_.out / "curve.csv");
  const Snapshot at_end = snapshot(engine);
  if (peak_force_ < 0.0) at_peak_ = at_end;
  Curve forces = histogram("link_force", "N", 250.0, at_peak_.link_forces, at_end.link_forces);
  Curve angles = histogram("pulling_angle", "deg", 5.0, at_peak_.pulling_angles, at_end.pulling_angles);
  forces.set_metadata("run_id", provenance.run_id);
  angles.set_metadata("run_id", provenance.run_id);
  write_csv(forces, options_.out / "link_force_histogram.csv");
  write_csv(angles, options_.out / "pulling_angle_histogram.csv");
  if (!at_peak_.sections.empty()) {
    Curve sections = membrane_curve(at_peak_.sections);
    sections.set_metadata("run_id", provenance.run_id);
    sections.set_metadata("tool_force_at_peak_N", format_number(peak_force_));
    // The sections are the links' state at that instant: their vertical force balances this one
    // while the net moves quasi-statically (the interval mean above chatters less).
    sections.set_metadata("tool_force_instant_at_peak_N", format_number(peak_instant_force_));
    write_csv(sections, options_.out / "membrane_at_peak.csv");
  }
  links_.write(options_.out, provenance.run_id);

  write_frame_index();

  Results results;
  results.curves = {{"history", history}, {"link_force_histogram", forces}, {"pulling_angle_histogram", angles}};
  add_engine_parameters(results, input_, summary);
  auto parameter = [&](const std::string& name, double value, const std::string& unit) {
    results.parameters.push_back({name, value, unit, std::nullopt});
  };
  parameter("mass_per_area_kg_per_m2", mesh_.mass_per_area, "1");
  parameter("sag_after_settling_m", summary.sag, "m");
  parameter("peak_force_N", summary.peak_force, "N");
  parameter("displacement_at_peak_m", summary.displacement_at_peak, "m");
  parameter("largest_balance_error_1", summary.largest_balance_error, "1");
  parameter("broken_links", static_cast<double>(summary.broken_links), "1");
  parameter("pretension_strain_1", summary.pretension_strain, "1");
  parameter("kinetic_energy_after_settling_J", summary.kinetic_after_settling, "J");
  if (input_.tool == "platter") {
    parameter("onset_displacement_m", summary.onset, "m");
    if (summary.force_at_420mm >= 0.0) parameter("force_at_420mm_N", summary.force_at_420mm, "N");
  }
  results.fields.emplace_back("frames", frames_.empty() ? "none" : "net.pvd (frames/net_<k>.vtu)");
  results.fields.emplace_back("title", input_.title);
  results.fields.emplace_back("status", run_status(summary));
  results.provenance = provenance;
  write_results(results, options_.out / "results.h5");

  // The headline figures for reports (the campaign's validation table), SI-named columns.
  nlohmann::json headline = {
      {"title", input_.title},
      {"label", label},
      {"tool", input_.tool},
      {"peak_force_N", summary.peak_force},
      {"displacement_at_peak_mm", 1000.0 * summary.displacement_at_peak},
      {"sag_after_settling_mm", 1000.0 * summary.sag},
      {"pretension_strain", summary.pretension_strain},
      {"support", edge_support_name(input_.support)},
      {"kinetic_energy_after_settling_J", summary.kinetic_after_settling},
      {"broken_links", summary.broken_links},
      {"links", summary.links},
      {"largest_balance_error_percent", 100.0 * summary.largest_balance_error},
      {"damping_share_to_peak_percent", 100.0 * damping_share_to_peak},
      {"time_step_s", summary.time_step},
      {"settle_time_step_s", summary.settle_time_step},
      {"settle_s", summary.settle_seconds},
      {"settled_at_rest", input_.settle_rest_ratio > 0.0 ? nlohmann::json(summary.settled_at_rest) : nlohmann::json()},
      {"settle_unbalanced_force_ratio", std::isfinite(summary.settle_unbalanced_ratio) ? nlohmann::json(summary.settle_unbalanced_ratio) : nlohmann::json()},
      {"settle_kinetic_arrests", summary.settle_arrests},
      {"settle_local_damping_from_s", summary.settle_local_damping_from >= 0.0 ? nlohmann::json(summary.settle_local_damping_from) : nlohmann::json()},
      {"wall_entered_at_s", summary.wall_entered_at < 0.0 ? nlohmann::json() : nlohmann::json(summary.wall_entered_at)},
      {"steps", summary.steps},
      {"wall_seconds", summary.wall_seconds},
      {"command", options_.command_line},
      {"run_id", provenance.run_id}};
  if (input_.tool == "platter") {
    headline["onset_displacement_mm"] = summary.onset < 0.0 ? nlohmann::json() : nlohmann::json(1000.0 * summary.onset);
    headline["onset_force_N"] = 1000.0;
    // null where the platter stopped short of 0.42 m (a net that failed earlier, a shorter travel).
    headline["force_at_420mm_N"] = summary.force_at_420mm < 0.0 ? nlohmann::json() : nlohmann::json(summary.force_at_420mm);
    headline["stopped_at_failure"] = summary.stopped_at_failure;
  }
  if (!at_peak_.sections.empty()) {
    // The innermost section, just outside the platter's base: F = 2 pi r T tan(slope).
    const MembraneSection& rim = at_peak_.sections.front();
    headline["rim_radius_m"] = rim.radius;
    headline["rim_tension_at_peak_kN_per_m"] = 1e-3 * rim.radial_tension;
    headline["rim_largest_sector_tension_at_peak_kN_per_m"] = 1e-3 * rim.largest_sector_tension;
    headline["rim_slope_at_peak_deg"] = rim.slope * 180.0 / kPi;
  }
  add_status(headline, summary);
  write_file_atomically(options_.out / "summary.json", [&](std::ostream& os) { os << headline.dump(2) << "\n"; });
}

}  // namespace dtwire::dem
