// The dem_specimen simulator (calibrate/include/dtwire/calibrate/dem_specimen.hpp): a DT specimen
// (one DT link, four SW arms, clamped grips) in the DEM engine, loaded quasi-statically.
// Checked against the closed-form stiffness of the spring assembly, for symmetry, for
// independence of the quasi-static answer from the increments, damping and move steps, for the
// length scaling of the sets, and by recovering known SW and DT parameters from whole-specimen
// curves it made itself (see the inverse-crime note at that test).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "dtwire/calibrate/dem_specimen.hpp"
#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/calibrate/synthesize.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/dem/contact_law.hpp"
#include "thesis_sets.hpp"

namespace dtwire::calibrate {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

using testing::thesis_sets;

DemSpecimenSimulator specimen(std::vector<double> path_m, double angle_deg = 0.0, int increments = 20,
                              int arm_links = 1, QuasiStaticOptions options = {}, const std::string& law = "thesis",
                              dem::ParameterMap fixed = thesis_sets()) {
  SpecimenGeometry geometry;
  geometry.arm_links = arm_links;
  SpecimenPath path;
  path.displacement_m = std::move(path_m);
  path.pull_angle_rad = angle_deg * kDegree;
  path.increments_per_leg = increments;
  return DemSpecimenSimulator(law, std::move(fixed), geometry, options, path);
}

double last(const Curve& c, const std::string& q) { return c.channel(q).values.back(); }

// Elastic tension, closed form. By the mirror symmetry x -> -x the junctions neither rotate nor
// move sideways, so each arm is a chain clamped at both ends (grip clamped, junction rotation 0)
// whose ends move apart by delta along z: axial part delta cos(beta) on the axial stiffness
// k_a (chain of n links in series), transverse part delta sin(beta) on the chain's transverse
// stiffness. A link of the engine has a shear spring k_s at its midpoint and a rotation spring
// k_r; for n links of length h = L/n clamped at both ends the transverse flexibility is
//   1/k_t = n / k_s' + (L^3 - L h^2) / (12 k_r' h)
// (moment linear along the chain, nodal rotations from the midpoint rule: exact; the link's
// deflection h (theta_a + theta_b)/2 is the trapezoidal rule of a quadratic: L h^2/12 short of
// the beam's L^3/12; n = 1: shear alone). Each half of the specimen: K_half = 2 (k_a cos^2 beta
// + k_t sin^2 beta); the DT link k_dt in series: 1/K = 2/K_half + 1/k_dt.
// The thesis law's link stiffnesses at length L (scaled from the set's reference length l0,
// r = l0/L): k_a = EA r, k_s = k_a / 2.6, k_r = EI_deg (180/pi) r.
double closed_form_tension_stiffness(const dem::ParameterMap& sets, int n) {
  const double L = 0.030, beta = 41.81 * kDegree;
  const double r_sw = sets.at("sw.reference_length_m") / (L / n);
  const double ka_link = sets.at("sw.EA_N") * r_sw, ks_link = ka_link / 2.6;
  const double kr_link = sets.at("sw.EI_Nm2_per_deg_convention") * 180.0 / kPi * r_sw;
  const double h = L / n;
  const double k_axial = ka_link / n;
  const double k_transverse = 1.0 / (n / ks_link + (L * L * L - L * h * h) / (12.0 * kr_link * h));
  const double half = 2.0 * (k_axial * std::pow(std::cos(beta), 2) + k_transverse * std::pow(std::sin(beta), 2));
  const double k_dt = sets.at("dt.EA_N") * sets.at("dt.reference_length_m") / 0.040;
  return 1.0 / (2.0 / half + 1.0 / k_dt);
}

TEST(DemSpecimen, ElasticTensionMatchesClosedFormAndIsSymmetric) {
  const dem::ParameterMap sets = thesis_sets();
  for (int n : {1, 2, 4}) {
    const double u = 1e-5;  // 0.01 mm: geometric changes of order 1e-4 of the arm lengths
    const DemSpecimenSimulator sim = specimen({0.0, u}, 0.0, 4, n);
    SpecimenRunInfo info;
    const Curve c = sim.simulate({}, info);
    const double k = last(c, "force") / last(c, "displacement");
    const double expected = closed_form_tension_stiffness(sets, n);
    std::cout << "arm_links " << n << ": K = " << k << " N/m, closed form " << expected << ", relative error "
              << k / expected - 1 << ", steps " << info.steps << " (largest relaxation " << info.largest_relax_steps
              << ")\n";
    EXPECT_NEAR(k / expected, 1.0, 1e-3) << "arm_links " << n;
    const double a1 = last(c, "arm1_force");
    EXPECT_NEAR(last(c, "arm2_force") / a1, 1.0, 1e-9);  // mirror x -> -x: exact
    EXPECT_NEAR(last(c, "arm4_force") / last(c, "arm3_force"), 1.0, 1e-9);
    EXPECT_NEAR(last(c, "arm3_force") / a1, 1.0, 1e-4);  // upper vs lower: to the relaxation tolerance
    EXPECT_NEAR(last(c, "dt_axial_force") / last(c, "force"), 1.0, 1e-4);
    EXPECT_LT(std::abs(last(c, "shear_force")), 1e-6 * last(c, "force"));
    EXPECT_LT(std::abs(last(c, "dt_moment")), 1e-6 * last(c, "force") * 0.04);
  }
}

// Elastic pull at an angle against an independent linear solve of the planar spring assembly:
// each link (axis e, in-plane normal t = e_y x e, length h) has the generalised strains
//   axial (u_b - u_a).e,  shear (u_b - u_a).t - h/2 (theta_a + theta_b),  bending theta_b - theta_a
// (rotations about +y; a rigid rotation strains nothing) with the springs k_a, k_s, k_r of the
// scaled thesis sets; K = sum B^T diag(k) B, grips prescribed, free nodes solved.
struct PlanarAnswer {
  double force = 0.0, shear_force = 0.0, dt_axial_force = 0.0;
};

PlanarAnswer planar_spring_assembly(const dem::ParameterMap& sets, int n, double angle, double delta) {
  const double L = 0.030, beta = 41.81 * kDegree, twist = 0.040;
  struct Link {
    int a, b;
    Eigen::Vector2d e;  // (x, z)
    double h, ka, ks, kr;
  };
  std::vector<Eigen::Vector2d> x{{0.0, 0.0}, {0.0, twist}};
  std::vector<Link> links;
  const auto springs = [&](const std::string& prefix, double h, Link& link) {
    const double r = sets.at(prefix + "reference_length_m") / h;
    link.h = h;
    link.ka = sets.at(prefix + "EA_N") * r;
    link.ks = link.ka / 2.6;
    link.kr = sets.at(prefix + "EI_Nm2_per_deg_convention") * 180.0 / kPi * r;
  };
  Link dt{0, 1, {0.0, 1.0}, 0, 0, 0, 0};
  springs("dt.", twist, dt);
  links.push_back(dt);
  std::vector<int> grips;
  const double side[4] = {1, -1, 1, -1}, up[4] = {1, 1, -1, -1};
  for (int arm = 0; arm < 4; ++arm) {
    const int junction = up[arm] > 0 ? 1 : 0;
    const Eigen::Vector2d e(side[arm] * std::sin(beta), up[arm] * std::cos(beta));
    int previous = junction;
    for (int i = 1; i <= n; ++i) {
      x.push_back(x[junction] + (i * L / n) * e);
      Link link{previous, static_cast<int>(x.size()) - 1, e, 0, 0, 0, 0};
      springs("sw.", L / n, link);
      links.push_back(link);
      previous = link.b;
    }
    grips.push_back(previous);
  }
  const int dofs = 3 * static_cast<int>(x.size());  // u_x, u_z, theta_y per node
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs, dofs);
  for (const Link& link : links) {
    const Eigen::Vector2d t(link.e.y(), -link.e.x());  // e_y x e in (x, z)
    Eigen::Matrix<double, 3, 6> B = Eigen::Matrix<double, 3, 6>::Zero();
    B.block<1, 2>(0, 0) = -link.e.transpose();
    B.block<1, 2>(0, 3) = link.e.transpose();
    B.block<1, 2>(1, 0) = -t.transpose();
    B.block<1, 2>(1, 3) = t.transpose();
    B(1, 2) = B(1, 5) = -0.5 * link.h;
    B(2, 2) = -1.0;
    B(2, 5) = 1.0;
    const Eigen::Matrix<double, 6, 6> k = B.transpose() * Eigen::Vector3d(link.ka, link.ks, link.kr).asDiagonal() * B;
    const int index[6] = {3 * link.a, 3 * link.a + 1, 3 * link.a + 2, 3 * link.b, 3 * link.b + 1, 3 * link.b + 2};
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) K(index[r], index[c]) += k(r, c);
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(dofs);
  std::vector<char> prescribed(dofs, 0);
  const Eigen::Vector2d d(std::sin(angle), std::cos(angle));
  for (int g = 0; g < 4; ++g) {
    for (int c = 0; c < 3; ++c) prescribed[3 * grips[g] + c] = 1;
    if (g < 2) u.segment<2>(3 * grips[g]) = delta * d;
  }
  std::vector<int> free;
  for (int i = 0; i < dofs; ++i)
    if (!prescribed[i]) free.push_back(i);
  Eigen::MatrixXd Kff(free.size(), free.size());
  Eigen::VectorXd rhs(free.size());
  for (std::size_t r = 0; r < free.size(); ++r) {
    rhs[r] = 0.0;
    for (int c = 0; c < dofs; ++c)
      if (prescribed[c]) rhs[r] -= K(free[r], c) * u[c];
    for (std::size_t c = 0; c < free.size(); ++c) Kff(r, c) = K(free[r], free[c]);
  }
  const Eigen::VectorXd uf = Kff.ldlt().solve(rhs);
  for (std::size_t r = 0; r < free.size(); ++r) u[free[r]] = uf[r];
  const Eigen::VectorXd f = K * u;  // external forces: at the grips, what they apply
  PlanarAnswer answer;
  const Eigen::Vector2d v(d.y(), -d.x());  // e_y x d
  for (int g = 0; g < 2; ++g) {
    answer.force += f.segment<2>(3 * grips[g]).dot(d);
    answer.shear_force += f.segment<2>(3 * grips[g]).dot(v);
  }
  answer.dt_axial_force = links[0].ka * (u.segment<2>(3) - u.segment<2>(0)).dot(links[0].e);
  return answer;
}

