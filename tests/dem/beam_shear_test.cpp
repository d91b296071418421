// The bond's shear spring (`beam_shear`, docs/dem_laws.md "Shear spring"). The engine's bond is
// two rigid halves joined at its midpoint by a shear spring k_s and a bending spring k_b. With the
// slender beam's k_s = 12 k_b / L^2 (k_b = EI / L) a chain of bonds is a chain of Euler-Bernoulli
// beam elements, whose nodal displacements under nodal loads are exact:
//   - one bond, clamped at a, tip load P: w = P L^3 / (3 EI), tip rotation P L^2 / (2 EI);
//   - two half-bonds (three nodes per wire), loads P_m at the middle and P_b at the tip:
//     w(x) = P a^2 (3x - a) / (6 EI) for x >= a, P x^2 (3a - x) / (6 EI) for x <= a, summed.
// With the plugin's k_s = k_EA / 2.6 the same bond is stiffer: P L^2 / (4 k_b) + P / k_s.
// Both laws that read the key (thesis, macro3d) are checked, and the key's misuses refused.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>

#include "net_node_support.hpp"
#include "dtwire/dem/engine.hpp"
#include "dtwire/dem/length_rescaling.hpp"

namespace dtwire::dem {
namespace {

constexpr double kDegreesPerRadian = 57.295779513082320876798154814105;

// The thesis's single-wire set (experiments/data/macroelement_thesis_params.json, single_wire),
// reference length 0.06 m; `length` replaces it (the bond's L in 12 EI / L^3).
ParameterMap thesis_single_wire(double length) {
  return {{"reference_length_m", length}, {"D_m", 0.0027}, {"EA_N", 1.6e7}, {"EI_Nm2_per_deg_convention", 0.122},
          {"N0_N", 2750}, {"Nult_N", 3200}, {"Nc_N", 1650}, {"m_f", 0.0285}, {"beta_f", 0.195}, {"k_F", 2.39e4},
          {"k_M", 1.12e3}, {"m_g", 4.78}, {"alpha_g", 0.5}, {"beta_g", 0.0358}, {"W1_J", 9.21}, {"W2_J", 140.01},
          {"alpha_d", 2.7}, {"slide_a", 0.0}, {"slide_b", 0.0}};
}

struct Deflections {
  double tip = 0.0, middle = 0.0, tip_rotation = 0.0;  // [m], [m], [rad]
};

// A cantilever along x clamped at x = 0 (node a pinned: translations and spin held), loaded
// across by gravity on its free nodes' masses; `parts` bonds of the set split in series.
Deflections cantilever(const std::string& law, const ParameterMap& set, double length, int parts, double tip_mass,
                       double middle_mass) {
  const double h = length / parts;
  std::vector<NetNode> nodes{test::make_node(Vector3(0, 0, 0), tip_mass, NodeFixity::Pinned)};
  for (int i = 1; i <= parts; ++i)
    nodes.push_back(test::make_node(Vector3(i * h, 0, 0), i == parts ? tip_mass : middle_mass, NodeFixity::Free));
  const ParameterMap part = split_in_series(law, set, parts);
  std::vector<EngineLink> links;
  for (int i = 0; i < parts; ++i)
    links.push_back({{i, i + 1, LinkTag::SingleWire, 0, parts}, make_contact_law(law, part)});
  EngineOptions options;
  options.gravity = Vector3(0, 0, -9.81);
  options.local_damping = 0.7;
  Engine engine(nodes, std::move(links), options);
  const RelaxResult relaxed = engine.relax(1e-10, 5000000);
  EXPECT_TRUE(relaxed.converged) << law << ": force ratio " << relaxed.force_ratio;
  Deflections d;
  d.tip = -engine.position(parts).z();
  if (parts == 2) d.middle = -engine.position(1).z();
  const Vector3 chord = engine.position(parts) - engine.position(parts - 1);
  d.tip_rotation = std::atan2(-chord.z(), chord.x());  // the last bond's chord, for one bond
  return d;
}

TEST(DemBeamShear, OneBondWithTheBeamsShearSpringIsTheEulerBernoulliCantilever) {
  const double length = 0.05, tip_mass = 0.05, P = tip_mass * 9.81;
  for (const std::string law : {"thesis", "macro3d"}) {
    ParameterMap set = thesis_single_wire(length);
    set["beam_shear"] = 1.0;
    const double EI = set.at("EI_Nm2_per_deg_convention") * kDegreesPerRadian * length;
    const Deflections d = cantilever(law, set, length, 1, tip_mass, 0.0);
    const double tip = P * std::pow(length, 3) / (3.0 * EI);
    std::cout << law << ", one bond, beam shear: tip " << d.tip * 1e3 << " mm (Euler-Bernoulli " << tip * 1e3
              << " mm)\n";
    // Small rotations (about 4e-3 rad): second-order terms near 1e-5 of the deflection.
    EXPECT_NEAR(d.tip / tip, 1.0, 1e-4) << law;

    // The plugin's shear spring: the bond's own closed form, 3/4 of the beam and the shear.
    set.erase("beam_shear");
    const double k_bend = EI / length, k_shear = set.at("EA_N") / 2.6;
    const double plugin_tip = P * length * length / (4.0 * k_bend) + P / k_shear;
    const Deflections p = cantilever(law, set, length, 1, tip_mass, 0.0);
    std::cout << law << ", one bond, plugin shear: tip " << p.tip * 1e3 << " mm (closed form " << plugin_tip * 1e3
              << " mm, " << plugin_tip / tip << " x Euler-Bernoulli)\n";
    EXPECT_NEAR(p.tip / plugin_tip, 1.0, 1e-4) << law;
  }
}

TEST(DemBeamShear, TwoHalfBondsGiveTheBeamsDeflectionsAtBothNodes) {
  const double length = 0.05, h = 0.5 * length, g = 9.81;
  const double tip_mass = 0.05, middle_mass = 0.01, P_b = tip_mass * g, P_m = middle_mass * g;
  for (const std::string law : {"thesis", "macro3d"}) {
    ParameterMap set = thesis_single_wire(length);
    set["beam_shear"] = 1.0;
    const double EI = set.at("EI_Nm2_per_deg_convention") * kDegreesPerRadian * length;
    const Deflections d = cantilever(law, set, length, 2, tip_mass, middle_mass);
    const double tip = P_b * std::pow(length, 3) / (3.0 * EI) + P_m * h * h * (3.0 * length - h) / (6.0 * EI);
    const double middle = P_b * h * h * (3.0 * length - h) / (6.0 * EI) + P_m * std::pow(h, 3) / (3.0 * EI);
    std::cout << law << ", two half-bonds, beam shear: tip " << d.tip * 1e3 << " mm (Euler-Bernoulli " << tip * 1e3
              << "), middle " << d.middle * 1e3 << " mm (" << middle * 1e3 << ")\n";
    EXPECT_NEAR(d.tip / tip, 1.0, 1e-4) << law;
    EXPECT_NEAR(d.middle / middle, 1.0, 1e-4) << law;
  }
}

TEST(DemBeamShear, TheKeysMisusesAreRefusedByName) {
  ParameterMap set = thesis_single_wire(0.06);
  for (const std::string law : {"thesis", "macro3d"}) {
    set["beam_shear"] = 2.0;
    EXPECT_THROW(make_contact_law(law, set), std::invalid_argument) << law;
    set["beam_shear"] = 1.0;
    set["shear_stiffness_N_per_m"] = 1e5;
    EXPECT_THROW(make_contact_law(law, set), std::invalid_argument) << law;
    set.erase("shear_stiffness_N_per_m");
    ParameterMap without_length = set;
    without_length.erase("reference_length_m");
    try {
      make_contact_law(law, without_length);
      ADD_FAILURE() << law << ": beam_shear without a reference length was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("reference_length_m"), std::string::npos) << e.what();
    }
    set.erase("beam_shear");
  }
}

}  // namespace
}  // namespace dtwire::dem
