// WirePM against hand-computed values of the 2.7 mm single-wire backbone
// (experiments/data/sw_2.7mm_dem_backbone.csv; Bertrand et al. 2008, Thoeni et al. 2013).
// Forces are piecewise linear in the elongation, so the tolerances are round-off: 1e-9 of the
// force scale unless stated otherwise next to the assertion.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLength = 0.06, kDiameter = 0.0027;
const double kArea = kPi * kDiameter * kDiameter / 4.0;  // 5.7256e-6 m^2
const double kStrain[] = {0.0, 0.0019230769, 0.0192, 0.05, 0.15, 0.25, 0.30, 0.35};
const double kStress[] = {0.0, 2.5e8, 3.2195e8, 3.8292e8, 5.1219e8, 5.5854e8, 5.6585e8, 5.6585e8};

ParameterMap backbone_parameters(double length = kLength) {
  ParameterMap p{{"reference_length_m", length}, {"diameter_m", kDiameter}};
  for (int i = 0; i < 8; ++i) {
    p["backbone_" + std::to_string(i) + "_strain_1"] = kStrain[i];
    p["backbone_" + std::to_string(i) + "_stress_Pa"] = kStress[i];
  }
  return p;
}

double u(int i) { return kStrain[i] * kLength; }   // elongation of curve point i [m]
double F(int i) { return kStress[i] * kArea; }     // force of curve point i [N]
double kn() { return F(1) / u(1); }                // 1.2405e7 N/m

Vector6 axial(double du) {
  Vector6 v = Vector6::Zero();
  v(0) = du;
  return v;
}

// Moves the law to an absolute elongation in `pieces` equal increments.
void move(WirePmLaw& law, double& at, double target, int pieces = 1) {
  for (int k = 0; k < pieces; ++k) {
    const double next = k + 1 == pieces ? target : at + (target - at) / (pieces - k);
    law.update(axial(next - at));
    at = next;
  }
}

WirePmLaw single_wire() { return WirePmLaw(make_wirepm_backbone(backbone_parameters())); }

TEST(WirePm, ElasticBranchHasFirstSegmentStiffness) {
  WirePmLaw law = single_wire();
  double at = 0.0;
  move(law, at, 0.5 * u(1));
  EXPECT_NEAR(law.forces()(0), 0.5 * F(1), 1e-12 * F(1));  // round-off only
  EXPECT_NEAR(law.backbone().unloading_stiffness, 1.2405364139727e7, 1e-6 * 1.24e7);  // F1/u1 by hand
  EXPECT_EQ(law.forces().tail<5>().norm(), 0.0);  // no shear, torsion or bending
}

TEST(WirePm, LoadingFollowsTheBackbone) {
  WirePmLaw law = single_wire();
  double at = 0.0;
  move(law, at, 0.5 * (u(1) + u(2)), 3);
  EXPECT_NEAR(law.forces()(0), 0.5 * (F(1) + F(2)), 1e-9 * F(2));  // midpoint of segment 2
  move(law, at, u(3) + 0.25 * (u(4) - u(3)), 5);
  EXPECT_NEAR(law.forces()(0), F(3) + 0.25 * (F(4) - F(3)), 1e-9 * F(4));
  EXPECT_NEAR(F(4), 2932.5708, 1e-3);  // 512.19 MPa on 5.7256 mm^2
}

TEST(WirePm, UnloadsElasticallyFromThePlasticElongation) {
  WirePmLaw law = single_wire();
  double at = 0.0;
  move(law, at, u(3), 4);
  const double plastic = u(3) - F(3) / kn();
  EXPECT_NEAR(law.plastic_elongation(), plastic, 1e-12);  // metres
  move(law, at, u(3) - 1e-4);
  EXPECT_NEAR(law.forces()(0), F(3) - kn() * 1e-4, 1e-9 * F(3));
  move(law, at, 0.5 * (plastic + u(3) - 1e-4));
  EXPECT_NEAR(law.forces()(0), kn() * (at - plastic), 1e-9 * F(3));
  move(law, at, plastic - 1e-5);  // slack: tension only
  EXPECT_EQ(law.forces()(0), 0.0);
  move(law, at, -1e-3);  // compression
  EXPECT_EQ(law.forces()(0), 0.0);
  EXPECT_FALSE(law.broken());
}

TEST(WirePm, ReloadsElasticallyThenRejoinsTheBackbone) {
  WirePmLaw law = single_wire();
  double at = 0.0;
  move(law, at, u(3), 2);
  move(law, at, 0.0);
  move(law, at, u(3) - 1e-4);  // below the historical maximum: still on the elastic line
  EXPECT_NEAR(law.forces()(0), F(3) - kn() * 1e-4, 1e-9 * F(3));
  move(law, at, 0.5 * (u(3) + u(4)));  // one increment that crosses the historical maximum
  EXPECT_NEAR(law.forces()(0), 0.5 * (F(3) + F(4)), 1e-9 * F(4));
}

