// Three nodes per wire (`[mesh] nodes_per_wire = 3`, Previtali ch. 3.4 study 1): a wire split at
// its midpoint into two half-links in series, each with the set of split_in_series
// (dtwire/dem/length_rescaling.hpp).
//   - Axial: the split wire pulled by its ends follows the whole link's force-elongation curve,
//     elastic and into plasticity before damage.
//   - Series at law level, every law: a part fed half the increments of a mixed axial-bending
//     path gives the whole link's forces and moments (the contract of split_in_series).
//   - Bending: a cantilever of two half-links under tip and middle loads against the closed form
//     of its discrete beam, and against the Euler-Bernoulli beam of the set's EI.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "net_node_support.hpp"
#include "dtwire/dem/engine.hpp"
#include "dtwire/dem/length_rescaling.hpp"
#include "dtwire/dem/thesis_macroelement.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegreesPerRadian = 180.0 / kPi;

// The thesis's single-wire set (experiments/data/macroelement_thesis_params.json, single_wire).
ParameterMap thesis_single_wire() {
  return {{"reference_length_m", 0.06}, {"D_m", 0.0027}, {"EA_N", 1.6e7}, {"EI_Nm2_per_deg_convention", 0.122},
          {"N0_N", 2750}, {"Nult_N", 3200}, {"Nc_N", 1650}, {"m_f", 0.0285}, {"beta_f", 0.195}, {"k_F", 2.39e4},
          {"k_M", 1.12e3}, {"m_g", 4.78}, {"alpha_g", 0.5}, {"beta_g", 0.0358}, {"W1_J", 9.21}, {"W2_J", 140.01},
          {"alpha_d", 2.7}, {"slide_a", 0.0}, {"slide_b", 0.0}};
}

using test::make_node;

struct PullCurve {
  std::vector<double> elongation, force;  // [m], [N]
  double plastic_elongation = 0.0, damage_factor = 1.0;  // of the (first) link at the end
};

// A 50 mm SW wire along x pulled to `travel` at `speed`; `split`: two half-links through a
// middle node. `symmetric`: both ends move apart at speed / 2 (the middle node stays at rest
// by symmetry, so the comparison sees the split of the set alone); otherwise node a is pinned
// and node b pulled, the middle node free (its inertia and damping enter). Every engine runs
// at the same fixed step, so the curves are sampled at the same elongations.
PullCurve pull(bool split, bool symmetric, double speed, double travel, double time_step) {
  const double length = 0.05, mass = 0.0022;
  const ParameterMap set = thesis_single_wire();
  std::vector<NetNode> nodes{make_node(Vector3(-0.5 * length, 0, 0), mass, symmetric ? NodeFixity::Guided : NodeFixity::Pinned),
                             make_node(Vector3(0.5 * length, 0, 0), mass, NodeFixity::Guided)};
  nodes[0].guided_velocity = Vector3(symmetric ? -0.5 * speed : 0.0, 0, 0);
  nodes[1].guided_velocity = Vector3(symmetric ? 0.5 * speed : speed, 0, 0);
  std::vector<EngineLink> links;
  if (split) {
    nodes.push_back(make_node(Vector3::Zero(), 0.5 * mass, NodeFixity::Free));
    const ParameterMap half = split_in_series("thesis", set, 2);
    links.push_back({{0, 2, LinkTag::SingleWire, 0, 2}, make_contact_law("thesis", half)});
    links.push_back({{2, 1, LinkTag::SingleWire, 0, 2}, make_contact_law("thesis", half)});
  } else {
    links.push_back({{0, 1, LinkTag::SingleWire}, make_contact_law("thesis", set)});
  }
  EngineOptions options;
  options.gravity = Vector3::Zero();
  options.local_damping = 0.7;
  options.time_step = time_step;
  Engine engine(nodes, std::move(links), options);
  PullCurve curve;
  const int samples = 200;
  const long steps = std::lround(travel / speed / time_step);
  for (long n = 1; n <= steps; ++n) {
    engine.step();
    if (n % (steps / samples) == 0) {
      curve.elongation.push_back(engine.link_law_length(0) + (split ? engine.link_law_length(1) : 0.0) - length);
      curve.force.push_back(engine.link(0).law->forces()[0]);
    }
  }
  const auto& law = dynamic_cast<const ThesisMacroElement&>(*engine.link(0).law);
  curve.plastic_elongation = law.plastic_elongation() * (split ? 2.0 : 1.0);
  curve.damage_factor = law.damage_factor();
  return curve;
}

double largest_relative_difference(const PullCurve& a, const PullCurve& b) {
  double largest = 0.0, peak = 0.0;
  for (double f : a.force) peak = std::max(peak, std::abs(f));
  for (std::size_t i = 0; i < a.force.size(); ++i) largest = std::max(largest, std::abs(a.force[i] - b.force[i]) / peak);
  return largest;
}

