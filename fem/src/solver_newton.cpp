#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1.h>
#include <petscksp.h>

#include <cmath>
#include <iomanip>
#include <sstream>

#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

// Newton-Raphson for one load step. The start is either the previous step's increment, scaled
// (`extrapolation`, within one load-path segment; boundary values set exactly), or the
// linearised predictor: iteration 0 applies the boundary increment through inhomogeneous
// constraints (as in deal.II step-44). Backtracking line search when the residual did not drop.
// Modified Newton (Tangent reuse contraction c > 0, direct solver): after an iteration that
// reduced the residual below c times the previous one, the next keeps the factorisation and
// assembles the residual only; a kept tangent whose step does not reduce the residual is
// abandoned (back to the step's start, fresh tangent there). Every load step starts fresh.
// Lagged LU (Linear solver = lagged-lu): every iteration assembles the tangent and solves with
// GMRES preconditioned by the last factorisation (direct_solver.hpp), an inexact Newton step.
bool WireSolver::Impl::solve_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                                  unsigned& iterations, std::string& reason) {
  applied_force = path_force(prm.load, t_new) / force_multiplier();
  make_constraints(predictor, t_old, t_new);
  const unsigned first_free = extrapolation ? 0 : 1;  // first iteration with homogeneous constraints
  if (extrapolation) {
    increment = *extrapolation;
    predictor.distribute(increment);
    solution.add(1.0, increment);
  }
  const double floor = 1e-14 * prm.material.young * prm.geometry.diameter * prm.geometry.diameter;
  PETScWrappers::MPI::Vector previous(owned, comm), previous_increment(owned, comm);
  double previous_residual = 0.0;
  const double reuse_below = prm.newton.krylov ? 0.0 : prm.newton.tangent_reuse_contraction;
  bool kept_tangent = false;  // this iteration solves with the last factorisation
  std::ostringstream history;
  history << std::scientific << std::setprecision(2);
  for (unsigned it = 0; it <= prm.newton.maximum_iterations; ++it) {
    const auto& constraints = it < first_free ? predictor : homogeneous;
    const bool stale_step = kept_tangent;  // the step that led here came from a kept tangent
    kept_tangent = kept_tangent && direct_solver.factorised();
    AssemblyOutcome a = assemble(!kept_tangent, constraints);
    if (stale_step && (!a.ok || a.residual > (1.0 - 1e-4) * previous_residual)) {
      history << " [fresh tangent]";
      solution = previous;
      kept_tangent = false;
      a = assemble(true, homogeneous);
    } else if (it > first_free && prm.newton.line_search && (!a.ok || a.residual > (1.0 - 1e-4) * previous_residual)) {
      double step = 1.0;
      for (unsigned ls = 0; ls < prm.newton.maximum_line_search_steps; ++ls) {
        step *= 0.5;
        solution = previous;
        solution.add(step, previous_increment);
        a = assemble(false, homogeneous);
        if (a.ok && a.residual < (1.0 - 1e-4 * step) * previous_residual) break;
      }
      history << " [line search " << step << "]";
      if (a.ok) a = assemble(true, homogeneous);
    }
    if (!a.ok) {
      reason = "inverted element or failed return mapping at iteration " + std::to_string(it);
      log << "    newton:" << history.str() << "\n";
      return false;
    }
    if (it >= first_free) {
      const double relative = a.residual / std::max(a.force_scale, floor);
      history << " " << relative;
      // Relative to the internal forces; the absolute floor (far above round-off, far below any
      // load of interest) ends steps in which no force builds up (rigid motion before contact).
      if (a.residual <= std::max(prm.newton.relative_tolerance * std::max(a.force_scale, floor), 1e-2 * floor)) {
        iterations = it;
        log << "    newton (relative residual):" << history.str() << "\n";
        return true;
      }
      if (it > first_free && a.residual > 1e6 * previous_residual) break;
    }
    Timer timer;
    try {
      if (prm.newton.krylov) {
        history << " (gmres " << solve_krylov() << ")";
      } else if (prm.newton.lagged_lu_iterations > 0) {
        // Forcing term a hundredth of the relative residual (an inexact Newton step keeps the
        // quadratic convergence, Dembo, Eisenstat & Steihaug 1982), no tighter than reaching the
        // Newton tolerance at the next iteration needs.
        const double relative = a.residual / std::max(a.force_scale, floor);
        const double forcing =
            std::min(1e-2, std::max(1e-2 * relative, 0.1 * prm.newton.relative_tolerance / relative));
        const unsigned gmres = direct_solver.solve_lagged(matrix, increment, rhs, forcing, prm.newton.lagged_lu_iterations);
        if (gmres > 0) history << "~" << gmres;
      } else if (kept_tangent) {
        history << "*";
        direct_solver.solve_again(increment, rhs);
      } else {
        direct_solver.solve(matrix, increment, rhs);
      }
    } catch (const std::exception& e) {
      reason = prm.newton.krylov ? std::string("Krylov solver failed: ") + e.what() : "direct solver failed";
      stats.solve_seconds += timer.wall_time();
      return false;
    }
    stats.solve_seconds += timer.wall_time();
    stats.factorisations = direct_solver.factorisations();
    constraints.distribute(increment);
    // Keep the tangent for the next iteration if this one contracted well enough.
    kept_tangent = reuse_below > 0.0 && it > first_free && a.residual < reuse_below * previous_residual;
    previous = solution;
    previous_increment = increment;
    previous_residual = a.residual;
    solution.add(1.0, increment);
  }
  reason = "no convergence in " + std::to_string(prm.newton.maximum_iterations) + " iterations";
  log << "    newton (relative residual):" << history.str() << "\n";
  return false;
}