TEST(DemSpecimen, ElasticPullAtAnAngleMatchesThePlanarSpringAssembly) {
  const dem::ParameterMap sets = thesis_sets();
  for (int n : {1, 2})
    for (double angle : {25.0, 47.0, 78.0}) {
      const double u = 1e-6;  // 1 um: geometric changes 3e-5 of the arm length (at 10 um: 5e-4 differences)
      const Curve c = specimen({0.0, u}, angle, 4, n).simulate({});
      const PlanarAnswer expected = planar_spring_assembly(sets, n, angle * kDegree, u);
      const double scale = std::abs(expected.force) + std::abs(expected.shear_force);
      std::cout << "arm_links " << n << ", pull " << angle << " deg: force " << last(c, "force") << " (assembly "
                << expected.force << "), shear " << last(c, "shear_force") << " (" << expected.shear_force
                << "), DT N " << last(c, "dt_axial_force") << " (" << expected.dt_axial_force << ")\n";
      EXPECT_NEAR(last(c, "force"), expected.force, 2e-4 * scale) << n << " " << angle;
      EXPECT_NEAR(last(c, "shear_force"), expected.shear_force, 2e-4 * scale) << n << " " << angle;
      EXPECT_NEAR(last(c, "dt_axial_force"), expected.dt_axial_force, 2e-4 * scale) << n << " " << angle;
    }
}

