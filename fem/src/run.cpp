#include "dtwire/fem/run.hpp"

#include <deal.II/base/mpi.h>

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <csignal>
#include <optional>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/core/resources.hpp"
#include "dtwire/core/results_store.hpp"
#include "contact/contact_curve.hpp"  // contact (issue 5)
#include "failure_place.hpp"
#include "link_kinematics.hpp"
#include "run_checks.hpp"
#include "run_resources.hpp"
#include "solver.hpp"

namespace dtwire::fem {
namespace {

// Writes to the log file and, if wanted, to stdout.
class TeeBuffer : public std::streambuf {
 public:
  TeeBuffer(std::streambuf* a, std::streambuf* b) : a_(a), b_(b) {}

 protected:
  int overflow(int c) override {
    if (c == EOF) return !EOF;
    if (a_ && a_->sputc(static_cast<char>(c)) == EOF) return EOF;
    if (b_ && b_->sputc(static_cast<char>(c)) == EOF) return EOF;
    return c;
  }
  int sync() override {
    if (a_) a_->pubsync();
    if (b_) b_->pubsync();
    return 0;
  }

 private:
  std::streambuf* a_;
  std::streambuf* b_;
};

const StepRecord* first_failure(const std::vector<StepRecord>& records) {
  for (const auto& r : records)
    if (r.damage >= 1.0) return &r;
  return nullptr;
}

// Generalised end results (issue 5): with d the load direction and k the rotation axis, the
// axial force N = F . d, shear V = F . (k x d), moment M = M_end . k (about the moving end
// centre) and their work-conjugates u (the load path), w = translation . (k x d), theta; the
// full force and moment vectors; the energy split and the balance error
// W_ext - (elastic + plastic + friction + penalty springs + grip bond energy and slip).
void add_generalised_channels(Curve& c, const std::vector<StepRecord>& records, const Parameters& p) {
  std::array<double, 3> d{{0.0, 0.0, 1.0}}, k = p.load.rotation_axis;
  if (!p.load.pull_direction.empty()) d = {{p.load.pull_direction[0], p.load.pull_direction[1], p.load.pull_direction[2]}};
  else if (p.load.direction == LoadDirection::lateral) d = {{1.0, 0.0, 0.0}};
  const std::array<double, 3> v{{k[1] * d[2] - k[2] * d[1], k[2] * d[0] - k[0] * d[2], k[0] * d[1] - k[1] * d[0]}};
  const auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  const auto channel = [&](const std::string& name, Dimension dimension, const char* unit,
                           const std::function<double(const StepRecord&)>& value) {
    std::vector<double> values;
    for (const auto& r : records) values.push_back(value(r));
    c.add_channel_si(name, dimension, values, *find_unit(unit));
  };
  channel("axial_force", Dimension::Force, "N", [&](const StepRecord& r) { return dot(r.end_force, d); });
  channel("shear_force", Dimension::Force, "N", [&](const StepRecord& r) { return dot(r.end_force, v); });
  channel("moment", Dimension::Moment, "Nm", [&](const StepRecord& r) { return dot(r.end_moment, k); });
  channel("transverse_displacement", Dimension::Length, "mm",
          [&](const StepRecord& r) { return dot(r.end_translation, v); });
  channel("rotation", Dimension::Angle, "rad", [](const StepRecord& r) { return r.end_rotation; });
  const char* axes[] = {"x", "y", "z"};
  for (unsigned a = 0; a < 3; ++a) {
    channel(std::string("end_force_") + axes[a], Dimension::Force, "N", [a](const StepRecord& r) { return r.end_force[a]; });
    channel(std::string("end_moment_") + axes[a], Dimension::Moment, "Nm",
            [a](const StepRecord& r) { return r.end_moment[a]; });
  }
  channel("external_work", Dimension::Energy, "J", [](const StepRecord& r) { return r.external_work; });
  // from the first record: an as-made specimen starts with the energy its forming left
  const double initial = stored_energy(records.front());
  channel("energy_balance_error", Dimension::Energy, "J",
          [&](const StepRecord& r) { return r.external_work - (stored_energy(r) - initial); });
}

// The twist as a DEM link (link_kinematics.hpp): chord elongation, relative rotation of the top
// section, axial and shear force, moment about the link midpoint.
void add_link_channels(Curve& c, const std::vector<StepRecord>& records, const OutputParameters& output) {
  const auto section = [&](std::size_t which, const StepRecord* s) {
    SectionPoints points{};
    for (unsigned k = 0; k < 4; ++k) {
      const std::size_t i = output.link_sections[which][k];
      for (unsigned a = 0; a < 3; ++a)
        points[k][a] = output.probe_points[i][a] + (s ? s->probe_displacements.at(i)[a] : 0.0);
    }
    return points;
  };
  std::vector<LinkState> states;
  for (const auto& s : records)
    states.push_back(link_state(section(0, nullptr), section(0, &s), section(1, nullptr), section(1, &s), s.end_force,
                                s.end_moment, s.end_centre));
  const auto channel = [&](const std::string& name, Dimension dimension, const char* unit,
                           const std::function<double(const LinkState&)>& value) {
    std::vector<double> values;
    for (const auto& s : states) values.push_back(value(s));
    c.add_channel_si(name, dimension, values, *find_unit(unit));
  };
  const char* axes[] = {"x", "y", "z"};
  channel("link_elongation", Dimension::Length, "mm", [](const LinkState& s) { return s.elongation; });
  for (unsigned a = 0; a < 3; ++a)
    channel(std::string("link_rotation_") + axes[a], Dimension::Angle, "rad",
            [a](const LinkState& s) { return s.rotation[a]; });
  channel("link_axial_force", Dimension::Force, "N", [](const LinkState& s) { return s.axial_force; });
  channel("link_shear_force", Dimension::Force, "N", [](const LinkState& s) { return s.shear_force; });
  for (unsigned a = 0; a < 3; ++a)
    channel(std::string("link_moment_") + axes[a], Dimension::Moment, "Nm",
            [a](const LinkState& s) { return s.moment[a]; });
  const SectionPoints bottom = section(0, nullptr), top = section(1, nullptr);
  double length = 0.0;
  for (unsigned a = 0; a < 3; ++a) length += std::pow((top[0][a] + top[1][a] - bottom[0][a] - bottom[1][a]) / 2, 2);
  std::ostringstream text;
  text << std::setprecision(10) << std::sqrt(length) * 1e3;
  c.set_metadata("link_length_mm", text.str());
}

// Mean change of distance between the material points of each extensometer pair (m).
double extensometer_elongation(const StepRecord& s, const OutputParameters& output) {
  double sum = 0.0;
  for (const auto& [i, j] : output.extensometer) {
    const auto& X = output.probe_points;
    const auto& U = s.probe_displacements;
    double reference = 0.0, current = 0.0;
    for (unsigned a = 0; a < 3; ++a) {
      reference += std::pow(X[j][a] - X[i][a], 2);
      current += std::pow(X[j][a] + U[j][a] - X[i][a] - U[i][a], 2);
    }
    sum += std::sqrt(current) - std::sqrt(reference);
  }
  return sum / static_cast<double>(output.extensometer.size());
}

// SIGINT during a run: the note (with how to resume) is appended to run.log through a plain
// file descriptor, the only async-signal-safe way, then the default action ends the process.
int interrupt_log = -1;
std::string interrupt_note;

extern "C" void record_interrupt(int signal_number) {
  if (interrupt_log >= 0) {
    [[maybe_unused]] const auto written = ::write(interrupt_log, interrupt_note.data(), interrupt_note.size());
  }
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

class InterruptRecord {
 public:
  InterruptRecord(const std::filesystem::path& log, const RunOptions& options, const Parameters& p) {
    const auto& out = options.output_directory.string();
    interrupt_note = "\ninterrupted (SIGINT); resume with: dtwire run " + options.parameter_file.string() + " -o " + out +
                     (p.output.checkpoint_interval > 0
                          ? " --restart STEP (STEP: the latest step under " + out + "/checkpoints)\n"
                          : " (no checkpoints: set Output/Checkpoint interval to resume part-way)\n");
    interrupt_log = ::open(log.c_str(), O_WRONLY | O_APPEND);
    previous_ = std::signal(SIGINT, record_interrupt);
  }
  ~InterruptRecord() {
    std::signal(SIGINT, previous_);
    if (interrupt_log >= 0) ::close(interrupt_log);
    interrupt_log = -1;
  }
  InterruptRecord(const InterruptRecord&) = delete;
  InterruptRecord& operator=(const InterruptRecord&) = delete;

 private:
  void (*previous_)(int) = SIG_DFL;
};

Curve make_curve(const std::vector<StepRecord>& records, const RunOptions& options, const Parameters& p,
                 const std::string& run_id) {
  std::vector<double> u, f, d, e, r, gauge;
  for (const auto& s : records) {
    u.push_back(s.displacement);
    f.push_back(s.force);
    d.push_back(s.plastic_dissipation);
    e.push_back(s.elastic_energy);
    r.push_back(s.neck_radius);
    // from the first record: an as-made specimen's springback is not an elongation of the test
    if (!p.output.extensometer.empty())
      gauge.push_back(extensometer_elongation(s, p.output) - extensometer_elongation(records.front(), p.output));
  }
  Curve c;
  if (p.output.extensometer_as_displacement) {
    c.add_channel_si("displacement", Dimension::Length, gauge, *find_unit("mm"));
    c.add_channel_si("grip_displacement", Dimension::Length, u, *find_unit("mm"));
  } else {
    c.add_channel_si("displacement", Dimension::Length, u, *find_unit("mm"));
    if (!gauge.empty()) c.add_channel_si("extensometer_elongation", Dimension::Length, gauge, *find_unit("mm"));
  }
  c.add_channel_si("force", Dimension::Force, f, *find_unit("N"));
  c.add_channel_si("plastic_dissipation", Dimension::Energy, d, *find_unit("J"));
  c.add_channel_si("elastic_energy", Dimension::Energy, e, *find_unit("J"));
  if (!p.geometry.double_twist && p.geometry.straight_axis) c.add_channel_si("neck_radius", Dimension::Length, r, *find_unit("mm"));
  if (p.material.failure.enabled()) {
    std::vector<double> damage;
    for (const auto& s : records) damage.push_back(s.damage);
    c.add_channel_si("damage", Dimension::Dimensionless, damage, *find_unit("1"));
    if (const StepRecord* failure = first_failure(records)) {
      std::ostringstream text;
      if (p.geometry.junction_planes.size() == 2) {  // a double twist's two ends
        const auto [low, high] = std::minmax(p.geometry.junction_planes[0], p.geometry.junction_planes[1]);
        const char* place = to_string(failure_place(failure->damage_z, p.geometry.diameter, {{low, high}}));
        c.set_metadata("failure_place", place);
        text << "in the " << place << ", ";
      }
      text << failure_mode(failure->damage_triaxiality, failure->damage_lode) << " at displacement " << failure->displacement * 1e3 << " mm, force "
           << failure->force << " N, z = " << failure->damage_z * 1e3 << " mm, r = " << failure->damage_r * 1e3
           << " mm, triaxiality " << failure->damage_triaxiality << ", Lode parameter " << failure->damage_lode;
      c.set_metadata("failure", text.str());
    }
  }
  if (!records.empty() && records.front().contact.enabled) {  // contact (issue 5)
    std::vector<contact::ContactRecord> contacts;
    for (const auto& s : records) contacts.push_back(s.contact);
    contact::add_contact_channels(c, contacts);
  }
  if (!records.empty() && records.front().wire_contact.enabled) {
    std::vector<contact::WireContactRecord> wires;
    for (const auto& s : records) wires.push_back(s.wire_contact);
    contact::add_wire_contact_channels(c, wires);
  }
  if (!records.empty() && records.front().grip.enabled) {  // bonded grips
    std::vector<contact::GripRecord> grips;
    for (const auto& s : records) grips.push_back(s.grip);
    contact::add_grip_channels(c, grips);
    const double area = records.front().grip.top_area;
    std::ostringstream mm2, newton;
    mm2 << std::setprecision(10) << area * 1e6;
    newton << std::setprecision(10) << p.load.grip.strength * area;
    c.set_metadata("grip_top_area_mm2", mm2.str());
    c.set_metadata("grip_capacity_N", newton.str());
  }
  if (p.generalised_output()) add_generalised_channels(c, records, p);
  if (!p.output.link_sections.empty()) add_link_channels(c, records, p.output);
  const char* axes[] = {"x", "y", "z"};
  for (std::size_t k = 0; k < p.output.probe_points.size(); ++k)
    for (unsigned a = 0; a < 3; ++a) {
      std::vector<double> values;
      for (const auto& s : records) values.push_back(s.probe_displacements.at(k)[a]);
      c.add_channel_si("probe" + std::to_string(k + 1) + "_displacement_" + axes[a], Dimension::Length, values,
                       *find_unit("mm"));
    }
  c.set_metadata("source", "dtwire run " + options.parameter_file.filename().string());
  c.set_metadata("run_id", run_id);
  c.set_metadata("model", std::string("finite-strain J2 plasticity, ") +
                              (p.formulation.fbar ? "F-bar" : "plain displacement") + " Q" +
                              std::to_string(p.formulation.degree) + " hexahedra");
  return c;
}

// summary.json beside the curve (issue 37): "status" ("ok" or "failed"), the checks' largest
// figures, and for a failed run the check (or the error) that stopped it.
void write_summary_json(const std::filesystem::path& file, const RunGuard& guard, const RunChecks& bounds,
                        const std::string& run_id, const std::optional<FailedCheck>& failed,
                        const std::string& error) {
  const bool ok = !failed && error.empty();
  nlohmann::json summary = {{"run_id", run_id},
                            {"status", ok ? "ok" : "failed"},
                            {"largest_energy_balance_error_percent", 100 * guard.largest_balance_error()},
                            {"largest_energy_imbalance_percent", 100 * guard.largest_imbalance()},
                            {"trapezoid_allowance_percent", 100 * guard.final_allowance()},
                            {"max_energy_balance_error_percent", 100 * bounds.max_balance_error},
                            {"largest_penetration_percent_of_diameter", 100 * guard.largest_penetration()},
                            {"max_penetration_percent_of_diameter", 100 * bounds.max_penetration}};
  if (failed)
    summary["failed_check"] = {{"check", failed->check},          {"entry", failed->entry},
                               {"step", failed->step},            {"pseudo_time", failed->time},
                               {"displacement_mm", failed->displacement * 1e3},
                               {"value_percent", 100 * failed->value}, {"bound_percent", 100 * failed->bound}};
  if (!ok) summary["message"] = failed ? failed->message() : error;
  write_file_atomically(file, [&](std::ostream& os) { os << summary.dump(2) << "\n"; });
}

// Memory and disk before the mesh is built or a file written (issue 37): every rank estimates
// alike, from the figures the first rank read, so that all refuse or none.
void check_resources_before_the_run(const Parameters& parameters, const RunOptions& options) {
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  std::array<std::uint64_t, 4> figures{};  // has available, available, has free disk, free disk
  if (root) {
    const auto available = available_memory();
    const auto free_disk = free_disk_space(options.output_directory);
    figures = {{available.has_value(), available.value_or(0), free_disk.has_value(), free_disk.value_or(0)}};
  }
  MPI_Bcast(figures.data(), static_cast<int>(figures.size()), MPI_UINT64_T, 0, MPI_COMM_WORLD);
  const auto figure = [&](std::size_t i) { return figures[i] ? std::optional<std::uint64_t>(figures[i + 1]) : std::nullopt; };
  check_run_resources(parameters, dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD), options.max_memory, figure(0),
                      figure(2), options.parameter_file.string(), options.output_directory);
}

// A check stopped the run inside the solver's step callback.
struct CheckStop {};

}  // namespace

RunSummary run_experiment(const RunOptions& options) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) throw std::logic_error("run_experiment: MPI is not initialised");
  const auto start = std::chrono::steady_clock::now();
  Parameters parameters = read_parameters(options.parameter_file, options.settings);
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const auto& out = options.output_directory;
  check_resources_before_the_run(parameters, options);
  if (root) {
    std::filesystem::create_directories(out);
    // Results of an earlier run in this folder would sit beside this run's log: remove them.
    for (const char* stale : {"curve.csv", "curve.partial.csv", "results.h5", "summary.json", kTwistedPairStateFile})
      std::filesystem::remove(out / stale);
    const auto state = out / kAsMadeStateFile;  // stale too, unless this run reads it
    const bool read_here = !parameters.forming.state_file.empty() && std::filesystem::exists(state) &&
                           std::filesystem::equivalent(state, parameters.forming.state_file);
    if (!read_here) std::filesystem::remove(state);
  }
  MPI_Barrier(MPI_COMM_WORLD);

  std::ofstream log_file;
  if (root) log_file.open(out / "run.log");
  TeeBuffer tee(root ? log_file.rdbuf() : nullptr, root && options.echo ? std::cout.rdbuf() : nullptr);
  std::ostream log(&tee);
  const std::string run_id = new_run_id();  // in the log, curve.csv and results.h5 alike
  log << "dtwire " << tool_version() << " (" << git_hash() << "): " << options.parameter_file.string() << ", run "
      << run_id << "\n";
  log.flush();
  std::optional<InterruptRecord> interrupt;
  if (root) interrupt.emplace(out / "run.log", options, parameters);

  // A mesh file deal.II cannot read is bad input, named as such (not a failed computation).
  const auto make_solver = [&]() {
    try {
      return std::make_unique<WireSolver>(parameters, log,
                                          parameters.output.fields ? out / "fields" : std::filesystem::path());
    } catch (const dealii::ExceptionBase& e) {
      if (parameters.geometry.mesh_file.empty()) throw ComputationError(deal_ii_message(e.what()));
      throw InputError(parameters.geometry.mesh_file.string(), "cannot read the mesh: " + deal_ii_message(e.what()));
    }
  };
  const std::unique_ptr<WireSolver> solver_owner = make_solver();
  WireSolver& solver = *solver_owner;
  parameters.geometry = solver.geometry();  // as read from a mesh file (length, double twist)
  solver.set_checkpoints(out / "checkpoints", parameters.output.checkpoint_interval, options.restart_step);
  if (parameters.forming.enabled && parameters.forming.state_file.empty()) solver.set_as_made_output(out / kAsMadeStateFile);
  if (parameters.forming.release_after_path) solver.set_twisted_pair_output(out / kTwistedPairStateFile);
  std::vector<StepRecord> records;
  RunSummary summary;
  summary.root = root;
  summary.curve_csv = out / "curve.csv";
  summary.results_h5 = out / "results.h5";
  summary.log = out / "run.log";
  // The self-checks judge every converged step; the records are the same on every rank, so all
  // ranks stop at the same step.
  RunGuard guard(parameters.checks, parameters.geometry.diameter);
  std::optional<FailedCheck> failed;
  const auto write_partial = [&](const std::string& status) {
    if (!root) return;
    if (records.size() >= kMinimumCurvePoints) {
      Curve partial = make_curve(records, options, parameters, run_id);
      partial.set_metadata("status", "failed: " + status);
      write_csv(partial, out / "curve.partial.csv");
    }
    write_summary_json(out / "summary.json", guard, parameters.checks, run_id, failed, status);
  };
  try {
    solver.run([&](const StepRecord& r) {
      records.push_back(r);
      if ((failed = guard.check(r))) throw CheckStop{};
    });
  } catch (const CheckStop&) {
    const std::string message = failed->message();
    log << "failed: " << message << "\n";
    log.flush();
    write_partial(message);
    throw ComputationError(message + "; the steps before it are in " + (out / "curve.partial.csv").string() +
                           " (bounds: subsection Checks)");
  } catch (const ComputationError& e) {
    write_partial(e.what());
    throw;
  }
  log << "checks: largest energy balance error " << 100 * guard.largest_balance_error() << " % of the external work (bound "
      << 100 * parameters.checks.max_balance_error << " %; imbalance " << 100 * guard.largest_imbalance()
      << " %, the trapezoidal work's allowance " << 100 * guard.final_allowance() << " %), largest penetration " << 100 * guard.largest_penetration()
      << " % of the diameter (bound " << 100 * parameters.checks.max_penetration << " %)\n";
  const auto& st = solver.statistics();
  summary.ranks = st.ranks;
  summary.dofs = st.dofs;
  summary.cells = st.cells;
  summary.steps = st.steps;
  summary.newton_iterations = st.newton_iterations;
  summary.cutbacks = st.cutbacks;
  summary.assembly_seconds = st.assembly_seconds;
  summary.solve_seconds = st.solve_seconds;
  if (st.forming.done)
    summary.springback = {true, !st.forming.state_file.empty(), st.forming.energy_balance, st.forming.largest_displacement * 1e3,
                          st.forming.clearance_mean * 1e3, st.forming.clearance_largest * 1e3, st.forming.seconds,
                          st.forming.top_rotation};
  for (const auto& r : records)
    if (std::abs(r.force) > std::abs(summary.peak_force_N)) {  // largest magnitude, signed
      summary.peak_force_N = r.force;
      summary.displacement_at_peak_mm = r.displacement * 1e3;
    }
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log << "done: " << st.steps << " steps, " << st.newton_iterations << " Newton iterations, " << st.cutbacks
      << " cut-backs, " << st.assemblies << " assemblies, " << st.factorisations << " factorisations; peak force " << summary.peak_force_N << " N at "
      << summary.displacement_at_peak_mm << " mm; wall " << summary.wall_seconds << " s (assembly "
      << st.assembly_seconds << " s, solve " << st.solve_seconds << " s)\n";
  log.flush();
  if (!root) return summary;

  Curve curve = make_curve(records, options, parameters, run_id);
  curve.set_metadata("status", "ok");
  if (st.ended_in_snap_back)
    curve.set_metadata("end", "no static state follows the fracture (snap-back): the curve ends at its last converged step");
  if (records.size() >= kMinimumCurvePoints) write_csv(curve, summary.curve_csv);
  else throw ComputationError("fewer than 3 load steps: no curve written");
  Results results;
  results.curves.emplace_back("curve", curve);
  results.parameters.push_back({"peak_force", summary.peak_force_N, "N", std::nullopt});
  results.parameters.push_back({"displacement_at_peak", summary.displacement_at_peak_mm * 1e-3, "m", std::nullopt});
  results.parameters.push_back({"dofs", static_cast<double>(st.dofs), "1", std::nullopt});
  results.parameters.push_back({"steps", static_cast<double>(st.steps), "1", std::nullopt});
  results.parameters.push_back({"newton_iterations", static_cast<double>(st.newton_iterations), "1", std::nullopt});
  results.parameters.push_back({"mpi_ranks", static_cast<double>(st.ranks), "1", std::nullopt});
  results.parameters.push_back({"largest_energy_balance_error", guard.largest_balance_error(), "1", std::nullopt});
  results.parameters.push_back({"largest_penetration_of_diameter", guard.largest_penetration(), "1", std::nullopt});
  if (const StepRecord* f = first_failure(records)) {
    results.parameters.push_back({"failure_displacement", f->displacement, "m", std::nullopt});
    results.parameters.push_back({"failure_force", f->force, "N", std::nullopt});
    results.parameters.push_back({"failure_triaxiality", f->damage_triaxiality, "1", std::nullopt});
    results.parameters.push_back({"failure_lode_parameter", f->damage_lode, "1", std::nullopt});
    log << "failure: " << curve.metadata("failure") << "\n";
  }
  if (st.forming.done) {  // as made: what the springback left (issue 19)
    const auto& fm = st.forming;
    Curve profile;
    const auto column = [&](const std::string& name, Dimension dimension, const char* unit,
                            const std::function<double(const FormingProfileRow&)>& value) {
      std::vector<double> v;
      for (const auto& row : fm.profile) v.push_back(value(row));
      profile.add_channel_si(name, dimension, v, *find_unit(unit));
    };
    column("wire", Dimension::Dimensionless, "1", [](const FormingProfileRow& r) { return r.wire; });
    column("arc_length", Dimension::Length, "mm", [](const FormingProfileRow& r) { return r.arc_length; });
    column("z", Dimension::Length, "mm", [](const FormingProfileRow& r) { return r.z; });
    column("von_mises_mean", Dimension::Stress, "MPa", [](const FormingProfileRow& r) { return r.von_mises_mean; });
    column("von_mises_max", Dimension::Stress, "MPa", [](const FormingProfileRow& r) { return r.von_mises_max; });
    column("plastic_strain_mean", Dimension::Dimensionless, "1",
           [](const FormingProfileRow& r) { return r.plastic_strain_mean; });
    column("plastic_strain_max", Dimension::Dimensionless, "1",
           [](const FormingProfileRow& r) { return r.plastic_strain_max; });
    column("damage_max", Dimension::Dimensionless, "1", [](const FormingProfileRow& r) { return r.damage_max; });
    write_csv(profile, out / "as_made.csv");
    struct Figure {
      const char* name;
      double value;
      const char* unit;
    };
    const Figure figures[] = {{"springback_energy_balance", fm.energy_balance, "1"},
                              {"springback_seconds", fm.seconds, "s"},
                              {"springback_largest_displacement", fm.largest_displacement, "m"},
                              {"clearance_mean", fm.clearance_mean, "m"},
                              {"clearance_largest", fm.clearance_largest, "m"},
                              {"forming_elastic_energy", fm.initial_elastic_energy, "J"},
                              {"residual_elastic_energy", fm.elastic_energy, "J"}};
    for (const auto& figure : figures) results.parameters.push_back({figure.name, figure.value, figure.unit, std::nullopt});
    if (fm.after_path) results.parameters.push_back({"release_top_rotation", fm.top_rotation, "rad", std::nullopt});
    if (fm.mapped_points > 0) {
      results.parameters.push_back({"twisted_pair_points", double(fm.mapped_points), "1", std::nullopt});
      results.parameters.push_back({"twisted_pair_largest_distance", fm.largest_mapping_distance, "m", std::nullopt});
    }
  }
  const auto files = solver.field_files();
  for (std::size_t i = 0; i < files.size(); ++i)
    results.fields.emplace_back(i == 0 ? "pvd" : "step_" + std::to_string(i - 1), "fields/" + files[i]);
  std::vector<std::filesystem::path> inputs{options.parameter_file};
  if (!parameters.geometry.mesh_file.empty()) inputs.push_back(parameters.geometry.mesh_file);
  if (parameters.forming.enabled || parameters.forming.release_after_path) inputs.push_back(parameters.forming.axis_file);
  if (!parameters.forming.state_file.empty()) inputs.push_back(parameters.forming.state_file);
  if (!parameters.forming.twisted_pair_state.empty()) inputs.push_back(parameters.forming.twisted_pair_state);
  results.provenance = make_provenance(options.command_line, inputs);
  results.provenance.run_id = run_id;
  write_results(results, summary.results_h5);
  write_summary_json(out / "summary.json", guard, parameters.checks, run_id, std::nullopt, "");
  return summary;
}

RunSummary run_experiment_with_mpi(const RunOptions& options) {
  // MPI can be initialised only once per process, and a campaign runs several experiments in
  // one process: keep MPI and PETSc up until exit.
  static std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    static int argc = 1;
    static char name[] = "dtwire";
    static char* args[] = {name, nullptr};
    static char** argv = args;
    mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(argc, argv);
  }
  return run_experiment(options);
}

}  // namespace dtwire::fem