TEST(DemWireSplit, SplitSingleWirePulledAxiallyFollowsTheWholeLink) {
  // 2 mm over 50 mm: 0.17 mm elastic (N0 / EA), then hardening to 3.2 kN; the plastic work
  // (about 5 J) stays below W1 = 9.21 J, so no damage.
  const double speed = 0.01, travel = 0.002, time_step = 1e-6;
  const PullCurve whole = pull(false, true, speed, travel, time_step);
  const PullCurve split = pull(true, true, speed, travel, time_step);
  ASSERT_EQ(whole.force.size(), split.force.size());
  EXPECT_GT(whole.force.back(), 2750.0 + 0.9 * (3200.0 - 2750.0));  // hardened towards Nult
  EXPECT_GT(whole.plastic_elongation, 0.0015);
  EXPECT_EQ(whole.damage_factor, 1.0);
  for (std::size_t i = 0; i < whole.force.size(); ++i) {
    EXPECT_NEAR(split.elongation[i], whole.elongation[i], 1e-12) << "sample " << i;
    EXPECT_NEAR(split.force[i], whole.force[i], 1e-6 * std::abs(whole.force[i])) << "sample " << i;
  }
  EXPECT_NEAR(split.plastic_elongation, whole.plastic_elongation, 1e-6 * whole.plastic_elongation);
  const double symmetric_gap = largest_relative_difference(whole, split);

  // One end pinned, the middle node free: it lags by its inertia (mass x acceleration at the
  // elastic-plastic knee) and by the damping; quasi-static at 1 cm/s within 1e-3 of the force.
  const PullCurve whole_pinned = pull(false, false, speed, travel, time_step);
  const PullCurve split_pinned = pull(true, false, speed, travel, time_step);
  const double free_gap = largest_relative_difference(whole_pinned, split_pinned);
  std::cout << "split vs whole wire, largest force difference / peak: symmetric pull " << symmetric_gap
            << ", free middle node " << free_gap << "\n";
  EXPECT_LT(free_gap, 1e-3);
}

// The contract of split_in_series for each law: along a path of stretch and bending into
// plasticity, a part fed 1/n of each increment carries the whole link's forces and moments.
TEST(DemWireSplit, EachLawsPartsInSeriesReproduceTheWholeLink) {
  ParameterMap coupled = thesis_single_wire();
  coupled["bending_axial_coupling"] = 1.0;
  const std::vector<std::pair<std::string, ParameterMap>> sets = {
      {"thesis", thesis_single_wire()},
      {"macro3d", thesis_single_wire()},
      {"macro3d", coupled},
      {"parallel_bond", {{"E_Pa", 2e11}, {"diameter_m", 0.0027}, {"length_m", 0.05}}}};
  for (const auto& [law, set] : sets) {
    for (int parts : {2, 3}) {
      std::unique_ptr<ContactLaw> whole = make_contact_law(law, set);
      std::unique_ptr<ContactLaw> part = make_contact_law(law, split_in_series(law, set, parts));
      double largest = 0.0, scale = 0.0;
      // 300 increments: a stretch of 2.4 mm (thesis, macro3d: yield at 0.17 mm) with a bending
      // rotation of 0.24 rad and a small shear, then a fifth of it back.
      const double stretch_step = 1e-5;
      for (int i = 0; i < 300; ++i) {
        Vector6 increment;
        const double sign = i < 240 ? 1.0 : -1.0;
        increment << sign * stretch_step, sign * 1e-7, 0.0, 0.0, sign * 1e-3, sign * 2e-4;
        whole->update(increment);
        part->update(increment / parts);
        const Vector6 w = whole->forces(), p = part->forces();
        scale = std::max(scale, w.cwiseAbs().maxCoeff());
        for (int c = 0; c < 6; ++c) largest = std::max(largest, std::abs(w[c] - p[c]) / std::max(std::abs(w[c]), 1e-3 * scale));
      }
      std::cout << law << (set.count("bending_axial_coupling") ? " (coupled)" : "") << ", " << parts
                << " parts: largest relative difference " << largest << ", largest force " << scale << "\n";
      EXPECT_LT(largest, 1e-6) << law << " in " << parts << " parts";
      EXPECT_FALSE(whole->broken());
    }
  }
  EXPECT_THROW(split_in_series("thesis", thesis_single_wire(), 0), std::invalid_argument);
  EXPECT_THROW(split_in_series("wirepm", {{"reference_length_m", 0.05}, {"diameter_m", 0.0027}}, 2), std::invalid_argument);
  EXPECT_THROW(split_in_series("parallel_bond", {{"E_Pa", 2e11}, {"diameter_m", 0.0027}}, 2), std::invalid_argument);
  EXPECT_THROW(split_in_series("rigid", {}, 2), std::invalid_argument);
}