// The relative deviation of b's force from a's at a's displacements (largest over the curve,
// relative to a's largest force). Both curves must be sampled at common displacements.
double force_deviation(const Curve& a, const Curve& b, const std::string& channel = "force") {
  const auto& xa = a.channel("time").values;
  const auto& fa = a.channel(channel).values;
  const auto& xb = b.channel("time").values;
  const auto& fb = b.channel(channel).values;
  double largest = 0.0, scale = 0.0;
  for (double f : fa) scale = std::max(scale, std::abs(f));
  std::size_t k = 0;
  for (std::size_t i = 0; i < xa.size(); ++i) {
    while (k < xb.size() && xb[k] < xa[i] - 1e-12) ++k;
    if (k == xb.size() || std::abs(xb[k] - xa[i]) > 1e-12) continue;
    largest = std::max(largest, std::abs(fb[k] - fa[i]));
  }
  return largest / scale;
}

dem::ParameterMap recovery_truth() {
  dem::ParameterMap sets = thesis_sets();
  sets["sw.N0_N"] = 1369;
  sets["sw.Nult_N"] = 3252;
  return sets;
}

// Quasi-static independence on plastic paths (both sets yield): tension and pull at 47 deg to
// 4 mm, against a reference run with 80 increments, 800 move steps, damping 0.5 and tolerance
// 1e-8. Variants: the defaults (40 increments, 200 move steps, damping 0.7, tolerance 1e-6),
// 20 and 80 increments, damping 0.3 and 0.9, 100 and 400 move steps. Largest deviation of the
// grip force, the DT link's force and arm 1's force over the curve, relative to the largest
// force: 2e-3 for the defaults, 5e-3 for the variants (measured figures below). The remaining
// dependence comes from the grips' motion within an increment (the upper arms lead the lower
// ones while the net follows): it shrinks with more move steps (1e-4 at 400).
TEST(DemSpecimen, QuasiStaticAnswerDoesNotDependOnIncrementsDampingOrMoveSteps) {
  const dem::ParameterMap sets = recovery_truth();
  for (double angle : {0.0, 47.0}) {
    QuasiStaticOptions reference_options;
    reference_options.move_steps = 800;
    reference_options.local_damping = 0.5;
    reference_options.tolerance = 1e-8;
    const Curve reference = specimen({0.0, 0.004}, angle, 80, 1, reference_options, "thesis", sets).simulate({});
    struct Variant {
      const char* what;
      int increments;
      QuasiStaticOptions options;
    };
    std::vector<Variant> variants{{"defaults", 40, {}}, {"20 increments", 20, {}}, {"80 increments", 80, {}}};
    Variant v{"damping 0.3", 40, {}};
    v.options.local_damping = 0.3;
    variants.push_back(v);
    v = {"damping 0.9", 40, {}};
    v.options.local_damping = 0.9;
    variants.push_back(v);
    v = {"100 move steps", 40, {}};
    v.options.move_steps = 100;
    variants.push_back(v);
    v = {"400 move steps", 40, {}};
    v.options.move_steps = 400;
    variants.push_back(v);
    for (const Variant& variant : variants) {
      const Curve c = specimen({0.0, 0.004}, angle, variant.increments, 1, variant.options, "thesis", sets).simulate({});
      const double force = force_deviation(reference, c);
      const double dt_force = force_deviation(reference, c, "dt_axial_force");
      const double arm = force_deviation(reference, c, "arm1_force");
      std::cout << "pull " << angle << " deg, " << variant.what << ": force " << force << ", DT force " << dt_force
                << ", arm 1 force " << arm << " (of the largest)\n";
      // Measured: tension <= 5e-5 (arm 8e-4 with 100 move steps); pull at 47 deg 8e-4 / 1.3e-3 (DT)
      // with the defaults, up to 2.4e-3 / 4.2e-3 with 100 move steps or damping 0.9.
      const double bound = std::string(variant.what) == "defaults" ? 2e-3 : 5e-3;
      EXPECT_LT(force, bound) << angle << " " << variant.what;
      EXPECT_LT(dt_force, bound) << angle << " " << variant.what;
      EXPECT_LT(arm, bound) << angle << " " << variant.what;
    }
  }
}

