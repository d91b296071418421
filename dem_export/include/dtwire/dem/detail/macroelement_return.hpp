#pragma once
// Implicit (backward-Euler) plastic update of the macro-element: the closest-point return of
// Simo & Hughes (1998, "Computational Inelasticity", ch. 3, boxes 3.1-3.2; non-associated flow as
// in their section 3.6), used by macro3d instead of the explicit RK2(3) substepping of Sloan (1987)
// and Sloan, Abbo & Sheng (2001) (macroelement_integrator.hpp), which stays the fallback.
//
// For one plastic increment dq = (du, dw_1, dw_2) from a state on (or inside) the surface:
//   Q_trial = Q_n + K dq,                                  K = diag(k_a, k_m, k_m)
//   Q = Q_trial - K dlambda g(Q, N_y)                      (flow evaluated at the END state)
//   z = z_n + dlambda (k_F |g_F| + k_M |g_M|),   N_y = N_0 + (1 - e^-z)(N_ult - N_0)
//   f(Q, N_y) = 0
// with z = k_F a_u + k_M a_w the hardening exponent. The flow's moment part is c M (c a constant
// once the compression branch is scaled, below), so M = M_trial / (1 + k_m c dlambda) is parallel
// to the trial moment and the system reduces to three unknowns (N, z, dlambda), solved by Newton
// with the analytical 3x3 Jacobian. In compression the flow is multiplied by kappa = N_y^2 m_f
// (only the multiplier's scale changes, dlambda absorbs it): then c = 2 rotation_flow_scale / D^2
// on both branches and the flow is continuous at N = 0, so an iteration may cross N = 0.
//
// Backward Euler is first-order accurate in the increment and unconditionally stable: the stiff
// axial flow of the published potential at low axial force (m_g h (2F - ...), ~76 F for the
// single wire) needs ~100 explicit substeps per DEM increment but one implicit step.
#include <array>

#include "dtwire/dem/detail/macroelement_surface.hpp"

namespace dtwire::dem::detail {

struct PlasticState;
struct ElasticStiffness;

struct ReturnSettings {
  int max_iterations = 8;
  double residual_tolerance = 1e-10;  // on f (normalised), on the axial flow residual / N_y, on z
};

// Returns the state after the increment dq from `start` (whose N_y must be current) in `end` and
// true when the elastic trial is inside or on the surface (then `end` is the trial, with its f)
// or when Newton converged within max_iterations to a non-negative multiplier; false (and `end`
// untouched) otherwise. Convergence: the largest of |f|, |R_N| / N_y and |R_z| / max(1, z_n) is
// below residual_tolerance, or the quadratic rate observed over the last two Newton iterations
// predicts it below after the step just computed (which is then taken). The end state is on the
// surface to residual_tolerance; its plastic displacements are the elastic complements
// (du_p = (N_trial - N) / k_a, ...), so that Q_1 - Q_0 = K (dq - dq_p) holds to round-off, which
// the energy bookkeeping relies on.
// `iterations` (optional) receives the residual evaluations after the trial's. With `use_hint`
// Newton starts from start.return_hint (the last return scaled by the trial f) instead of the
// trial; the solution is the same to the tolerance. start.h_cache / h_exponent carry the last
// value of the surface's exponential, so that most returns call no libm exponential at all.
bool closest_point_return(const SurfaceParameters& p, const ElasticStiffness& k, const ReturnSettings& settings,
                          const PlasticState& start, const std::array<double, 3>& dq, PlasticState& end,
                          int* iterations = nullptr, bool use_hint = true);

}  // namespace dtwire::dem::detail