// A cantilever of two half-links (the wire of length L = 2h clamped at node a, middle node m,
// tip b) under gravity across it, P_m = m_m g at the middle and P_b = m_b g at the tip. The
// engine's bond is two rigid half-segments joined at the link's midpoint by a shear spring
// k_s and a bending spring k_b, so the chain is rigid bodies with springs at x = h/2 and 3h/2
// carrying V_1 = P_m + P_b, M_1 = P_m h/2 + 3 P_b h/2 and V_2 = P_b, M_2 = P_b h/2:
//   w_b = (M_1/k_b) 3h/2 + (M_2/k_b) h/2 + (V_1 + V_2)/k_s,   w_m = (M_1/k_b) h/2 + V_1/k_s.
// Each half has k_b = 2 k_EI (per radian) and k_s = 2 k_EA / 2.6 (the thesis law's shear). With
// the set's beam stiffness EI = k_EI L (the whole link's bending spring EI / L), the
// Euler-Bernoulli tip deflection under a tip load is P L^3 / (3 EI); the discrete beam bends by
// 5/16 instead of 1/3 of it (6.25 % stiffer, the midpoint rule's error on two segments).
TEST(DemWireSplit, MiddleNodeGivesTheWireBeamBendingStiffness) {
  const double length = 0.05, h = 0.5 * length, g = 9.81;
  const double tip_mass = 0.05, middle_mass = 0.01;  // loads 0.49 N and 0.098 N
  const ParameterMap set = thesis_single_wire();
  const ParameterMap half = split_in_series("thesis", set, 2);
  std::vector<NetNode> nodes{make_node(Vector3(0, 0, 0), tip_mass, NodeFixity::Pinned),
                             make_node(Vector3(h, 0, 0), middle_mass, NodeFixity::Free),
                             make_node(Vector3(length, 0, 0), tip_mass, NodeFixity::Free)};
  std::vector<EngineLink> links;
  links.push_back({{0, 1, LinkTag::SingleWire, 0, 2}, make_contact_law("thesis", half)});
  links.push_back({{1, 2, LinkTag::SingleWire, 0, 2}, make_contact_law("thesis", half)});
  EngineOptions options;
  options.gravity = Vector3(0, 0, -g);
  options.local_damping = 0.7;
  Engine engine(nodes, std::move(links), options);
  const RelaxResult relaxed = engine.relax(1e-9, 5000000);
  ASSERT_TRUE(relaxed.converged) << relaxed.force_ratio;

  const double k_bend = 2.0 * set.at("EI_Nm2_per_deg_convention") * kDegreesPerRadian;
  const double k_shear = 2.0 * set.at("EA_N") / 2.6;
  const double P_m = middle_mass * g, P_b = tip_mass * g;
  const double V1 = P_m + P_b, M1 = P_m * h / 2 + 1.5 * P_b * h, V2 = P_b, M2 = P_b * h / 2;
  const double tip = (M1 / k_bend) * 1.5 * h + (M2 / k_bend) * 0.5 * h + (V1 + V2) / k_shear;
  const double middle = (M1 / k_bend) * 0.5 * h + V1 / k_shear;
  const double tip_measured = -engine.position(2).z(), middle_measured = -engine.position(1).z();
  std::cout << "cantilever of two half-links: tip " << tip_measured * 1e3 << " mm (closed form " << tip * 1e3
            << "), middle " << middle_measured * 1e3 << " mm (closed form " << middle * 1e3 << ")\n";
  // Small rotations (tip 0.06 mm over 50 mm, about 2e-3 rad: second-order terms near 1e-6);
  // measured 2e-6 apart.
  EXPECT_NEAR(tip_measured / tip, 1.0, 1e-4);
  EXPECT_NEAR(middle_measured / middle, 1.0, 1e-4);

  // The tip load alone against the Euler-Bernoulli cantilever of the set's EI.
  const double EI = set.at("EI_Nm2_per_deg_convention") * kDegreesPerRadian * length;
  const double euler_bernoulli = P_b * std::pow(length, 3) / (3.0 * EI);
  const double discrete_tip_load = (1.5 * P_b * h / k_bend) * 1.5 * h + (M2 / k_bend) * 0.5 * h + 2.0 * P_b / k_shear;
  std::cout << "tip load alone: discrete beam " << discrete_tip_load * 1e3 << " mm, Euler-Bernoulli "
            << euler_bernoulli * 1e3 << " mm (ratio " << discrete_tip_load / euler_bernoulli << ")\n";
  EXPECT_NEAR(discrete_tip_load / euler_bernoulli, 15.0 / 16.0, 0.005);  // 5/16 of 1/3, plus 0.2 % of shear
  // The whole elastic: the moment at the root stays far inside the yield surface.
  EXPECT_EQ(dynamic_cast<const ThesisMacroElement&>(*engine.link(0).law).plastic_rotation(), 0.0);
}

}  // namespace
}  // namespace dtwire::dem