// Recovery (issue 15): experiments/dt_fe_fit/dem_specimen_recovery.toml fits the DT set's EA,
// N0, Nult and the SW set's N0, Nult jointly to whole-specimen curves (grip force; in tension
// also the DT elongation, at 47 deg also the shear force) on three paths: tension to 4 mm, pull
// at 47 deg to 4 mm, pull at 78 deg to 4 mm and back to 2 mm.
// INVERSE CRIME: the targets are made by the same simulator (same engine, law, geometry,
// quasi-static settings and increments) at the reference values, so the test shows that the
// five parameters are identifiable from these curves and that the fit machinery recovers them;
// it says nothing about how well the element represents an FE or laboratory specimen. The
// noise (Gaussian, 1 % of each channel's range, at 81 points per curve) is the only model
// error.
FitDefinition recovery_fit(double noise, std::uint64_t seed) {
  FitReadOptions options;
  options.read_targets = false;
  FitDefinition def = read_fit_file(
      std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/dt_fe_fit/dem_specimen_recovery.toml", options);
  ParameterValues truth;
  for (const auto& p : def.parameters) truth[p.name] = p.reference.value();
  std::mt19937_64 generator(seed);
  for (auto& e : def.experiments) e.target = synthesize_target(e, truth, noise, generator, 81);
  return def;
}

FitResult run_recovery(double noise, std::uint64_t seed) {
  FitDefinition def = recovery_fit(noise, seed);
  EXPECT_EQ(def.experiments.size(), 3u);
  EXPECT_EQ(def.parameters.size(), 5u);
  ProblemEvaluator evaluator(def.experiments, def.parameters, def.evaluation);
  const FitResult result = run_fit(evaluator, def.fit);
  std::cout << "noise " << noise << " seed " << seed << ": wall " << result.wall_seconds << " s, "
            << result.statistics.simulations << " simulations, cost " << result.cost << "\n";
  for (std::size_t i = 0; i < result.values.size(); ++i) {
    const auto& p = result.parameters[i];
    const double sigma = result.sigma.empty() ? NAN : result.sigma[i];
    std::cout << "  " << p.name << ": true " << *p.reference << ", fitted " << result.values[i] << " +- " << sigma
              << " (z " << (result.values[i] - *p.reference) / sigma << ", relative error "
              << result.values[i] / *p.reference - 1 << ")\n";
  }
  for (const auto& q : result.quality)
    std::cout << "  " << q.experiment << " " << q.quantity << ": NRMSE " << q.nrmse << "\n";
  for (const auto& w : result.warnings) std::cout << "  warning: " << w << "\n";
  return result;
}

TEST(DemSpecimen, JointFitRecoversSwAndDtParametersWithoutNoise) {
  const FitResult result = run_recovery(0.0, 1);
  ASSERT_TRUE(result.completed);
  for (std::size_t i = 0; i < result.values.size(); ++i)
    EXPECT_NEAR(result.values[i] / *result.parameters[i].reference, 1.0, 1e-3) << result.parameters[i].name;
}

TEST(DemSpecimen, JointFitRecoversSwAndDtParametersWithinTwoSigmaWithOnePercentNoise) {
  const FitResult result = run_recovery(0.01, 7);
  ASSERT_TRUE(result.completed);
  ASSERT_EQ(result.sigma.size(), result.values.size());
  for (std::size_t i = 0; i < result.values.size(); ++i) {
    const auto& p = result.parameters[i];
    EXPECT_LT(std::abs(result.values[i] - *p.reference), 2.0 * result.sigma[i]) << p.name;
    EXPECT_LT(result.sigma[i], 0.05 * *p.reference) << p.name;
  }
  for (const auto& q : result.quality) EXPECT_LT(q.nrmse, 0.02) << q.experiment << " " << q.quantity;
}

// The quoted uncertainty over eight noise realisations (1 % noise, 5 parameters each): the
// sandwich sigma must cover the truth as often as a normal 2-sigma interval does (95.4 %;
// measured 39 of 40), and must not be inflated to get there: the RMS of the z-scores is near 1
// (chi-square with 40 degrees of freedom: sqrt(chi2/40) lies in [0.77, 1.21] 95 % of the time;
// the bound is wider because the five z-scores of one fit are correlated).
TEST(DemSpecimen, RecoveryCoverageOverSeeds) {
  int within = 0, total = 0;
  double z_squared = 0.0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const FitResult result = run_recovery(0.01, seed);
    ASSERT_TRUE(result.completed) << "seed " << seed;
    ASSERT_EQ(result.sigma.size(), result.values.size()) << "seed " << seed;
    for (std::size_t i = 0; i < result.values.size(); ++i) {
      const double z = (result.values[i] - *result.parameters[i].reference) / result.sigma[i];
      ++total;
      z_squared += z * z;
      if (std::abs(z) < 2.0) ++within;
    }
  }
  const double z_rms = std::sqrt(z_squared / total);
  std::cout << within << " of " << total << " estimates within 2 sigma, RMS z " << z_rms << "\n";
  EXPECT_GE(within, 34) << "of " << total;  // P(<= 33 of 40 | p = 0.954) < 0.5 %
  EXPECT_GT(z_rms, 0.5);
  EXPECT_LT(z_rms, 1.6);
}

