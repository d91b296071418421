#pragma once
// The macro-element's yield surface in the N-M plane (thesis and macro3d share it;
// detail/macroelement_surface.hpp), traced as a curve for plots against FE envelopes: at a
// given yield strength N_y the moment M(F) >= 0 on f(F, M, N_y) = 0 for F from -Nc to N_y
// (the surface is symmetric in M). N_y = N0 gives the initial yield surface, N_y = Nult the
// fully hardened one, the largest the element can reach before damage (Previtali thesis;
// docs/dem_laws.md). Units: F in N, M in N m, as the laws' forces.
#include <string>
#include <vector>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

struct YieldSurfaceCurve {
  double yield_strength_N = 0.0;
  std::vector<double> axial_force_N;  // increasing, from -Nc to N_y
  std::vector<double> moment_Nm;      // >= 0; 0 at both ends
};

// `law`: "thesis" or "macro3d" (thesis-keyed maps are converted as the law converts them).
// Throws std::invalid_argument for another law, bad parameters, points < 3 or N_y <= 0.
YieldSurfaceCurve yield_surface_curve(const std::string& law, const ParameterMap& parameters,
                                      double yield_strength_N, int points);

// The initial (N_y = N0) and fully hardened (N_y = Nult) curves of a parameter set.
std::vector<YieldSurfaceCurve> initial_and_ultimate_yield_surfaces(const std::string& law,
                                                                   const ParameterMap& parameters, int points);

}  // namespace dtwire::dem
