#include "dtwire/dem/yield_surface.hpp"

#include <cmath>
#include <stdexcept>

#include "dtwire/dem/macro3d.hpp"
#include "dtwire/dem/thesis_macroelement.hpp"
#include "macroelement_reading.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The surface exactly as the law builds it: the law is constructed first so that its parameter
// checks (and macro3d's compressive-strength cap under bending-axial coupling) apply.
detail::SurfaceParameters surface_of(const std::string& law, const ParameterMap& given) {
  if (law == "thesis") {
    const ThesisMacroElement element(given);
    return detail::read_surface(given, law, "k_F", "k_M", 1.0);
  }
  if (law == "macro3d") {
    const Macro3dLaw element(given);  // the given map: the conversion below drops reference_length_m
    const ParameterMap p = given.count("EA_N") ? macro3d_parameters_from_thesis(given) : given;
    detail::SurfaceParameters s = detail::read_surface(p, law, "k_F_per_m", "k_M_per_rad", 1.0);
    detail::read_moment_hardening(p, law, s);
    s.Nc = element.compressive_strength();
    s.prepare();
    return s;
  }
  throw std::invalid_argument("yield surface: law '" + law + "' has no N-M yield surface (expected thesis or macro3d)");
}

}  // namespace

YieldSurfaceCurve yield_surface_curve(const std::string& law, const ParameterMap& parameters,
                                      double yield_strength_N, int points) {
  if (points < 3) throw std::invalid_argument("yield surface: at least 3 points");
  if (!(yield_strength_N > 0.0) || !std::isfinite(yield_strength_N))
    throw std::invalid_argument("yield surface: the yield strength must be > 0");
  const detail::SurfaceParameters s = surface_of(law, parameters);
  YieldSurfaceCurve curve;
  curve.yield_strength_N = yield_strength_N;
  // f is affine in M^2 at fixed F: f = f(F, 0) + c M^2, c = f(F, 1) - f(F, 0) > 0.
  // Cosine spacing in F puts more points near the two tips, where M changes fastest.
  for (int i = 0; i < points; ++i) {
    const double t = 0.5 * (1.0 - std::cos(kPi * i / (points - 1)));
    const double F = i == points - 1 ? yield_strength_N : -s.Nc + t * (s.Nc + yield_strength_N);  // exact tips
    const double f0 = detail::yield_function(s, F, 0.0, yield_strength_N);
    const double c = detail::yield_function(s, F, 1.0, yield_strength_N) - f0;
    const double M2 = f0 < 0.0 ? -f0 / c : 0.0;
    curve.axial_force_N.push_back(F);
    curve.moment_Nm.push_back(std::sqrt(M2));
  }
  return curve;
}

std::vector<YieldSurfaceCurve> initial_and_ultimate_yield_surfaces(const std::string& law,
                                                                   const ParameterMap& parameters, int points) {
  const detail::SurfaceParameters s = surface_of(law, parameters);
  return {yield_surface_curve(law, parameters, s.N0, points), yield_surface_curve(law, parameters, s.Nult, points)};
}

}  // namespace dtwire::dem