// The length scaling of a set (docs/calibrate.md): stiffnesses and hardening rates x r, damage
// energies / r, forces and shape parameters unchanged, r = reference / link length.
// A peak row on a target of another origin: the specimen's tension curve with the published sets
// (arms without damage, as dt_specimen_fit.toml) up to its peak, then a snap the thesis law cannot
// make (the force falls to 40 % within 0.5 mm, as the FE wire's crack band does), so no set of
// the law reproduces the target. dt.N0 and dt.Nult fitted from a start far from the truth (2000,
// 8000 N). With the peak row the fit keeps the specimen's strength: the simulated peak and
// dt.Nult within 5 % (the tolerance of a recovery) of the target's and of the set that made the
// rising branch (measured: -3.9 %); without it the snap pulls the set weaker, to dt.Nult's lower
// bound 4600 N (-8 %): the row is what holds the strength (docs/calibrate.md, "Peak rows").
TEST(DemSpecimen, APeakRowKeepsTheStrengthOfATargetThatSnaps) {
  dem::ParameterMap truth = thesis_sets();
  truth["sw.W1_J"] = 1e6;
  truth["sw.W2_J"] = 2e6;
  const std::vector<double> path{0.0, 0.003, 0.034};
  const Curve full = specimen(path, 0.0, 10, 1, {}, "thesis", truth).simulate({});
  const std::vector<double> u = full.si("displacement"), f = full.si("force");
  const std::size_t peak = static_cast<std::size_t>(std::max_element(f.begin(), f.end()) - f.begin());
  ASSERT_GT(peak, 5u);
  ASSERT_LT(peak + 1, f.size()) << "the published set must peak inside the path";
  std::cout << "target: peak " << f[peak] << " N at " << 1e3 * u[peak] << " mm\n";
  std::vector<double> tu(u.begin(), u.begin() + static_cast<std::ptrdiff_t>(peak) + 1);
  std::vector<double> tf(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(peak) + 1);
  tu.push_back(u[peak] + 5e-4);
  tf.push_back(0.4 * f[peak]);
  Curve target;
  target.add_channel("displacement", *find_unit("m"), tu);
  target.add_channel("force", *find_unit("N"), tf);

  dem::ParameterMap fixed = truth;
  fixed.erase("dt.N0_N");
  fixed.erase("dt.Nult_N");
  const auto fit = [&](bool with_peak) {
    Experiment e;
    e.name = "tension";
    e.target = target;
    // Past the snap by 2 mm: far enough to see a set that goes on rising, short of where the
    // trial sets break (a broken specimen is a failed run).
    e.simulator = std::make_shared<DemSpecimenSimulator>(
        specimen({0.0, 0.003, u[peak] + 0.002}, 0.0, 10, 1, {}, "thesis", fixed));
    e.channels = {{"force", 1.0, 0.0}};
    if (with_peak) e.peaks = {{"force", 1.0, 0.0}};
    std::vector<ParameterDefinition> parameters{{"dt.N0_N", "N", 2000, 500, 4500, 0, truth.at("dt.N0_N")},
                                                {"dt.Nult_N", "N", 8000, 4600, 9500, 0, truth.at("dt.Nult_N")}};
    ProblemEvaluator evaluator({e}, parameters, EvaluationOptions{});
    FitOptions options;
    options.max_iterations = 40;
    const FitResult result = run_fit(evaluator, options);
    const Curve fitted = e.simulator->simulate({{"dt.N0_N", result.values[0]}, {"dt.Nult_N", result.values[1]}});
    const std::vector<double> fitted_force = fitted.si("force");
    const double simulated_peak = *std::max_element(fitted_force.begin(), fitted_force.end());
    std::cout << (with_peak ? "with" : "without") << " the peak row: dt.N0 " << result.values[0] << " N, dt.Nult "
              << result.values[1] << " N (truth " << truth.at("dt.Nult_N") << "), peak " << simulated_peak
              << " N against " << f[peak] << " N, cost " << result.cost << "\n";
    return std::make_pair(result.values[1], simulated_peak);
  };
  const auto [nult, peak_force] = fit(true);
  EXPECT_NEAR(peak_force / f[peak], 1.0, 0.05);
  EXPECT_NEAR(nult / truth.at("dt.Nult_N"), 1.0, 0.05);
  const auto without = fit(false);
  EXPECT_GT(std::abs(without.first / truth.at("dt.Nult_N") - 1.0), std::abs(nult / truth.at("dt.Nult_N") - 1.0));
}

