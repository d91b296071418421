// The factory knows the laws by name and reports unknown names and missing fields.
#include <gtest/gtest.h>

#include "dtwire/dem/contact_law.hpp"
#include "dtwire/dem/law_schema.hpp"
#include "dtwire/dem/length_rescaling.hpp"
#include "dtwire_contact.h"
#include "law_test_support.hpp"

namespace dtwire::dem {
namespace {

TEST(LawFactory, CreatesTheMacroElementsAndTheParallelBond) {
  const ParameterMap thesis = test::thesis_parameters("double_twist");
  EXPECT_EQ(make_contact_law("thesis", thesis)->name(), "thesis");
  EXPECT_EQ(make_contact_law("macro3d", thesis)->name(), "macro3d");
  const ParameterMap bond = {{"E_Pa", 2e11}, {"diameter_m", 2.7e-3}, {"length_m", 0.04}};
  EXPECT_EQ(make_contact_law("parallel_bond", bond)->name(), "parallel_bond");
  // clone() keeps the state
  auto law = make_contact_law("macro3d", thesis);
  law->update(test::generalised(1e-5, 0.01));
  const auto copy = law->clone();
  EXPECT_EQ(copy->forces(), law->forces());
}

TEST(LawFactory, NamesTheMissingField) {
  ParameterMap thesis = test::thesis_parameters("single_wire");
  thesis.erase("m_g");
  try {
    make_contact_law("thesis", thesis);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("m_g"), std::string::npos);
  }
  EXPECT_THROW(make_contact_law("nonexistent", {}), std::invalid_argument);
}

std::string refusal(const std::string& law, const ParameterMap& parameters) {
  try {
    make_contact_law(law, parameters);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

// Issue 20: a misspelled name used to be ignored, leaving the law's default in place.
TEST(LawSchema, EveryLawRefusesANameItDoesNotRead) {
  ParameterMap thesis = test::thesis_parameters("double_twist");
  thesis["slideb"] = thesis.at("slide_b");
  for (const char* law : {"thesis", "macro3d"}) {
    const std::string message = refusal(law, thesis);
    EXPECT_NE(message.find("unknown parameter 'slideb'"), std::string::npos) << law << ": " << message;
    EXPECT_NE(message.find("slide_b"), std::string::npos) << "the names the law reads are listed";
  }
  const ParameterMap bond = {{"E_Pa", 2e11}, {"diameter_m", 2.7e-3}, {"length_m", 0.04}, {"tensile_strenght_Pa", 1e9}};
  EXPECT_NE(refusal("parallel_bond", bond).find("'tensile_strenght_Pa'"), std::string::npos);
  const ParameterMap wirepm = {{"reference_length_m", 0.06}, {"diameter_m", 2.7e-3},  {"backbone_0_strain_1", 0.01},
                               {"backbone_0_stress_Pa", 1e9}, {"backbone_1_strain_1", 0.05}, {"backbone_1_stress_Pa", 1.2e9},
                               {"lambda_eps_1", 0.5}};
  EXPECT_NE(refusal("wirepm", wirepm).find("'lambda_eps_1'"), std::string::npos);
}

TEST(LawSchema, AcceptsEveryNameThePublishedSetsAndTheLawsRead) {
  for (const char* wire : {"single_wire", "double_twist"}) {
    const ParameterMap thesis = test::thesis_parameters(wire);  // includes reference_length_m, slide_a/b
    EXPECT_TRUE(unknown_law_parameters("thesis", thesis).empty()) << wire;
    EXPECT_TRUE(unknown_law_parameters("macro3d", thesis).empty()) << wire;
  }
  // macro3d's own SI names, and WirePM's backbone points by pattern (any index, not a look-alike).
  EXPECT_TRUE(is_law_parameter("macro3d", "bending_stiffness_Nm_per_rad"));
  EXPECT_TRUE(is_law_parameter("wirepm", "backbone_12_stress_Pa"));
  EXPECT_FALSE(is_law_parameter("wirepm", "backbone_x_stress_Pa"));
  EXPECT_FALSE(is_law_parameter("wirepm", "backbone_1_stress_MPa"));
  EXPECT_FALSE(is_law_parameter("thesis", "backbone_1_stress_Pa"));
  // Every name of the schema is one the law takes without complaint (no stale entry).
  ParameterMap thesis = test::thesis_parameters("single_wire");
  // rk_tolerance, the damage mode and the shear spring, which the set lacks (the switches at a value
  // they take: beam_shear 0 with a given shear_stiffness_N_per_m).
  for (const std::string& name : law_parameter_names("thesis"))
    if (!thesis.count(name)) thesis[name] = name == "damage_scales_forces" || name == "beam_shear" ? 0.0 : 1e-6;
  EXPECT_NO_THROW(make_contact_law("thesis", thesis));
  EXPECT_THROW(law_parameter_names("thesys"), std::invalid_argument);
}

TEST(LawSchema, TheCAbiRefusesTheSameNames) {
  const char* names[] = {"E_Pa", "diameter_m", "length_m", "poison_1"};
  const double values[] = {2e11, 2.7e-3, 0.04, 0.3};
  EXPECT_EQ(dtwire_bond_create("parallel_bond", names, values, 4), nullptr);
  EXPECT_NE(std::string(dtwire_contact_last_error()).find("unknown parameter 'poison_1'"), std::string::npos)
      << dtwire_contact_last_error();
  dtwire_bond* bond = dtwire_bond_create("parallel_bond", names, values, 3);
  EXPECT_NE(bond, nullptr);
  dtwire_bond_destroy(bond);
}

// A set calibrated on a 0.06 m bond carried to a 0.05 m link at equal strain: stiffnesses and
// k_F x 1.2, damage works / 1.2, forces kept; a pull to the same strain then gives the same
// force (the elastic branch: N = EA' u' = EA (L_ref/L) (eps L) = EA eps L_ref).
TEST(LengthRescaling, EqualStrainGivesEqualForceAndWorkPerLength) {
  const ParameterMap set = test::thesis_parameters("single_wire");
  const ParameterMap link = rescale_to_link_length(set, 0.05);
  EXPECT_DOUBLE_EQ(link.at("EA_N"), set.at("EA_N") * 1.2);
  EXPECT_DOUBLE_EQ(link.at("EI_Nm2_per_deg_convention"), set.at("EI_Nm2_per_deg_convention") * 1.2);
  EXPECT_DOUBLE_EQ(link.at("k_F"), set.at("k_F") * 1.2);
  EXPECT_DOUBLE_EQ(link.at("k_M"), set.at("k_M") * 1.2);
  EXPECT_DOUBLE_EQ(link.at("W1_J"), set.at("W1_J") / 1.2);
  EXPECT_DOUBLE_EQ(link.at("N0_N"), set.at("N0_N"));
  EXPECT_DOUBLE_EQ(link.at("reference_length_m"), 0.05);
  const double strain = 1e-4;  // elastic
  auto force = [&](const ParameterMap& p, double length) {
    auto law = make_contact_law("thesis", p);
    law->update(test::generalised(strain * length, 0.0));
    return law->forces()[0];
  };
  EXPECT_NEAR(force(link, 0.05), force(set, 0.06), 1e-9 * force(set, 0.06));
  // Bent to the same curvature well past the moment capacity, with a slow moment hardening
  // (k_M 0.5 per degree, so that the plastic rotation's hardening shows): the same moment.
  ParameterMap slow = set;
  slow["k_M"] = 0.5;
  const ParameterMap slow_link = rescale_to_link_length(slow, 0.05);
  const double curvature_deg_per_m = 500.0;  // 30 deg over the 0.06 m bond (first yield near 10 deg)
  auto moment = [&](const ParameterMap& p, double length) {
    auto law = make_contact_law("thesis", p);
    for (int k = 1; k <= 200; ++k) law->update(test::generalised(0.0, curvature_deg_per_m * length / 200 * M_PI / 180));
    return law->forces()[4];
  };
  EXPECT_NEAR(moment(slow_link, 0.05), moment(slow, 0.06), 1e-6 * std::abs(moment(slow, 0.06)));
  ParameterMap no_length = set;
  no_length.erase("reference_length_m");
  EXPECT_THROW(rescale_to_link_length(no_length, 0.05), std::invalid_argument);
  EXPECT_THROW(rescale_to_link_length(set, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::dem