TEST(WirePm, BreaksPastTheLastPoint) {
  WirePmLaw law = single_wire();
  double at = 0.0;
  move(law, at, u(7) - 1e-6, 10);
  EXPECT_NEAR(law.forces()(0), F(7), 1e-9 * F(7));  // flat last segment
  EXPECT_FALSE(law.broken());
  move(law, at, u(7) + 1e-6);
  EXPECT_TRUE(law.broken());
  EXPECT_EQ(law.failure_mode(), FailureMode::Elongation);
  EXPECT_EQ(law.forces()(0), 0.0);
  move(law, at, 0.5 * u(7));  // a broken bond stays broken
  EXPECT_EQ(law.forces()(0), 0.0);
}

TEST(WirePm, EnergyIsTheExactAreaUnderTheCurveForAnyStepSize) {
  // Hand area of a pull to u3: three trapezoids.
  const double area = 0.5 * F(1) * u(1) + 0.5 * (F(1) + F(2)) * (u(2) - u(1)) + 0.5 * (F(2) + F(3)) * (u(3) - u(2));
  for (const int pieces : {1, 7, 1000}) {
    WirePmLaw law = single_wire();
    double at = 0.0;
    move(law, at, u(3), pieces);
    const EnergyAccount e = law.energy();
    EXPECT_NEAR(e.external, area, 1e-12 * area) << pieces;                       // round-off
    EXPECT_NEAR(e.elastic, F(3) * F(3) / (2.0 * kn()), 1e-12 * area) << pieces;  // F^2 / 2 kn
    EXPECT_NEAR(e.plastic, area - F(3) * F(3) / (2.0 * kn()), 1e-12 * area) << pieces;
  }
}

TEST(WirePm, EnergyBalanceClosesOnARandomCyclicPathThroughBreak) {
  WirePmLaw law = single_wire();
  std::mt19937_64 random(12345);
  std::uniform_real_distribution<double> step(-2e-4, 3e-4);
  double at = 0.0;
  double peak = 0.0;
  while (!law.broken()) {
    move(law, at, at + step(random));
    peak = std::max(peak, law.forces()(0));
    const EnergyAccount e = law.energy();
    ASSERT_NEAR(e.external, e.elastic + e.plastic + e.damage, 1e-10 * std::max(1.0, e.external));  // 1e-10 rel
    ASSERT_GE(e.plastic, -1e-12);
  }
  const EnergyAccount e = law.energy();
  EXPECT_EQ(e.elastic, 0.0);
  EXPECT_NEAR(e.damage, F(7) * F(7) / (2.0 * kn()), 1e-9);  // stored energy released at break [J]
  EXPECT_NEAR(peak, F(7), 1e-9 * F(7));  // the flat last segment is reached before the break
}

TEST(WirePm, BertrandDoubleTwistScaling) {
  ParameterMap p = backbone_parameters(0.04);
  p["double_twist"] = 1;
  p["lambda_k"] = 0.73;
  p["lambda_eps"] = 0.47;
  p["poisson_1"] = 0.3;
  const WirePmBackbone b = make_wirepm_backbone(p);
  // Hand values (Bertrand 2008): k = F1/u1 = 1.86080e7 N/m, alpha = atan(l0/(3 pi d)) = 1.00420 rad,
  // k_h = 8.29510e5 N/m, k_DT = 2 (0.73 k_h + 0.27 k) = 1.125943e7 N/m.
  EXPECT_NEAR(b.unloading_stiffness, 1.1259428867963e7, 1e-9 * 1.126e7);
  const double u1 = kStrain[1] * 0.04;
  EXPECT_NEAR(b.points[1].elongation, u1, 1e-15);
  EXPECT_NEAR(b.points[1].force, 1.1259428867963e7 * u1, 1e-6);
  const double force_scale = 1.1259428867963e7 / 1.86080462095906e7;
  EXPECT_NEAR(b.points[2].elongation, 0.47 * kStrain[2] * 0.04, 1e-15);  // strains scaled by lambda_eps
  EXPECT_NEAR(b.points[7].force, force_scale * F(7), 1e-6 * F(7));
}

TEST(WirePm, OwnDoubleTwistCurveUsesTwiceTheArea) {
  ParameterMap p = backbone_parameters(0.04);
  p["double_twist"] = 1;
  p["double_twist_model"] = 1;
  const WirePmBackbone b = make_wirepm_backbone(p);
  EXPECT_NEAR(b.points[3].force, 2.0 * F(3), 1e-9 * F(3));
  EXPECT_NEAR(b.points[3].elongation, kStrain[3] * 0.04, 1e-15);
}