TEST(DemSpecimen, SetsAreScaledToTheLinkLength) {
  const dem::ParameterMap set = {{"EA_N", 1.6e7}, {"EI_Nm2_per_deg_convention", 0.122}, {"k_F", 2.39e4},
                                 {"k_M", 1120},   {"W1_J", 9.21},  {"W2_J", 140.01},
                                 {"N0_N", 2750},  {"m_f", 0.0285}, {"reference_length_m", 0.06},
                                 {"bending_stiffness_Nm_per_rad", 7.0}, {"shear_strength_N", 900}};
  const dem::ParameterMap half = scale_to_link_length(set, 0.06, 0.03);
  EXPECT_DOUBLE_EQ(half.at("EA_N"), 3.2e7);
  EXPECT_DOUBLE_EQ(half.at("EI_Nm2_per_deg_convention"), 0.244);
  EXPECT_DOUBLE_EQ(half.at("k_F"), 4.78e4);
  EXPECT_DOUBLE_EQ(half.at("k_M"), 2240);
  EXPECT_DOUBLE_EQ(half.at("bending_stiffness_Nm_per_rad"), 14.0);
  EXPECT_DOUBLE_EQ(half.at("W1_J"), 4.605);
  EXPECT_DOUBLE_EQ(half.at("W2_J"), 70.005);
  EXPECT_DOUBLE_EQ(half.at("N0_N"), 2750);
  EXPECT_DOUBLE_EQ(half.at("m_f"), 0.0285);
  EXPECT_DOUBLE_EQ(half.at("shear_strength_N"), 900);
  EXPECT_DOUBLE_EQ(half.at("reference_length_m"), 0.03);
  // A SW arm in two links of 15 mm has the axial stiffness of one 30 mm link: EA x 60/30.
  const dem::ParameterMap sets = thesis_sets();
  EXPECT_NEAR(closed_form_tension_stiffness(sets, 1), specimen({0.0, 1e-5}, 0.0, 2, 1).simulate({}).channel("force").values.back() / 1e-5,
              1e-4 * closed_form_tension_stiffness(sets, 1));
}

