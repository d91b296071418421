// The JSON contract of `dtwire gap --json` (docs/gap.md): keys and types, parsed back.
#include <gtest/gtest.h>

#include <random>

#include <nlohmann/json.hpp>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

TEST(GapJsonContract, KeysAndTypesAfterARoundTrip) {
  const ForceCurve sim = voce_tension_curve();
  const ForceCurve lab_model = apply_effects(sim, {{&find_effect("machine_compliance"), {0.5}}},
                                             curve_scale(sim));
  std::mt19937 rng(3);
  LabSampling s;
  s.points = 500;
  s.noise_sigma_N = 5.0;
  ForceCurve lab1 = sample_lab_curve(lab_model, s, rng);
  ForceCurve lab2 = sample_lab_curve(lab_model, s, rng);
  lab1.source = "lab1.csv";
  lab2.source = "lab2.csv";
  DiagnosisOptions options;
  options.effects = {"machine_compliance", "gauge_length", "wire_friction"};
  const Diagnosis d = diagnose({lab1, lab2}, sim, options);
  const auto j = nlohmann::json::parse(diagnosis_json(d).dump());

  ASSERT_TRUE(j.at("metric").is_string());
  ASSERT_TRUE(j.at("noise_floor").is_number());
  ASSERT_TRUE(j.at("gap_before").is_number());
  ASSERT_TRUE(j.at("cause").is_string());
  ASSERT_TRUE(j.at("where").is_array());
  ASSERT_FALSE(j.at("where").empty());
  for (const auto& w : j.at("where")) {
    EXPECT_TRUE(w.at("region").is_string());
    EXPECT_TRUE(w.at("from_mm").is_number());
    EXPECT_TRUE(w.at("to_mm").is_number());
    EXPECT_TRUE(w.at("share").is_number());
    EXPECT_TRUE(w.at("direction").is_string());
  }
  ASSERT_TRUE(j.at("ranking").is_array());
  ASSERT_EQ(j.at("ranking").size(), 2u);  // wire_friction needs --model: not tested
  for (const auto& r : j.at("ranking")) {
    EXPECT_TRUE(r.at("effect").is_string());
    EXPECT_TRUE(r.at("params").is_object());
    EXPECT_TRUE(r.at("gap_after").is_number());
    EXPECT_TRUE(r.at("shrink").is_number());
    EXPECT_TRUE(r.at("score").is_number());
    // shrink is 1 - gap_after / gap_before (round-off tolerance).
    EXPECT_NEAR(r.at("shrink").get<double>(),
                1.0 - r.at("gap_after").get<double>() / j.at("gap_before").get<double>(), 1e-12);
  }
  EXPECT_EQ(j.at("cause"), "machine_compliance");
  EXPECT_EQ(j.at("not_tested"), nlohmann::json::array({"wire_friction"}));
  EXPECT_TRUE(j.at("predictive_check").at("done").get<bool>());
  // The compliance fitted on lab1 predicts lab2 (same specimen model, new noise).
  EXPECT_GT(j.at("predictive_check").at("shrink").get<double>(), 0.7);
}

TEST(GapJsonContract, NonFiniteNumbersAreRefused) {
  nlohmann::json j = {{"a", {1.0, std::nan("")}}};
  EXPECT_THROW(require_finite(j), std::exception);
}

}  // namespace
}  // namespace dtwire::gap