TEST(WirePm, ThoeniDistortionShiftsTheCurveAndAddsTheSoftPoint) {
  ParameterMap p = backbone_parameters();
  p["lambda_u"] = 0.2;
  p["lambda_F"] = 0.5;
  p["seed"] = -1;  // YADE convention: r = 1
  const WirePmBackbone b = make_wirepm_backbone(p);
  const double shift = 0.2 * kLength;  // dL = lambda_u l0 r
  const double length = kLength + shift;
  EXPECT_NEAR(b.shift, shift, 1e-15);
  ASSERT_EQ(b.points.size(), 9u);  // origin, soft point, 7 curve points
  EXPECT_NEAR(b.points[1].elongation, shift + 0.5 * kStrain[1] * length, 1e-15);
  EXPECT_NEAR(b.points[1].force, 0.5 * F(1), 1e-9);
  EXPECT_NEAR(b.points[2].elongation, shift + kStrain[1] * length, 1e-15);
  EXPECT_NEAR(b.unloading_stiffness, F(1) / (kStrain[1] * length), 1e-3);  // kn from the unshifted point
  // Soft branch: half the first-point force at the soft point.
  WirePmLaw law(b);
  double at = 0.0;
  move(law, at, b.points[1].elongation);
  EXPECT_NEAR(law.forces()(0), 0.5 * F(1), 1e-9 * F(1));

  p["seed"] = 7;  // a per-bond draw: the same seed gives the same curve, another seed another
  EXPECT_EQ(make_wirepm_backbone(p).shift, make_wirepm_backbone(p).shift);
  const double r7 = triangular_variate_from_seed(7);
  EXPECT_NEAR(make_wirepm_backbone(p).shift, 0.2 * kLength * r7, 1e-15);
  EXPECT_NE(triangular_variate_from_seed(7), triangular_variate_from_seed(8));
}

TEST(WirePm, TriangularVariatesHaveTheTriangularMoments) {
  // Triangular on [0, 1], mode 0.5: mean 1/2, variance 1/24, P(r < 0.25) = 1/8.
  const int n = 200000;
  double sum = 0.0, sum_sq = 0.0;
  int below_quarter = 0;
  for (int seed = 0; seed < n; ++seed) {
    const double r = triangular_variate_from_seed(static_cast<std::uint64_t>(seed));
    ASSERT_GE(r, 0.0);
    ASSERT_LE(r, 1.0);
    sum += r;
    sum_sq += r * r;
    below_quarter += r < 0.25;
  }
  const double mean = sum / n;
  const double variance = sum_sq / n - mean * mean;
  // Tolerances: about 5 standard errors of each estimator at n = 2e5.
  EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 24.0 / n));
  EXPECT_NEAR(variance, 1.0 / 24.0, 5.0 * std::sqrt(1.4 / n) / 24.0);  // mu4 = 2.4 sigma^4
  EXPECT_NEAR(static_cast<double>(below_quarter) / n, 0.125, 5.0 * std::sqrt(0.125 * 0.875 / n));
}

TEST(WirePm, BadParametersNameTheField) {
  const auto message_of = [](const ParameterMap& p) {
    try {
      make_contact_law("wirepm", p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ParameterMap p = backbone_parameters();
  p.erase("diameter_m");
  EXPECT_NE(message_of(p).find("diameter_m"), std::string::npos);
  p = backbone_parameters();
  p["backbone_3_strain_1"] = 0.01;  // decreasing strain
  EXPECT_NE(message_of(p).find("backbone_3_strain_1"), std::string::npos);
  p = backbone_parameters();
  for (int i = 2; i < 8; ++i) p.erase("backbone_" + std::to_string(i) + "_strain_1");
  EXPECT_NE(message_of(p).find("at least two backbone points"), std::string::npos);
  p = backbone_parameters();
  p["lambda_u"] = 0.2;
  p["seed"] = 1.5;
  EXPECT_NE(message_of(p).find("seed"), std::string::npos);
  p = backbone_parameters();
  p["double_twist"] = 2;
  EXPECT_NE(message_of(p).find("double_twist"), std::string::npos);
}

TEST(WirePm, FactoryAndCloneKeepTheState) {
  const auto law = make_contact_law("wirepm", backbone_parameters());
  EXPECT_EQ(law->name(), "wirepm");
  law->update(axial(u(3)));
  const auto copy = law->clone();
  law->update(axial(-1e-4));
  EXPECT_NEAR(copy->forces()(0), F(3), 1e-9 * F(3));
  EXPECT_NEAR(law->forces()(0), F(3) - kn() * 1e-4, 1e-9 * F(3));
}

}  // namespace
}  // namespace dtwire::dem