// macro3d reduces to the thesis element on planar paths (docs/dem_laws.md): the same specimen
// curves with either law and the published sets (pull at 47 deg, both sets plastic).
TEST(DemSpecimen, Macro3dGivesTheThesisCurves) {
  dem::ParameterMap sets = recovery_truth();
  const Curve thesis = specimen({0.0, 0.003}, 47.0, 20, 1, {}, "thesis", sets).simulate({});
  const Curve macro3d = specimen({0.0, 0.003}, 47.0, 20, 1, {}, "macro3d", sets).simulate({});
  const double deviation = force_deviation(thesis, macro3d);
  std::cout << "macro3d vs thesis, pull at 47 deg: " << deviation << " of the largest force\n";
  EXPECT_LT(deviation, 2e-3);
}

TEST(DemSpecimen, FailuresAreComputationErrors) {
  // Broken before the path's end: the DT's damage energies lowered to 2 J (W1) and 10 J (W2),
  // reached within about 2 mm of plastic elongation at Nult.
  try {
    specimen({0.0, 0.01}, 0.0, 40).simulate({{"dt.W1_J", 2.0}, {"dt.W2_J", 10.0}});
    ADD_FAILURE() << "no error";
  } catch (const ComputationError& error) {
    std::cout << error.what() << "\n";
    EXPECT_NE(std::string(error.what()).find("broke"), std::string::npos) << error.what();
  }
  // The law rejects the set (Nult < N0).
  EXPECT_THROW(specimen({0.0, 0.001}).simulate({{"dt.Nult_N", 1000.0}}), ComputationError);
  // Not converged within the step budget.
  QuasiStaticOptions hurried;
  hurried.max_relax_steps = 2;
  EXPECT_THROW(specimen({0.0, 0.001}, 0.0, 4, 1, hurried).simulate({}), ComputationError);
  // Bad construction: no prefix, unknown law, missing reference length.
  dem::ParameterMap unprefixed = thesis_sets();
  unprefixed["N0_N"] = 1.0;
  EXPECT_THROW(specimen({0.0, 0.001}, 0.0, 4, 1, {}, "thesis", unprefixed), std::invalid_argument);
  EXPECT_THROW(specimen({0.0, 0.001}, 0.0, 4, 1, {}, "wirepm"), std::invalid_argument);
  dem::ParameterMap no_length = thesis_sets();
  no_length.erase("sw.reference_length_m");
  EXPECT_THROW(specimen({0.0, 0.001}, 0.0, 4, 1, {}, "thesis", no_length), std::invalid_argument);
}

