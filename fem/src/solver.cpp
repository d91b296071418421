#include "solver.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>

#include "dtwire/core/error.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

WireSolver::WireSolver(const Parameters& parameters, std::ostream& log, std::filesystem::path field_directory)
    : impl_(std::make_unique<Impl>(parameters, log, std::move(field_directory))) {
  impl_->setup();
}

WireSolver::~WireSolver() = default;

const SolverStatistics& WireSolver::statistics() const { return impl_->stats; }
const GeometryParameters& WireSolver::geometry() const { return impl_->prm.geometry; }
bool WireSolver::is_root() const { return Utilities::MPI::this_mpi_process(impl_->comm) == 0; }
std::vector<std::string> WireSolver::field_files() const {
  auto files = impl_->written_fields;
  if (!files.empty()) files.insert(files.begin(), "fields.pvd");
  return files;
}

void WireSolver::set_as_made_output(const std::filesystem::path& file) { impl_->as_made_output = file; }
void WireSolver::set_twisted_pair_output(const std::filesystem::path& file) { impl_->twisted_pair_output = file; }

void WireSolver::run(const std::function<void(const StepRecord&)>& on_step) {
  Impl& s = *impl_;
  const auto& stepping = s.prm.stepping;
  const auto& path = s.prm.load.path;
  const double t_end = path.back().first;
  const double tiny = 1e-12 * t_end;

  const unsigned interval = s.prm.output.fields ? s.prm.output.field_interval : 0;
  double t = 0.0, dt = stepping.initial_step;
  unsigned step = 0;
  PETScWrappers::MPI::Vector saved(s.owned, s.comm), last_step(s.owned, s.comm), scaled(s.owned, s.comm);
  double last_dt = 0.0, last_knot = -1.0;
  bool retry = false;
  // After a step in which the failure indicator is at or past 1: logs it and tells whether the run
  // stops. Without softening the indicator's first reaching 1 is the failure; with softening the
  // cracked points lose their stress and the run stops when the force has fallen to the stop
  // fraction of its peak (a tensile machine's break detection).
  const auto stop_after_failure = [&s](const StepRecord& record) {
    const bool first = s.history.size() < 2 || s.history[s.history.size() - 2].damage < 1.0;
    if (first)
      s.log << "  ductile failure indicator reached " << record.damage << " at z = " << record.damage_z * 1e3
            << " mm, r = " << record.damage_r * 1e3 << " mm (triaxiality " << record.damage_triaxiality
            << ", Lode parameter " << record.damage_lode << ")\n";
    if (!s.prm.material.stop_at_failure) return false;
    if (!s.prm.material.failure.softens()) {
      s.log << "  stopping at failure (Stop at failure = true)\n";
      return true;
    }
    double peak = 0.0;
    for (const auto& r : s.history) peak = std::max(peak, std::abs(r.force));
    if (std::abs(record.force) > s.prm.material.stop_force_fraction * peak) return false;
    s.log << "  the force fell to " << std::abs(record.force) << " N, at most " << s.prm.material.stop_force_fraction
          << " of its peak " << peak << " N: stopping after the fracture (Failure stop force fraction)\n";
    return true;
  };
  s.log << std::setprecision(6);
  StepRecord record;
  if (s.restart_step >= 0) {
    Impl::SteppingState state;
    s.read_checkpoint(static_cast<unsigned>(s.restart_step), state, last_step);
    s.update_nonlocal_indicator();  // not in the checkpoint: it follows from the committed D
    t = state.t;
    dt = state.dt;
    step = state.step;
    last_dt = state.last_dt;
    last_knot = state.last_knot;
    s.assemble(false, s.homogeneous);  // stresses for output; the committed history stays as read
    for (const auto& r : s.history) on_step(r);
    record = s.history.back();
    s.log << "restarted from the checkpoint of step " << step << " at t = " << t << "\n";
  } else {
    if (!s.prm.forming.state_file.empty()) {  // as made, as an earlier run left it
      s.read_as_made_state(s.prm.forming.state_file);
    } else if (s.prm.forming.enabled) {  // as made: formed, then sprung back (solver_forming.cpp)
      s.apply_forming_history();
      s.release_forming();
      if (!s.as_made_output.empty()) s.write_as_made_state(s.as_made_output);
    }
    s.assemble(false, s.homogeneous);  // initial state (stress-free unless as made), fills the field records
    s.commit();
    record.plastic_dissipation = s.dissipation * s.force_multiplier() * s.length_multiplier();
    record.elastic_energy = s.elastic_energy * s.force_multiplier() * s.length_multiplier();
    record.neck_radius = s.neck_radius();
    s.record_contact_parts(record, false);
    s.record_end(record);
    s.record_probes(record);
    on_step(record);
    s.history.push_back(record);
    if (interval > 0) s.write_fields(0, 0.0);
  }
  while (t < t_end - tiny) {
    double knot = t_end;
    for (const auto& p : path)
      if (p.first > t + tiny) { knot = p.first; break; }
    double dt_try = std::min(dt, knot - t);
    if (knot - (t + dt_try) < 1e-3 * dt_try) dt_try = knot - t;  // no sliver step before a knot
    saved = s.solution;
    unsigned iterations = 0;
    std::string reason;
    s.log << "step " << step + 1 << ": t = " << t << " -> " << t + dt_try << " (dt = " << dt_try
          << "), top " << (s.prm.load.force_control ? "force " : "displacement ")
          << (s.prm.load.force_control ? path_force(s.prm.load, t + dt_try) : path_displacement(s.prm.load, t + dt_try) * 1e3)
          << (s.prm.load.force_control ? " N\n" : " mm\n");
    // Extrapolate the previous increment only inside the same load-path segment, not on a retry.
    const bool extrapolate = !retry && last_dt > 0.0 && knot == last_knot;
    if (extrapolate) {
      scaled = last_step;
      scaled *= dt_try / last_dt;
    }
    if (s.solve_contact_step(t, t + dt_try, extrapolate ? &scaled : nullptr, saved, iterations, reason)) {
      s.commit();
      last_step = s.solution;
      last_step -= saved;
      last_dt = dt_try;
      last_knot = knot;
      retry = false;
      t = std::abs(t + dt_try - knot) <= tiny ? knot : t + dt_try;
      ++step;
      ++s.stats.steps;
      s.stats.newton_iterations += iterations;
      record.step = step;
      record.time = t;
      record.displacement = (s.prm.load.force_control ? s.ghosted[s.force_dof] : path_displacement(s.prm.load, t)) *
                            s.length_multiplier();
      record.force = s.reaction();
      record.plastic_dissipation = s.dissipation * s.force_multiplier() * s.length_multiplier();
      record.elastic_energy = s.elastic_energy * s.force_multiplier() * s.length_multiplier();
      record.neck_radius = s.neck_radius();
      record.iterations = iterations;
      s.record_damage(record);
      s.record_contact_parts(record, true);
      s.record_end(record);
      s.record_probes(record);
      s.log << "  converged in " << iterations << " iteration(s): force " << record.force << " N, neck radius "
            << record.neck_radius * 1e3 << " mm" << std::endl;  // flushed: progress of long runs
      s.log_junction_state();
      on_step(record);
      s.history.push_back(record);
      if (interval > 0 && step % interval == 0) s.write_fields(step, t);
      if (s.prm.material.failure.enabled() && record.damage >= 1.0 && stop_after_failure(record)) break;
      if (iterations <= stepping.easy_iterations && dt < stepping.maximum_step) {
        const double grown = std::min(stepping.maximum_step, dt * stepping.growth_factor);
        s.log << "  easy step (" << iterations << " <= " << stepping.easy_iterations << " iterations): dt "
              << dt << " -> " << grown << "\n";
        dt = grown;
      }
      if (s.checkpoint_interval > 0 && step % s.checkpoint_interval == 0)
        s.write_checkpoint({t, dt, last_dt, last_knot, step}, last_step);
    } else {
      s.solution = saved;
      retry = true;
      ++s.stats.cutbacks;
      const double reduced = dt_try * stepping.cutback_factor;
      s.log << "  step failed (" << reason << "): cut back dt " << dt_try << " -> " << reduced << std::endl;
      if (reduced < stepping.minimum_step && s.prm.material.failure.softens() && s.history.back().damage >= 1.0) {
        // A crack that releases more elastic energy than it dissipates snaps back: no static
        // state follows the last one. The curve up to it is the answer; the log says why it ends.
        s.log << "  dt below the minimum step " << stepping.minimum_step << " after the failure indicator reached 1: "
              << "no static state follows the crack (snap-back); the curve ends at t = " << t << "\n";
        s.stats.ended_in_snap_back = true;
        break;
      }
      if (reduced < stepping.minimum_step) {
        s.log << "  dt below the minimum step " << stepping.minimum_step << ": giving up at t = " << t << "\n";
        throw ComputationError("load stepping failed at pseudo-time " + std::to_string(t) + " (" + reason +
                               "; step below the minimum " + std::to_string(stepping.minimum_step) + ")");
      }
      dt = reduced;
    }
  }
  bool fields_due = interval == 0 || step % interval != 0;
  if (s.prm.forming.release_after_path) {  // the twisting head lets go (solver_forming.cpp)
    s.log << "release: the top grips let go (As made/Release after path)\n";
    s.release_top_end();
    s.stats.forming.after_path = true;
    if (!s.twisted_pair_output.empty()) s.write_twisted_pair_state(s.twisted_pair_output);
    if (interval > 0) s.write_fields(step + 1, t + 1.0);  // the released state, at pseudo-time t_end + 1
    fields_due = false;
  }
  if (s.prm.output.fields && fields_due) s.write_fields(step, t);
}

}  // namespace dtwire::fem
