// Material-point verification of the J2 log-strain plasticity (label verification):
// homogeneous uniaxial bar past yield vs the closed form for every hardening law, plastic
// incompressibility (J_p = 1), unloading, and the algorithmic tangent vs finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>

#include "j2_log_plasticity.hpp"

namespace dtwire::fem {
namespace {

constexpr double kE = 206.9e9, kNu = 0.29;

HardeningParameters law(HardeningLaw which) {
  HardeningParameters p;
  p.law = which;
  switch (which) {
    case HardeningLaw::linear:
      p.yield_stress = 450e6;
      p.linear_modulus = 1.2e9;
      break;
    case HardeningLaw::voce:  // Simo (1992) necking benchmark
      p.yield_stress = 450e6;
      p.saturation_stress = 715e6;
      p.saturation_rate = 16.93;
      p.linear_modulus = 129.24e6;
      break;
    case HardeningLaw::swift:
      p.swift_coefficient = 900e6;
      p.swift_offset = 0.01;
      p.swift_exponent = 0.2;
      break;
    case HardeningLaw::table:
      p.table_plastic_strain = {0.0, 0.02, 0.05, 0.2};
      p.table_stress = {400e6, 480e6, 530e6, 600e6};
      break;
  }
  return p;
}

J2LogPlasticity model(HardeningLaw which) {
  return J2LogPlasticity(ElasticParameters{kE, kNu}, IsotropicHardening(law(which)));
}

// Uniaxial stress: F = diag(lambda, mu, mu), mu from tau_22 = 0 by Newton with the tangent.
StressUpdate uniaxial(const J2LogPlasticity& m, double lambda, const PlasticState& state, double& mu,
                      double cell_size = 0.0) {
  for (int it = 0; it < 50; ++it) {
    Tensor2 F;
    F[0][0] = lambda;
    F[1][1] = F[2][2] = mu;
    const StressUpdate r = m.update(F, state, true, cell_size);
    const double residual = r.first_piola[1][1];
    if (std::abs(residual) < 1e-2) return r;  // Pa: round-off of K * eps (1.6e11 * 1e-16) ~ 1e-5
    mu -= residual / (r.tangent[1][1][1][1] + r.tangent[1][1][2][2]);
  }
  ADD_FAILURE() << "lateral stress iteration did not converge";
  return {};
}

// Closed form of the homogeneous bar in Hencky plasticity: the axial log strain is
// ln(lambda) = alpha + sigma_y(alpha)/E and the axial Kirchhoff stress tau = sigma_y(alpha).
double closed_form_alpha(const IsotropicHardening& h, double log_stretch) {
  double lo = 0.0, hi = log_stretch;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mid + h.flow_stress(mid) / kE > log_stretch ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

class HomogeneousBar : public ::testing::TestWithParam<HardeningLaw> {};

TEST_P(HomogeneousBar, TensionPastYieldMatchesClosedFormThenUnloadsElastically) {
  const J2LogPlasticity m = model(GetParam());
  PlasticState state;
  double mu = 1.0;
  const int steps = 40;
  const double max_log_strain = 0.25;
  for (int n = 1; n <= steps; ++n) {
    const double log_stretch = max_log_strain * n / steps;
    const StressUpdate r = uniaxial(m, std::exp(log_stretch), state, mu);
    state = r.state;
    if (log_stretch < m.hardening().flow_stress(0.0) / kE) continue;  // still elastic
    const double alpha = closed_form_alpha(m.hardening(), log_stretch);
    // Tolerances: the closed form is exact, so only round-off and the 1e-6 Pa lateral
    // equilibrium tolerance remain.
    EXPECT_NEAR(state.equivalent_plastic_strain, alpha, 1e-10) << "step " << n;
    EXPECT_NEAR(r.kirchhoff[0][0], m.hardening().flow_stress(alpha), 1e-8 * r.kirchhoff[0][0]) << "step " << n;
    // Plastic volume preservation: J_p = det(Cp^-1)^(-1/2) = 1.
    const double Jp = 1.0 / std::sqrt(dealii::determinant(state.plastic_metric_inverse));
    EXPECT_NEAR(Jp, 1.0, 1e-12) << "step " << n;
  }
  // Unloading by 0.1 % axial log strain: elastic, tau drops by E * 0.001, alpha frozen.
  const double alpha_max = state.equivalent_plastic_strain;
  const StressUpdate r = uniaxial(m, std::exp(max_log_strain - 1e-3), state, mu);
  EXPECT_EQ(r.plastic_increment, 0.0);
  EXPECT_NEAR(r.kirchhoff[0][0], m.hardening().flow_stress(alpha_max) - kE * 1e-3, 1e-6 * kE * 1e-3);
}

std::string law_name(const ::testing::TestParamInfo<HardeningLaw>& info) {
  const char* names[] = {"linear", "voce", "swift", "table"};
  return names[static_cast<int>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(EveryHardeningLaw, HomogeneousBar,
                         ::testing::Values(HardeningLaw::linear, HardeningLaw::voce, HardeningLaw::swift,
                                           HardeningLaw::table),
                         law_name);

double relative_tangent_error(const J2LogPlasticity& m, const Tensor2& F, const PlasticState& state,
                              double cell_size = 0.0) {
  const StressUpdate r = m.update(F, state, true, cell_size);
  const double h = 1e-6;
  double err2 = 0.0, ref2 = 0.0;
  for (unsigned k = 0; k < 3; ++k)
    for (unsigned l = 0; l < 3; ++l) {
      Tensor2 Fp = F, Fm = F;
      Fp[k][l] += h;
      Fm[k][l] -= h;
      const Tensor2 dP =
          (m.update(Fp, state, false, cell_size).first_piola - m.update(Fm, state, false, cell_size).first_piola) / (2 * h);
      for (unsigned i = 0; i < 3; ++i)
        for (unsigned j = 0; j < 3; ++j) {
          err2 += std::pow(dP[i][j] - r.tangent[i][j][k][l], 2);
          ref2 += std::pow(r.tangent[i][j][k][l], 2);
        }
    }
  return std::sqrt(err2 / ref2);
}

class ConsistentTangent : public ::testing::TestWithParam<HardeningLaw> {};

TEST_P(ConsistentTangent, MatchesCentralFiniteDifferences) {
  const J2LogPlasticity m = model(GetParam());
  // A non-proportional history: stretch and shear, then a general F in a plastic step.
  PlasticState state;
  Tensor2 F1 = dealii::unit_symmetric_tensor<3>();
  F1[0][0] = 1.03;
  F1[1][1] = F1[2][2] = 0.985;
  F1[0][1] = 0.02;
  state = m.update(F1, state, false).state;
  ASSERT_GT(state.equivalent_plastic_strain, 0.0);
  Tensor2 F2 = F1;
  F2[1][2] = 0.03;
  F2[2][0] = -0.015;
  F2[0][0] = 1.05;
  const StressUpdate plastic = m.update(F2, state, false);
  ASSERT_GT(plastic.plastic_increment, 0.0);
  // Relative error of the algorithmic tangent; tolerance 1e-6 (central differences, h = 1e-6).
  EXPECT_LT(relative_tangent_error(m, F2, state), 1e-6);
  // Elastic step (unloading toward F1 from the plastic state) and the undeformed state.
  Tensor2 F3 = F1;
  F3[0][0] = 1.045;
  const PlasticState after = plastic.state;
  Tensor2 F_unload = F2;
  F_unload[0][0] -= 0.002;
  ASSERT_EQ(m.update(F_unload, after, false).plastic_increment, 0.0);
  EXPECT_LT(relative_tangent_error(m, F_unload, after), 1e-6);
  EXPECT_LT(relative_tangent_error(m, dealii::unit_symmetric_tensor<3>(), PlasticState{}), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(EveryHardeningLaw, ConsistentTangent,
                         ::testing::Values(HardeningLaw::linear, HardeningLaw::voce, HardeningLaw::swift,
                                           HardeningLaw::table),
                         law_name);

TEST(StressInvariants, UniaxialTensionHasTriaxialityOneThirdAndLodeOne) {
  SymTensor2 sigma;
  sigma[0][0] = 100.0;
  const StressInvariants inv = stress_invariants(sigma);
  EXPECT_NEAR(inv.von_mises, 100.0, 1e-12);
  EXPECT_NEAR(inv.triaxiality, 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(inv.lode_parameter, 1.0, 1e-12);
}

TEST(Hardening, RejectsNonIncreasingTable) {
  HardeningParameters p = law(HardeningLaw::table);
  p.table_plastic_strain[2] = p.table_plastic_strain[1];
  EXPECT_THROW(IsotropicHardening{p}, std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::fem

namespace dtwire::fem {
namespace {

// Johnson-Cook indicator in uniaxial tension (triaxiality 1/3 throughout): D = alpha / eps_f(1/3).
TEST(FailureIndicator, UniaxialDamageIsPlasticStrainOverStrainToFailure) {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = 400e6;
  h.linear_modulus = 1e9;
  const FailureParameters jc{0.05, 3.44, -2.12};
  const J2LogPlasticity m(ElasticParameters{200e9, 0.3}, IsotropicHardening(h), jc);
  PlasticState state;
  double mu = 1.0;
  for (int n = 1; n <= 20; ++n) state = uniaxial(m, std::exp(0.01 * n), state, mu).state;
  const double strain_to_failure = 0.05 + 3.44 * std::exp(-2.12 / 3.0);
  // Tolerance: the lateral-equilibrium iteration leaves eta = 1/3 to ~1e-10.
  EXPECT_NEAR(state.damage, state.equivalent_plastic_strain / strain_to_failure, 1e-9);
}

// Shear branch (symmetric Bai-Wierzbicki form): isochoric plane strain F = diag(l, 1/l, 1) is a
// pure shear state, triaxiality 0 and Lode parameter 0 (principal Hencky strains e, -e, 0), so
// D = alpha / (s (d1 + d2)) exactly; uniaxial tension (Lode angle parameter 1) is unaffected.
TEST(FailureIndicator, PlaneStrainDamageUsesTheShearBranch) {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = 400e6;
  h.linear_modulus = 1e9;
  FailureParameters locus{0.05, 3.44, -2.12};
  locus.shear_ductility_ratio = 0.4;
  const J2LogPlasticity m(ElasticParameters{200e9, 0.3}, IsotropicHardening(h), locus);
  PlasticState state;
  for (int n = 1; n <= 20; ++n) {
    const double l = std::exp(0.01 * n);
    Tensor2 F;
    F[0][0] = l;
    F[1][1] = 1.0 / l;
    F[2][2] = 1.0;
    state = m.update(F, state, false).state;
  }
  ASSERT_GT(state.equivalent_plastic_strain, 0.1);
  EXPECT_NEAR(state.damage, state.equivalent_plastic_strain / (0.4 * (0.05 + 3.44)), 1e-12);
  EXPECT_NEAR(locus.strain_to_failure(1.0 / 3.0, 1.0), 0.05 + 3.44 * std::exp(-2.12 / 3.0), 1e-15);
  EXPECT_NEAR(locus.strain_to_failure(-1.0 / 3.0, -1.0), 0.05 + 3.44 * std::exp(2.12 / 3.0), 1e-14);
}

}  // namespace
}  // namespace dtwire::fem

namespace dtwire::fem {
namespace {

// Combined isotropic (linear) and Armstrong-Frederick kinematic hardening, uniaxial. Closed form
// (Lemaitre & Chaboche 1990, sec. 5.4): with p the accumulated plastic strain, the uniaxial
// backstress X = (3/2) beta_axial obeys dX = C d eps_p - gamma X dp, so under monotonic tension
// X = (C/gamma)(1 - exp(-gamma p)) and tau = sigma_y(p) + X; on reversal the material yields
// again at tau = X* - sigma_y(p*) (elastic range 2 sigma_y: Bauschinger effect), then in
// compression X = -C/gamma + (X* + C/gamma) exp(-gamma (p - p*)) and tau = X - sigma_y(p).
constexpr double kC = 20e9, kGamma = 100.0;  // backstress saturates at C/gamma = 200 MPa

J2LogPlasticity kinematic_model() {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = 400e6;
  h.linear_modulus = 1e9;
  return J2LogPlasticity(ElasticParameters{kE, kNu}, IsotropicHardening(h), {}, KinematicParameters{kC, kGamma});
}

TEST(KinematicHardening, UniaxialCycleMatchesArmstrongFrederickClosedForm) {
  const J2LogPlasticity m = kinematic_model();
  const double saturation = kC / kGamma;
  // Backward Euler integrates dX/dp = C - gamma X with a global error <= X_sat (h/2) max(x e^-x),
  // h = gamma dp per step = 100 x 2.5e-5: <= 4.6e-4 X_sat. Tolerance 1e-3 X_sat = 0.2 MPa.
  const double tolerance = 1e-3 * saturation;
  PlasticState state;
  double mu = 1.0, tau = 0.0;
  const int steps = 2000;
  const double peak_strain = 0.05;
  for (int n = 1; n <= steps; ++n) {
    const StressUpdate r = uniaxial(m, std::exp(peak_strain * n / steps), state, mu);
    state = r.state;
    tau = r.kirchhoff[0][0];
    const double p = state.equivalent_plastic_strain;
    if (p == 0.0) continue;
    const double X = saturation * (1.0 - std::exp(-kGamma * p));
    ASSERT_NEAR(1.5 * state.backstress[0][0], X, tolerance) << "step " << n;
    ASSERT_NEAR(tau, m.hardening().flow_stress(p) + X, tolerance) << "step " << n;
  }
  EXPECT_NEAR(dealii::trace(state.backstress), 0.0, 1e-6);  // deviatoric
  const double p_star = state.equivalent_plastic_strain, X_star = 1.5 * state.backstress[0][0];
  const double sigma_star = m.hardening().flow_stress(p_star);
  // Bauschinger: Hencky elasticity is linear in log strain, so the reverse yield is at
  // ln(lambda) = peak - (tau* - (X* - sigma_y*))/E = peak - 2 sigma_y* / E (to 1e-7 in log strain).
  const double reverse_yield = peak_strain - (tau - (X_star - sigma_star)) / kE;
  PlasticState before = state;
  const StressUpdate elastic = uniaxial(m, std::exp(reverse_yield + 1e-7), before, mu);
  EXPECT_EQ(elastic.plastic_increment, 0.0);
  // Stress 1e-7 (log strain) before the reverse yield point: X* - sigma_y* + E 1e-7, to 1e-6 sigma_y*.
  EXPECT_NEAR(elastic.kirchhoff[0][0], X_star - sigma_star + kE * 1e-7, 1e-6 * sigma_star);
  EXPECT_GT(uniaxial(m, std::exp(reverse_yield - 1e-7), before, mu).plastic_increment, 0.0);
  std::cout << "[kinematic] p* = " << p_star << ", X* = " << X_star * 1e-6 << " MPa (closed form "
            << saturation * (1 - std::exp(-kGamma * p_star)) * 1e-6 << "), forward yield " << tau * 1e-6
            << " MPa, reverse yield " << (elastic.kirchhoff[0][0] - kE * 1e-7) * 1e-6 << " MPa (X* - sigma_y* = "
            << (X_star - sigma_star) * 1e-6 << ")\n";
  // Reverse plastic loading in compression to -0.05 (fine steps again).
  for (int n = 1; n <= 2 * steps; ++n) {
    const double strain = reverse_yield + (-peak_strain - reverse_yield) * n / (2 * steps);
    const StressUpdate r = uniaxial(m, std::exp(strain), state, mu);
    state = r.state;
    const double p = state.equivalent_plastic_strain;
    if (p == p_star) continue;
    const double X = -saturation + (X_star + saturation) * std::exp(-kGamma * (p - p_star));
    ASSERT_NEAR(1.5 * state.backstress[0][0], X, tolerance) << "reverse step " << n;
    ASSERT_NEAR(r.kirchhoff[0][0], X - m.hardening().flow_stress(p), tolerance) << "reverse step " << n;
  }
  const double Jp = 1.0 / std::sqrt(dealii::determinant(state.plastic_metric_inverse));
  EXPECT_NEAR(Jp, 1.0, 1e-12);  // isochoric plastic flow
}

TEST(KinematicHardening, ConsistentTangentMatchesCentralFiniteDifferences) {
  const J2LogPlasticity m = kinematic_model();
  // Non-proportional history so that the backstress is not coaxial with the next trial stress.
  PlasticState state;
  Tensor2 F1 = dealii::unit_symmetric_tensor<3>();
  F1[0][0] = 1.03;
  F1[1][1] = F1[2][2] = 0.985;
  F1[0][1] = 0.02;
  state = m.update(F1, state, false).state;
  ASSERT_GT(state.backstress.norm(), 0.0);
  Tensor2 F2 = F1;
  F2[1][2] = 0.03;
  F2[2][0] = -0.015;
  F2[0][0] = 1.05;
  const StressUpdate plastic = m.update(F2, state, false);
  ASSERT_GT(plastic.plastic_increment, 0.0);
  EXPECT_LT(relative_tangent_error(m, F2, state), 1e-6);  // central differences, h = 1e-6
  // Reverse plastic step (compression after tension) and an elastic step with a backstress.
  Tensor2 F_reverse = F1;
  F_reverse[0][0] = 0.99;
  F_reverse[1][1] = F_reverse[2][2] = 1.006;
  ASSERT_GT(m.update(F_reverse, plastic.state, false).plastic_increment, 0.0);
  EXPECT_LT(relative_tangent_error(m, F_reverse, plastic.state), 1e-6);
  Tensor2 F_unload = F2;
  F_unload[0][0] -= 0.002;
  ASSERT_EQ(m.update(F_unload, plastic.state, false).plastic_increment, 0.0);
  EXPECT_LT(relative_tangent_error(m, F_unload, plastic.state), 1e-6);
}

}  // namespace
}  // namespace dtwire::fem

namespace dtwire::fem {
namespace {

// Hosford-Coulomb locus (Mohr & Marcadet 2015, IJSS 67-68, eq. 20) at the stress states where it
// has a closed form: b in uniaxial (eta 1/3, xi 1) and equibiaxial tension (eta 2/3, xi -1) for
// every a, c; in shear (eta 0, xi 0) the Hosford term is 1 for a = 2 (von Mises) and 2/sqrt(3)
// for a = 1 (Tresca), the Coulomb term 0; in plane-strain tension (eta 1/sqrt(3), xi 0) the
// Coulomb term is 2 c / sqrt(3). Tolerance: round-off of pow and cos (1e-12 relative).
FailureParameters hosford_coulomb(double a, double b, double c, double n = 0.1) {
  FailureParameters f;
  f.locus = FractureLocus::hosford_coulomb;
  f.hc_a = a, f.hc_b = b, f.hc_c = c, f.hc_n = n;
  return f;
}

TEST(HosfordCoulomb, ClosedFormsAtUniaxialEquibiaxialShearAndPlaneStrain) {
  for (const double a : {1.0, 1.4, 2.0})
    for (const double c : {0.0, 0.05, 0.2}) {
      const FailureParameters f = hosford_coulomb(a, 0.8, c);
      EXPECT_NEAR(f.strain_to_failure(1.0 / 3.0, 1.0), 0.8, 1e-12) << "a " << a << ", c " << c;
      EXPECT_NEAR(f.strain_to_failure(2.0 / 3.0, -1.0), 0.8, 1e-12) << "a " << a << ", c " << c;
    }
  const double c = 0.1, n = 0.1, b = 0.8;
  EXPECT_NEAR(hosford_coulomb(2.0, b, c).strain_to_failure(0.0, 0.0) / (b * std::pow(1.0 + c, 1.0 / n)), 1.0, 1e-12);
  EXPECT_NEAR(hosford_coulomb(1.0, b, c).strain_to_failure(0.0, 0.0) /
                  (b * std::pow((1.0 + c) * std::sqrt(3.0) / 2.0, 1.0 / n)),
              1.0, 1e-12);
  EXPECT_NEAR(hosford_coulomb(2.0, b, c).strain_to_failure(1.0 / std::sqrt(3.0), 0.0) /
                  (b * std::pow((1.0 + c) / (1.0 + 2.0 * c / std::sqrt(3.0)), 1.0 / n)),
              1.0, 1e-12);
  // a < 2 lowers the shear ductility against uniaxial tension: the junction's shear can fail first.
  EXPECT_LT(hosford_coulomb(1.2, b, 0.02).strain_to_failure(0.0, 0.0), b);
  // Under enough pressure the bracket turns negative: no damage accrues.
  EXPECT_TRUE(std::isinf(hosford_coulomb(2.0, b, 0.5).strain_to_failure(-3.0, -1.0)));
  EXPECT_FALSE(hosford_coulomb(2.0, 0.0, 0.1).enabled());
}

// The indicator along a material-point path is the plastic strain over the locus at the path's
// stress state: uniaxial (D = alpha / b) and isochoric plane strain F = diag(l, 1/l, 1), pure
// shear (D = alpha / eps_f(0, 0)). Tolerance: the lateral-equilibrium iteration's eta (1e-9).
TEST(HosfordCoulomb, IndicatorAccruesAlongUniaxialAndShearPaths) {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = 400e6;
  h.linear_modulus = 1e9;
  const FailureParameters locus = hosford_coulomb(1.3, 0.9, 0.05);
  const J2LogPlasticity m(ElasticParameters{200e9, 0.3}, IsotropicHardening(h), locus);
  PlasticState tension, shear;
  double mu = 1.0;
  for (int k = 1; k <= 20; ++k) {
    tension = uniaxial(m, std::exp(0.01 * k), tension, mu).state;
    Tensor2 F;
    F[0][0] = std::exp(0.01 * k);
    F[1][1] = std::exp(-0.01 * k);
    F[2][2] = 1.0;
    shear = m.update(F, shear, false).state;
  }
  ASSERT_GT(tension.equivalent_plastic_strain, 0.1);
  EXPECT_NEAR(tension.damage, tension.equivalent_plastic_strain / 0.9, 1e-9);
  EXPECT_NEAR(shear.damage, shear.equivalent_plastic_strain / locus.strain_to_failure(0.0, 0.0), 1e-9);
}

// Crack-band softening (Bazant & Oh 1983): a perfectly plastic bar in uniaxial tension whose
// indicator reaches 1 at alpha_i loses its stress as w = (alpha - alpha_i) h / u_f. The work per
// unit crack area after initiation, h times the dissipation density, is
//   G = sigma_y u_f (w_max - w_max^2 / 2) + psi w_max h   (psi = sigma_y^2 / 2E, the elastic
// energy released), the same for every cell size h. Tolerance 0.5 %: the trapezoidal rule over
// 2e-3 strain steps and the step in which D crosses 1.
TEST(Softening, CrackBandWorkIsIndependentOfTheCellSize) {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = 400e6;
  h.linear_modulus = 0.0;
  FailureParameters locus{0.2, 0.0, 0.0};  // eps_f = 0.2 at every stress state
  locus.softening_displacement = 0.5e-3;
  locus.largest_softening = 0.99;
  const J2LogPlasticity m(ElasticParameters{200e9, 0.3}, IsotropicHardening(h), locus);
  const double psi = 400e6 * 400e6 / (2.0 * 200e9);
  for (const double cell : {1e-3, 0.25e-3}) {
    PlasticState state;
    double mu = 1.0, initiation = -1.0, dissipation_at_initiation = 0.0, stress = 0.0;
    const double end_strain = 0.2 + 1.2 * 0.5e-3 / cell;  // past w_max
    for (int k = 1; k * 2e-3 <= end_strain; ++k) {
      const StressUpdate r = uniaxial(m, std::exp(2e-3 * k), state, mu, cell);
      if (initiation < 0.0 && r.state.damage >= 1.0) {
        initiation = state.equivalent_plastic_strain + (1.0 - state.damage) * 0.2;
        dissipation_at_initiation = state.plastic_dissipation + (initiation - state.equivalent_plastic_strain) * 400e6;
        // Before the crack: the undegraded flow stress.
        EXPECT_NEAR(stress, 400e6, 1e-6 * 400e6);
      }
      if (initiation >= 0.0 && r.state.softening < locus.largest_softening) {
        const double w = (r.state.equivalent_plastic_strain - initiation) * cell / locus.softening_displacement;
        EXPECT_NEAR(r.state.softening, w, 1e-9) << "cell " << cell << ", step " << k;
      }
      stress = r.kirchhoff[0][0];
      state = r.state;
    }
    ASSERT_GE(initiation, 0.0);
    EXPECT_NEAR(state.softening, 0.99, 1e-15);
    EXPECT_NEAR(stress, 0.01 * 400e6, 1e-6 * 400e6);  // the cracked point keeps 1 - w_max
    const double w_max = 0.99;
    const double expected = 400e6 * 0.5e-3 * (w_max - 0.5 * w_max * w_max) + psi * w_max * cell;
    // After w_max the point flows at 1 % of its stress: subtract that tail's work.
    const double tail = (state.equivalent_plastic_strain - initiation - w_max * 0.5e-3 / cell) * 0.01 * 400e6;
    EXPECT_NEAR((state.plastic_dissipation - dissipation_at_initiation - tail) * cell / expected, 1.0, 5e-3)
        << "cell " << cell;
  }
}

// Non-local initiation: the crack starts where the committed average of the indicator plus this
// step's local increment reaches 1, not the local indicator. A perfectly plastic bar with
// eps_f = 0.2, locally at D = 0.5 but with a neighbourhood averaging 0.9, crosses 1 within a step of
// Delta alpha > 0.02: w = (Delta alpha - 0.02) h / u_f. Without the radius the same step (local D
// 0.5 -> 0.7) does not soften.
TEST(Softening, ANonlocalIndicatorStartsTheCrackWhereTheAverageReachesOne) {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = 400e6;
  h.linear_modulus = 0.0;
  FailureParameters locus{0.2, 0.0, 0.0};
  locus.softening_displacement = 0.5e-3;
  const double cell = 1e-3;
  FailureParameters nonlocal = locus;
  nonlocal.nonlocal_radius = 0.5e-3;
  ASSERT_TRUE(nonlocal.nonlocal() && !locus.nonlocal());
  for (const auto& [failure, softens] : {std::pair{nonlocal, true}, std::pair{locus, false}}) {
    const J2LogPlasticity m(ElasticParameters{200e9, 0.3}, IsotropicHardening(h), failure);
    PlasticState state;
    double mu = 1.0;
    state = uniaxial(m, std::exp(0.1 + 400e6 / 200e9), state, mu).state;  // alpha about 0.1, D = alpha / 0.2
    ASSERT_NEAR(state.damage, state.equivalent_plastic_strain / 0.2, 1e-9);
    ASSERT_LT(state.damage, 0.55);
    state.nonlocal_damage = 0.9;
    const StressUpdate r = uniaxial(m, std::exp(0.15 + 400e6 / 200e9), state, mu, cell);
    const double dalpha = r.state.equivalent_plastic_strain - state.equivalent_plastic_strain;
    ASSERT_GT(dalpha, 0.03);
    EXPECT_NEAR(r.state.damage, state.damage + dalpha / 0.2, 1e-9);  // the local indicator as before
    EXPECT_EQ(r.state.nonlocal_damage, 0.9);                            // carried until the solver's refresh
    if (softens)
      EXPECT_NEAR(r.state.softening, (dalpha - (1.0 - 0.9) * 0.2) * cell / locus.softening_displacement, 1e-9);
    else
      EXPECT_EQ(r.state.softening, 0.0);
  }
}

// The algorithmic tangent with softening (a step past initiation, w growing) and after it (w at
// w_max) against central differences; tolerance as the undamaged tangent's (1e-6), looser (1e-5)
// where the stress is 1 % of the flow stress and round-off weighs more.
TEST(Softening, TangentMatchesCentralFiniteDifferences) {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = 400e6;
  h.linear_modulus = 1e9;
  for (const bool kinematic : {false, true}) {
    FailureParameters locus{0.05, 0.0, 0.0};
    locus.softening_displacement = 0.2e-3;
    const J2LogPlasticity m(ElasticParameters{200e9, 0.3}, IsotropicHardening(h), locus,
                            kinematic ? KinematicParameters{20e9, 100.0} : KinematicParameters{});
    const double cell = 0.5e-3;
    PlasticState state;
    Tensor2 F = dealii::unit_symmetric_tensor<3>();
    for (int k = 1; k <= 200 && state.softening < 0.3; ++k) {
      F[0][0] = 1.0 + 2e-3 * k;
      F[1][1] = F[2][2] = 1.0 - 1e-3 * k;
      F[0][1] = 5e-4 * k;
      state = m.update(F, state, false, cell).state;
    }
    ASSERT_GT(state.softening, 0.0) << "kinematic " << kinematic;
    ASSERT_LT(state.softening, 0.99);
    Tensor2 next = F;
    next[0][0] += 2e-3;
    next[1][1] -= 1e-3;
    const StressUpdate step = m.update(next, state, false, cell);
    ASSERT_GT(step.state.softening, state.softening);
    EXPECT_LT(relative_tangent_error(m, next, state, cell), 1e-6) << "kinematic " << kinematic;
  }
}

}  // namespace
}  // namespace dtwire::fem