TEST(DemSpecimen, InterfaceDeclaresChannelsAndPrefixedNames) {
  const DemSpecimenSimulator sim = specimen({0.0, 0.001});
  const auto names = sim.parameter_names();
  for (const char* name : {"sw.N0_N", "dt.N0_N", "sw.EA_N", "dt.reference_length_m"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  EXPECT_TRUE(sim.thread_safe());
  const Curve c = sim.simulate({});
  ASSERT_EQ(c.channels().size(), sim.channels().size());
  for (const auto& [quantity, dimension] : sim.channels()) {
    ASSERT_TRUE(c.has(quantity)) << quantity;
    EXPECT_EQ(c.channel(quantity).unit.dimension, dimension) << quantity;
  }
  // The identity changes with anything that changes the curve.
  EXPECT_NE(sim.identity(), specimen({0.0, 0.001}, 10.0).identity());
  EXPECT_NE(sim.identity(), specimen({0.0, 0.001}, 0.0, 5).identity());
  EXPECT_NE(sim.identity(), specimen({0.0, 0.001}, 0.0, 20, 2).identity());
}

// Fit-file errors name file:line and the field.
std::string fit_file_error(const std::string& text) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "dtwire_dem_specimen_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "bad.toml";
  std::ofstream(file) << text;
  FitReadOptions options;
  options.read_targets = false;
  try {
    read_fit_file(file, options);
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

TEST(DemSpecimen, FitFileErrorsNameLineAndField) {
  const std::string params = (std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/data/macroelement_thesis_params.json").string();
  const std::string head = "[simulator]\nkind = \"dem_specimen\"\nlaw = \"thesis\"\nfixed_parameters_file = \"" + params + "\"\n";
  const std::string parameter = "[[parameter]]\nname = \"dt.N0_N\"\ninitial = 2000\nlower = 500\nupper = 5000\n";
  const std::string experiment = "[[experiment]]\nname = \"t\"\ntarget = \"t.csv\"\nchannels = [\"force\"]\npath_displacement_mm = [0, 1]\n";
  EXPECT_EQ(fit_file_error(head + parameter + experiment), "no error");
  // A fitted name without its wire type.
  std::string e = fit_file_error(head + "[[parameter]]\nname = \"N0_N\"\ninitial = 2000\nlower = 500\nupper = 5000\n" + experiment);
  EXPECT_NE(e.find(":6:"), std::string::npos) << e;
  EXPECT_NE(e.find("parameter[1].name"), std::string::npos) << e;
  EXPECT_NE(e.find("sw.<law parameter>"), std::string::npos) << e;
  // A fixed name without a prefix, and a misspelled one.
  e = fit_file_error(head + "[simulator.fixed]\nN0_N = 1\n" + parameter + experiment);
  EXPECT_NE(e.find(":6:"), std::string::npos) << e;
  EXPECT_NE(e.find("simulator.fixed.N0_N"), std::string::npos) << e;
  e = fit_file_error(head + "[simulator.fixed]\n\"sw.N0\" = 1\n" + parameter + experiment);
  EXPECT_NE(e.find("sw.N0_N"), std::string::npos) << e;
  // A law the specimen does not take; a section given the law_replay way; a bad specimen field.
  e = fit_file_error("[simulator]\nkind = \"dem_specimen\"\nlaw = \"wirepm\"\n" + parameter + experiment);
  EXPECT_NE(e.find(":3:"), std::string::npos) << e;
  e = fit_file_error(head + "fixed_parameters_section = \"single_wire\"\n" + parameter + experiment);
  EXPECT_NE(e.find("sw_section"), std::string::npos) << e;
  e = fit_file_error(head + "[simulator.specimen]\narm_angel_deg = 40\n" + parameter + experiment);
  EXPECT_NE(e.find("simulator.specimen.arm_angel_deg"), std::string::npos) << e;
  e = fit_file_error(head + "[simulator.quasi_static]\nlocal_damping = 1.5\n" + parameter + experiment);
  EXPECT_NE(e.find(":6:"), std::string::npos) << e;
  // Paths: a rotation path, a path not starting at 0, an unknown channel.
  e = fit_file_error(head + parameter + experiment + "path_rotation_deg = [0, 1]\n");
  EXPECT_NE(e.find("path_rotation_deg"), std::string::npos) << e;
  e = fit_file_error(head + parameter + "[[experiment]]\nname = \"t\"\ntarget = \"t.csv\"\nchannels = [\"force\"]\npath_displacement_mm = [1, 2]\n");
  EXPECT_NE(e.find("path_displacement_mm"), std::string::npos) << e;
  e = fit_file_error(head + parameter + "[[experiment]]\nname = \"t\"\ntarget = \"t.csv\"\nchannels = [\"moment_y\"]\npath_displacement_mm = [0, 1]\n");
  EXPECT_NE(e.find("no channel 'moment_y'"), std::string::npos) << e;
  // pull_angle_deg with another simulator kind.
  e = fit_file_error("[simulator]\nkind = \"voce_bar\"\n[[parameter]]\nname = \"E_Pa\"\ninitial = 2\nlower = 1\nupper = 3\n"
                     "[[experiment]]\nname = \"t\"\ntarget = \"t.csv\"\nabscissa = \"strain\"\nchannels = [\"stress\"]\n"
                     "path_strain_1 = [0, 0.01]\npull_angle_deg = 10\n");
  EXPECT_NE(e.find("pull_angle_deg"), std::string::npos) << e;
}

}  // namespace
}  // namespace dtwire::calibrate