// Rigid-body modes of the owned dofs from their support points, orthonormalised (PETSc's
// near-null-space contract) by modified Gram-Schmidt.
void WireSolver::Impl::make_rigid_body_modes() {
  std::map<types::global_dof_index, Point<3>> points_of;
  DoFTools::map_dofs_to_support_points(MappingQ1<3>(), dof_handler, points_of);
  std::array<IndexSet, 3> component;
  for (unsigned c = 0; c < 3; ++c) {
    std::vector<bool> mask(3, false);
    mask[c] = true;
    component[c] = DoFTools::extract_dofs(dof_handler, ComponentMask(mask));
  }
  rigid_body_modes.assign(6, PETScWrappers::MPI::Vector(owned, comm));
  for (const auto i : owned) {
    const Point<3>& x = points_of.at(i);
    unsigned c = 0;
    while (!component[c].is_element(i)) ++c;
    rigid_body_modes[c](i) = 1.0;                                                  // translations
    rigid_body_modes[3](i) = c == 0 ? -x[1] : c == 1 ? x[0] : 0.0;                 // rotation about z
    rigid_body_modes[4](i) = c == 1 ? -x[2] : c == 2 ? x[1] : 0.0;                 // about x
    rigid_body_modes[5](i) = c == 2 ? -x[0] : c == 0 ? x[2] : 0.0;                 // about y
  }
  for (unsigned m = 0; m < 6; ++m) {
    rigid_body_modes[m].compress(VectorOperation::insert);
    for (unsigned k = 0; k < m; ++k) rigid_body_modes[m].add(-(rigid_body_modes[m] * rigid_body_modes[k]), rigid_body_modes[k]);
    rigid_body_modes[m] /= rigid_body_modes[m].l2_norm();
  }
}

unsigned WireSolver::Impl::solve_krylov() {
  const auto check = [](PetscErrorCode code) {
    if (code != 0) throw std::runtime_error("PETSc error " + std::to_string(code));
  };
  std::vector<Vec> modes;
  for (const auto& v : rigid_body_modes) modes.push_back(v);
  MatNullSpace near_null_space;
  check(MatNullSpaceCreate(comm, PETSC_FALSE, static_cast<PetscInt>(modes.size()), modes.data(), &near_null_space));
  check(MatSetNearNullSpace(matrix, near_null_space));
  KSP ksp;
  check(KSPCreate(comm, &ksp));
  check(KSPSetOperators(ksp, matrix, matrix));
  check(KSPSetType(ksp, KSPGMRES));
  check(KSPGMRESSetRestart(ksp, 200));
  check(KSPSetTolerances(ksp, prm.newton.linear_tolerance, 0.0, PETSC_DEFAULT,
                         static_cast<PetscInt>(prm.newton.maximum_linear_iterations)));
  PC pc;
  check(KSPGetPC(ksp, &pc));
  check(PCSetType(pc, PCGAMG));
  check(KSPSolve(ksp, rhs, increment));
  KSPConvergedReason converged;
  PetscInt iterations = 0;
  check(KSPGetConvergedReason(ksp, &converged));
  check(KSPGetIterationNumber(ksp, &iterations));
  check(KSPDestroy(&ksp));
  check(MatNullSpaceDestroy(&near_null_space));
  if (converged < 0)
    throw std::runtime_error("GMRES did not converge (reason " + std::to_string(converged) + ") in " +
                             std::to_string(iterations) + " iterations");
  return static_cast<unsigned>(iterations);
}

// ---- contact (issue 5) ----
// Augmented Lagrangian by Uzawa iterations around Newton (Simo & Laursen 1992): after each
// converged solve the multipliers take the converged pressures and the step is solved again
// from its start (the converged increment as predictor), until the largest penetration is
// below the gap tolerance or the augmentation budget is spent. Friction history stays at the
// committed state throughout.
bool WireSolver::Impl::solve_contact_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                                          const PETScWrappers::MPI::Vector& start, unsigned& iterations,
                                          std::string& reason) {
  refresh_relevant_values();  // the committed state (after a cut-back too)
  contact::StepStart step;
  step.t_old = t_old;
  step.t_new = t_new;
  step.relevant_values = &relevant_values;
  step.top_motion = contact::top_end_motion(prm.load, load_direction, rotation_centre, t_new);
  step.extrapolated = extrapolation != nullptr;
  bool new_pairs = false;
  for (const auto& part : contact_parts) new_pairs = part->begin_step(step) || new_pairs;
  if (new_pairs) {
    log << "    wire contact: new candidate pairs, matrix pattern rebuilt\n";
    make_matrix();
  }
  if (!solve_step(t_old, t_new, extrapolation, iterations, reason)) return false;
  PETScWrappers::MPI::Vector converged(owned, comm);
  const auto augment = [&]() {  // every part updates its multipliers (no short-circuit)
    bool again = false;
    for (const auto& part : contact_parts) again = part->augment() || again;
    return again;
  };
  while (augment()) {
    converged = solution;
    converged -= start;
    solution = start;
    unsigned more = 0;
    unsigned augmentations = 0;
    for (const auto& part : contact_parts) augmentations = std::max(augmentations, part->augmentations());
    log << "    augmentation " << augmentations << "\n";
    if (!solve_step(t_old, t_new, &converged, more, reason)) return false;
    iterations += more;
  }
  return true;
}
// ---- end contact ----

}  // namespace dtwire::fem
