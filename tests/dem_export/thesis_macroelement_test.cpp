// The thesis macro-element against its published driver loadings (Previtali thesis; PFC7
// plugin example_cases/2ball_driver): (a) axial pull, (b) compression, (c) spin, (d) pull + spin,
// (e) free oscillation, with the published single-wire calibration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dtwire/dem/thesis_macroelement.hpp"
#include "law_test_support.hpp"

namespace dtwire::dem {
namespace {

using test::pi;

struct ThesisFixture : ::testing::Test {
  ParameterMap p = test::thesis_parameters("single_wire");
  double k_axial() const { return p.at("EA_N"); }
  double k_moment_per_rad() const { return p.at("EI_Nm2_per_deg_convention") * 180.0 / pi; }
  double Ny_of(double a_u, double a_w_deg) const {
    const double eta = 1.0 - std::exp(-p.at("k_F") * a_u - p.at("k_M") * a_w_deg);
    return p.at("N0_N") + eta * (p.at("Nult_N") - p.at("N0_N"));
  }
  double moment_capacity(double Ny) const { return p.at("D_m") * std::sqrt(p.at("m_f")) * Ny; }
};

// (a) Pure tension: elastic up to N0, then F = N_y(u_p) -> Nult.
TEST_F(ThesisFixture, PureTensionYieldsAtN0AndHardensTowardNult) {
  ThesisMacroElement law(p);
  double u = 0.0;
  const double step = 2e-6;
  bool yielded = false;
  for (int i = 0; i < 1450; ++i) {  // 2.9 mm: plastic work stays below W1 (no damage yet)
    law.update(test::generalised(step, 0.0));
    u += step;
    const double F = law.forces()[0];
    EXPECT_EQ(law.forces()[4], 0.0);  // no moment appears on a pure pull
    if (law.plastic_elongation() == 0.0) {
      EXPECT_LE(F, p.at("N0_N") * (1.0 + 1e-12));                // tol: round-off
      EXPECT_NEAR(F, k_axial() * u, 1e-12 * k_axial() * u);      // tol: round-off
      continue;
    }
    if (!yielded) {  // first plastic step: starts from the surface at N0
      yielded = true;
      EXPECT_NEAR(u - law.plastic_elongation() - F / k_axial(), 0.0, 1e-15);
    }
    // On the surface: F = N_y(u_p); tol 1e-6 relative (RK tolerance, no drift correction).
    EXPECT_NEAR(F, Ny_of(law.plastic_elongation(), 0.0), 1e-6 * F);
    // Closed form: u = u_p + N_y(u_p) / k, solved for u_p by Newton.
    double up = law.plastic_elongation();
    for (int it = 0; it < 50; ++it) {
      const double decay = std::exp(-p.at("k_F") * up);
      const double g = up + Ny_of(up, 0.0) / k_axial() - u;
      const double dg = 1.0 + p.at("k_F") * decay * (p.at("Nult_N") - p.at("N0_N")) / k_axial();
      up -= g / dg;
    }
    EXPECT_NEAR(F, Ny_of(up, 0.0), 1e-6 * F);  // tol: RK tolerance 1e-6
  }
  EXPECT_TRUE(yielded);
  EXPECT_EQ(law.damage_factor(), 1.0);
  EXPECT_LE(law.damage_work(), p.at("W1_J"));
  // Hardened to the ultimate strength (exp(-k_F u_p) ~ e^-60); tol 1e-6 relative.
  EXPECT_NEAR(law.forces()[0], p.at("Nult_N"), 1e-6 * p.at("Nult_N"));
}

// (c) Spin at fixed length: F stays 0 (dg/dF = 0 at F = 0 for alpha_g = 1/2) and the moment
// capacity is D sqrt(m_f) N_y, starting at N_y = N0; the reversal yields at -D sqrt(m_f) N_y.
TEST_F(ThesisFixture, MomentCapacityAtZeroForceIsDSqrtMfNy) {
  ThesisMacroElement law(p);
  test::PathBuilder path;
  path.to(test::generalised(0.0, 0.25), 500).to(test::generalised(0.0, -0.22), 940);
  double largest_elastic_moment = 0.0;
  int plastic_steps_positive = 0, plastic_steps_negative = 0;
  double previous_rotation_p = 0.0;
  test::run(law, path.increments, [&](std::size_t) {
    const double M = law.forces()[4];
    EXPECT_LE(std::abs(law.forces()[0]), 1e-9);  // tol: F stays 0 N (round-off)
    ASSERT_EQ(law.damage_factor(), 1.0);         // the path stays below W1
    if (law.plastic_rotation() == 0.0) {
      largest_elastic_moment = std::max(largest_elastic_moment, std::abs(M));
      return;
    }
    if (law.plastic_rotation() != previous_rotation_p) {
      // Plastic step: |M| = D sqrt(m_f) N_y; tol 1e-6 relative (RK tolerance).
      EXPECT_NEAR(std::abs(M), moment_capacity(law.yield_strength()), 1e-6 * std::abs(M));
      (M > 0 ? plastic_steps_positive : plastic_steps_negative)++;
    }
    previous_rotation_p = law.plastic_rotation();
  });
  EXPECT_LE(largest_elastic_moment, moment_capacity(p.at("N0_N")) * (1.0 + 1e-12));  // tol round-off
  EXPECT_GT(plastic_steps_positive, 10);
  EXPECT_GT(plastic_steps_negative, 10);

  // Without hardening the capacity stays D sqrt(m_f) N0: a plateau from the crossing on.
  ParameterMap rigid_plastic = p;
  rigid_plastic["k_F"] = 0.0;
  rigid_plastic["k_M"] = 0.0;
  ThesisMacroElement plateau(rigid_plastic);
  int plateau_steps = 0;
  test::run(plateau, test::spin(0.25, 500), [&](std::size_t) {
    if (plateau.plastic_rotation() == 0.0) return;
    ++plateau_steps;
    // tol 1e-9 relative: crossing solved to 1e-14 in f, circular arc integrated exactly
    EXPECT_NEAR(plateau.forces()[4], moment_capacity(p.at("N0_N")), 1e-9 * moment_capacity(p.at("N0_N")));
  });
  EXPECT_GT(plateau_steps, 100);
}

// (b) Compression: elastic to -Nc, then a plateau at -Nc (the compression surface does not
// depend on the hardening at M = 0); bending on the plateau follows F^2/Nc^2 + (M/M_Y)^2 = 1.
TEST_F(ThesisFixture, CompressionPlateauAndCompressionBendingSurface) {
  ThesisMacroElement law(p);
  test::PathBuilder path;
  path.to(test::generalised(-1.0e-3, 0.0), 500).to(test::generalised(-1.0e-3, 0.3), 300);
  int plateau_steps = 0, bending_steps = 0;
  double previous_up = 0.0, previous_wp = 0.0;
  test::run(law, path.increments, [&](std::size_t i) {
    const Vector6 q = law.forces();
    EXPECT_GE(q[0], -p.at("Nc_N") * (1.0 + 1e-6));  // never beyond -Nc; tol RK 1e-6
    const bool plastic = law.plastic_elongation() != previous_up || law.plastic_rotation() != previous_wp;
    previous_up = law.plastic_elongation();
    previous_wp = law.plastic_rotation();
    if (!plastic) return;
    if (i < 500) {
      EXPECT_NEAR(q[0], -p.at("Nc_N"), 1e-6 * p.at("Nc_N"));  // plateau; tol RK 1e-6
      ++plateau_steps;
    } else {
      // Published compression surface; tol 1e-5 (drift of the uncorrected RK over the path).
      EXPECT_NEAR(test::published_surface(p, q[0], q[4], law.yield_strength()), 0.0, 1e-5);
      ++bending_steps;
    }
  });
  EXPECT_GT(plateau_steps, 400);
  EXPECT_GT(bending_steps, 10);
}

// (d) Pull + spin along radial paths: the first yield lies on the published surface (tension and
// compression branches), and plastic states stay on it.
TEST_F(ThesisFixture, RadialPathsYieldOnThePublishedSurface) {
  for (const double angle_deg : {-150.0, -120.0, -60.0, -30.0, 0.0, 20.0, 45.0, 70.0, 85.0}) {
    SCOPED_TRACE(angle_deg);
    ThesisMacroElement law(p);
    // Direction in (u / u_yield, theta / theta_yield) so every ray reaches the surface.
    const double u_scale = p.at("N0_N") / k_axial();
    const double theta_scale = moment_capacity(p.at("N0_N")) / k_moment_per_rad();
    const double a = angle_deg * pi / 180.0;
    const auto path = test::pull_spin(1.5 * u_scale * std::cos(a), 1.5 * theta_scale * std::sin(a), 600);
    bool yielded = false;
    test::run(law, path, [&](std::size_t) {
      const Vector6 q = law.forces();
      const double f = test::published_surface(p, q[0], q[4], law.yield_strength());
      if (law.plastic_elongation() == 0.0 && law.plastic_rotation() == 0.0) {
        EXPECT_LE(f, 1e-12);  // elastic states inside; tol round-off
      } else {
        yielded = true;
        EXPECT_NEAR(f, 0.0, 1e-5);  // on the surface; tol: uncorrected RK drift
      }
    });
    EXPECT_TRUE(yielded);
  }
}

// Damage starts at W1 (the factor is exactly 1 before) and the bond breaks when the factor
// reaches 0.01, i.e. at W1 + (W2 - W1) 0.99^(1/alpha_d) < W2.
TEST_F(ThesisFixture, DamageStartsAtW1AndBreaksByW2) {
  ThesisMacroElement law(p);
  const double W1 = p.at("W1_J"), W2 = p.at("W2_J"), alpha = p.at("alpha_d");
  const double W_break = W1 + (W2 - W1) * std::pow(0.99, 1.0 / alpha);
  double last_work_before_break = 0.0;
  bool damaged = false;
  for (int i = 0; i < 10000 && !law.broken(); ++i) {  // up to 100 mm in 0.01 mm steps
    last_work_before_break = law.damage_work();
    law.update(test::generalised(1e-5, 0.0));
    if (law.broken()) break;
    const double W = law.damage_work();
    if (W <= W1) {
      EXPECT_EQ(law.damage_factor(), 1.0);
    } else {
      damaged = true;
      // tol: round-off of the closed form
      EXPECT_NEAR(law.damage_factor(), 1.0 - std::pow((W - W1) / (W2 - W1), alpha), 1e-12);
      // tol 1e-5: drift of the uncorrected RK accumulated over thousands of plastic steps
      EXPECT_NEAR(law.forces()[0], law.damage_factor() * law.yield_strength(), 1e-5 * p.at("Nult_N"));
    }
  }
  EXPECT_TRUE(damaged);
  ASSERT_TRUE(law.broken());
  EXPECT_LT(last_work_before_break, W_break);
  EXPECT_GE(law.damage_work(), W_break);
  EXPECT_LE(law.damage_work(), W2);
  EXPECT_EQ(law.forces().norm(), 0.0);
}

// As the PFC7 plugin (damage_scales_forces = 0): the damage factor is tracked exactly as in the
// softening mode, but the transmitted force stays the undamaged one until the bond is deleted at
// the same plastic work; the energy account still closes (external = elastic + plastic + damage).
TEST_F(ThesisFixture, PluginDamageModeTransmitsUndamagedForceAndBreaksAtTheSameWork) {
  ParameterMap plugin = p;
  plugin["damage_scales_forces"] = 0.0;
  ThesisMacroElement softening(p), transmitting(plugin);
  bool damaged = false;
  int step = 0;
  for (; step < 10000 && !softening.broken(); ++step) {
    softening.update(test::generalised(1e-5, 0.0));
    transmitting.update(test::generalised(1e-5, 0.0));
    ASSERT_EQ(softening.broken(), transmitting.broken()) << "step " << step;
    if (softening.broken()) break;
    EXPECT_EQ(transmitting.damage_factor(), softening.damage_factor());
    // tol 1e-5: drift of the uncorrected RK (as DamageStartsAtW1AndBreaksByW2)
    if (transmitting.plastic_elongation() > 0.0) {
      EXPECT_NEAR(transmitting.forces()[0], transmitting.yield_strength(), 1e-5 * p.at("Nult_N"));
    }
    if (softening.damage_factor() < 1.0) {
      damaged = true;
      // tol: round-off; both modes integrate the same effective state
      EXPECT_NEAR(softening.forces()[0], softening.damage_factor() * transmitting.forces()[0], 1e-9 * p.at("Nult_N"));
      EXPECT_GT(transmitting.forces()[0], softening.forces()[0]);
    }
    const EnergyAccount e = transmitting.energy();
    // tol: round-off relative to the work done
    EXPECT_NEAR(e.external, e.elastic + e.plastic + e.damage, 1e-9 * std::max(1.0, e.external));
    EXPECT_EQ(e.damage, 0.0);  // nothing is softened before the bond is deleted
  }
  EXPECT_TRUE(damaged);
  ASSERT_TRUE(transmitting.broken());
  EXPECT_EQ(transmitting.forces().norm(), 0.0);
  const EnergyAccount e = transmitting.energy();
  EXPECT_GT(e.damage, 0.0);  // the stored energy is released at the deletion
  EXPECT_NEAR(e.external, e.plastic + e.damage, 1e-9 * e.external);
  EXPECT_THROW(ThesisMacroElement([&] { ParameterMap bad = p; bad["damage_scales_forces"] = 0.5; return bad; }()),
               std::invalid_argument);
}

// A ductility break (break_plastic_strain): the bond breaks in the increment where the plastic
// elongation reaches the strain times the reference length, long before the damage work W2.
TEST_F(ThesisFixture, PlasticStrainBreakAtTheGivenElongation) {
  ParameterMap ductile = p;
  ductile["break_plastic_strain"] = 0.05;  // 3 mm on the 0.06 m reference length
  ThesisMacroElement law(ductile);
  const double step = 1e-5, limit = 0.05 * p.at("reference_length_m");
  double last_plastic = 0.0;
  for (int i = 0; i < 10000 && !law.broken(); ++i) {
    last_plastic = law.plastic_elongation();
    law.update(test::generalised(step, 0.0));
  }
  ASSERT_TRUE(law.broken());
  EXPECT_LT(last_plastic, limit);
  EXPECT_GE(law.plastic_elongation(), limit);
  EXPECT_LT(law.plastic_elongation(), limit + step);  // within the increment that crossed it
  EXPECT_LT(law.damage_work(), p.at("W2_J"));
  EXPECT_EQ(law.forces().norm(), 0.0);
  const EnergyAccount e = law.energy();
  EXPECT_NEAR(e.external, e.plastic + e.damage, 1e-9 * e.external);  // tol: round-off
  ParameterMap no_length = ductile;
  no_length.erase("reference_length_m");
  EXPECT_THROW(ThesisMacroElement{no_length}, std::invalid_argument);
}

// (e) Free oscillation of a node on the bond (axial and rotational, symplectic Euler): the first
// swing yields; the forces always follow the sign of the elastic displacement (no spurious sign
// inversion), the mechanical energy never grows, and the late elastic swings are symmetric.
TEST_F(ThesisFixture, FreeOscillationHasNoSignFlip) {
  ThesisMacroElement law(p);
  const double mass = 4.3e-3, inertia = 5.0e-8;  // Thoeni 2013 net node
  const double period_axial = 2.0 * pi * std::sqrt(mass / k_axial());
  const double period_rotation = 2.0 * pi * std::sqrt(inertia / k_moment_per_rad());
  const double dt = std::min(period_axial, period_rotation) / 400.0;
  double velocity = 12.0, spin_rate = 2.0 * pi / period_rotation * 0.25;  // both first swings yield
  double u = 0.0, theta = 0.0;
  const double initial_energy = 0.5 * mass * velocity * velocity + 0.5 * inertia * spin_rate * spin_rate;
  const int steps = static_cast<int>(20.0 * period_rotation / dt);
  double late_max = 0.0, late_min = 0.0;
  for (int i = 0; i < steps; ++i) {
    const Vector6 q = law.forces();
    velocity -= q[0] / mass * dt;
    spin_rate -= q[4] / inertia * dt;
    law.update(test::generalised(velocity * dt, spin_rate * dt));
    u += velocity * dt;
    theta += spin_rate * dt;
    const Vector6 now = law.forces();
    // Sign follows the elastic displacement: N = k (u - u_p), M = k_M (theta - theta_p).
    const double d = law.damage_factor();
    EXPECT_NEAR(now[0], d * k_axial() * (u - law.plastic_elongation()), 1e-6 * p.at("N0_N"));  // tol: round-off of sums
    EXPECT_NEAR(now[4], d * k_moment_per_rad() * (theta - law.plastic_rotation()),
                1e-9 * moment_capacity(p.at("N0_N")));  // tol: round-off of sums
    const double energy = 0.5 * mass * velocity * velocity + 0.5 * inertia * spin_rate * spin_rate +
                          law.energy().elastic;
    EXPECT_LE(energy, initial_energy * 1.01);  // tol: 1 % modified-energy wobble of symplectic Euler
    if (i > steps / 2) {
      late_max = std::max(late_max, now[4]);
      late_min = std::min(late_min, now[4]);
    }
  }
  EXPECT_GT(std::abs(law.plastic_rotation()), 0.0);  // the first swing did yield
  EXPECT_GT(late_max, 0.0);
  EXPECT_LT(late_min, 0.0);
  // The late swings are elastic about theta_p: symmetric peaks; tol 2 % (sampling of the peak).
  EXPECT_NEAR(late_max, -late_min, 0.02 * late_max);
}

}  // namespace
}  // namespace dtwire::dem
