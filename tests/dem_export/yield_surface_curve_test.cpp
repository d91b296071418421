// The N-M yield-surface curves (dtwire/dem/yield_surface.hpp) against the published surface
// written out independently (law_test_support.hpp), the closed-form moment capacity and the
// first yield of the laws themselves on radial paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dtwire/dem/macro3d.hpp"
#include "dtwire/dem/thesis_macroelement.hpp"
#include "dtwire/dem/yield_surface.hpp"
#include "law_test_support.hpp"

namespace dtwire::dem {
namespace {

// Linear interpolation of the curve's moment at axial force F.
double moment_at(const YieldSurfaceCurve& curve, double F) {
  const auto& x = curve.axial_force_N;
  const auto upper = std::upper_bound(x.begin(), x.end(), F);
  if (upper == x.begin() || upper == x.end()) throw std::out_of_range("F outside the curve");
  const std::size_t i = static_cast<std::size_t>(upper - x.begin());
  const double t = (F - x[i - 1]) / (x[i] - x[i - 1]);
  return (1.0 - t) * curve.moment_Nm[i - 1] + t * curve.moment_Nm[i];
}

TEST(YieldSurfaceCurve, EveryPointIsOnThePublishedSurface) {
  for (const char* wire : {"single_wire", "double_twist"}) {
    SCOPED_TRACE(wire);
    const ParameterMap p = test::thesis_parameters(wire);
    const auto curves = initial_and_ultimate_yield_surfaces("thesis", p, 201);
    ASSERT_EQ(curves.size(), 2u);
    EXPECT_DOUBLE_EQ(curves[0].yield_strength_N, p.at("N0_N"));
    EXPECT_DOUBLE_EQ(curves[1].yield_strength_N, p.at("Nult_N"));
    for (const YieldSurfaceCurve& curve : curves) {
      EXPECT_DOUBLE_EQ(curve.axial_force_N.front(), -p.at("Nc_N"));
      EXPECT_DOUBLE_EQ(curve.axial_force_N.back(), curve.yield_strength_N);
      // Tips: M = 0 (tol: round-off of f ~ 1e-16 becomes sqrt(1e-16) ~ 1e-8 relative in M).
      const double capacity = p.at("D_m") * std::sqrt(p.at("m_f")) * curve.yield_strength_N;
      EXPECT_NEAR(curve.moment_Nm.front(), 0.0, 1e-7 * capacity);
      EXPECT_NEAR(curve.moment_Nm.back(), 0.0, 1e-7 * capacity);
      for (std::size_t i = 0; i < curve.axial_force_N.size(); ++i)
        EXPECT_NEAR(test::published_surface(p, curve.axial_force_N[i], curve.moment_Nm[i], curve.yield_strength_N), 0.0,
                    1e-12);  // tol: round-off
      // Closed form at F = 0: M = D sqrt(m_f) N_y (tol: linear interpolation over 201 points).
      EXPECT_NEAR(moment_at(curve, 0.0), capacity, 1e-3 * capacity);
    }
  }
}

// The thesis law on radial (u, theta) paths: its first plastic state lies on the curve drawn at
// that state's N_y (tol 0.2 %: interpolation over 2001 points and the RK return's drift).
TEST(YieldSurfaceCurve, TheLawFirstYieldsOnTheCurve) {
  const ParameterMap p = test::thesis_parameters("double_twist");
  const double k_axial = p.at("EA_N"), k_moment = p.at("EI_Nm2_per_deg_convention") * 180.0 / test::pi;
  const double capacity = p.at("D_m") * std::sqrt(p.at("m_f")) * p.at("N0_N");
  for (const double angle_deg : {-120.0, -45.0, 10.0, 45.0, 80.0}) {
    SCOPED_TRACE(angle_deg);
    ThesisMacroElement law(p);
    const double a = angle_deg * test::pi / 180.0;
    const auto path = test::pull_spin(1.5 * p.at("N0_N") / k_axial * std::cos(a), 1.5 * capacity / k_moment * std::sin(a), 3000);
    bool checked = false;
    test::run(law, path, [&](std::size_t) {
      if (checked || (law.plastic_elongation() == 0.0 && law.plastic_rotation() == 0.0)) return;
      checked = true;
      const Vector6 q = law.forces();
      const YieldSurfaceCurve curve = yield_surface_curve("thesis", p, law.yield_strength(), 2001);
      EXPECT_NEAR(std::abs(q[4]), moment_at(curve, q[0]), 2e-3 * capacity);
    });
    EXPECT_TRUE(checked);
  }
}

TEST(YieldSurfaceCurve, Macro3dMatchesTheThesisAndSplitsTheMomentHardening) {
  ParameterMap p = test::thesis_parameters("double_twist");
  const auto thesis = initial_and_ultimate_yield_surfaces("thesis", p, 101);
  const auto same = initial_and_ultimate_yield_surfaces("macro3d", p, 101);
  for (int s = 0; s < 2; ++s)
    for (std::size_t i = 0; i < thesis[s].moment_Nm.size(); ++i)
      EXPECT_NEAR(same[s].moment_Nm[i], thesis[s].moment_Nm[i], 1e-12 * (1.0 + thesis[s].moment_Nm[i]));
  // r_M = 1: the moment capacity stays D sqrt(m_f) N0 while the axial strength hardens to Nult.
  p["moment_hardening_ratio"] = 1.0;
  const auto split = initial_and_ultimate_yield_surfaces("macro3d", p, 201);
  const double capacity0 = p.at("D_m") * std::sqrt(p.at("m_f")) * p.at("N0_N");
  EXPECT_NEAR(moment_at(split[1], 0.0), capacity0, 1e-3 * capacity0);
  EXPECT_DOUBLE_EQ(split[1].axial_force_N.back(), p.at("Nult_N"));
  // With the bending-axial coupling (it needs the bond length, which a thesis-keyed map carries):
  // Nc is capped at 0.9 k_m / (2 c), c = kappa L / 24, as the law caps it.
  p["bending_axial_coupling"] = 40.0;
  const auto coupled = initial_and_ultimate_yield_surfaces("macro3d", p, 51);
  const double k_m = p.at("EI_Nm2_per_deg_convention") * 180.0 / test::pi;
  const double cap = 0.9 * k_m / (2.0 * 40.0 * p.at("reference_length_m") / 24.0);
  ASSERT_LT(cap, p.at("Nc_N"));
  EXPECT_NEAR(coupled[0].axial_force_N.front(), -cap, 1e-9 * cap);
}

TEST(YieldSurfaceCurve, RejectsOtherLawsAndBadArguments) {
  const ParameterMap p = test::thesis_parameters("single_wire");
  EXPECT_THROW(yield_surface_curve("wirepm", p, 1000.0, 50), std::invalid_argument);
  EXPECT_THROW(yield_surface_curve("thesis", p, 1000.0, 2), std::invalid_argument);
  EXPECT_THROW(yield_surface_curve("thesis", p, -1.0, 50), std::invalid_argument);
  ParameterMap broken = p;
  broken.erase("m_f");
  EXPECT_THROW(yield_surface_curve("thesis", broken, 1000.0, 50), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::dem
