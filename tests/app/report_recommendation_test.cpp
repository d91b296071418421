// Issue 52: the campaign report opens with the recommended parameter set, chosen by the stated
// rules of app/campaign/report_recommendation.hpp; a punch that does not apply to its set-up is
// shown as such, never as a result.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "campaign/campaign_file.hpp"
#include "campaign/campaign_runner.hpp"
#include "campaign/report_recommendation.hpp"
#include "campaign/report_summary.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

TEST(PunchApplicability, ARunWithoutAPeakWithinItsTravelDoesNotApply) {
  // Rises to its last point (the WirePM sets in the slack state: 1.8 kN at the end of 0.75 m).
  const auto rising = punch_not_applicable({0.0, 0.25, 0.5, 0.75}, {0.0, 100.0, 250.0, 1770.0});
  ASSERT_TRUE(rising.has_value());
  EXPECT_NE(rising->find("no peak within the travel"), std::string::npos) << *rising;
  EXPECT_NE(rising->find("1.8 kN at 0.75 m"), std::string::npos) << *rising;
  // Never carries the onset force of 1 kN, wherever its maximum is.
  const auto weak = punch_not_applicable({0.0, 0.25, 0.5, 0.75}, {0.0, 900.0, 300.0, 200.0});
  ASSERT_TRUE(weak.has_value());
  EXPECT_NE(weak->find("onset force"), std::string::npos) << *weak;
  // A net that fails within the travel (the thesis sets: 45 kN at 0.55 m, then links break).
  EXPECT_FALSE(punch_not_applicable({0.0, 0.2, 0.548, 0.6, 0.75}, {0.0, 1000.0, 45000.0, 20000.0, 5000.0}).has_value());
}

TEST(PunchApplicability, ARunWhoseNetWasNotAtRestDoesNotApply) {
  const auto moving = punch_not_at_rest({{"settled_at_rest", false}, {"settle_s", 120.0}, {"settle_unbalanced_force_ratio", 0.0031}});
  ASSERT_TRUE(moving.has_value());
  EXPECT_NE(moving->find("not at rest"), std::string::npos) << *moving;
  EXPECT_NE(moving->find("120.0 s"), std::string::npos) << *moving;
  EXPECT_NE(moving->find("0.003100"), std::string::npos) << *moving;
  EXPECT_FALSE(punch_not_at_rest({{"settled_at_rest", true}}).has_value());
  EXPECT_FALSE(punch_not_at_rest({{"settled_at_rest", nullptr}}).has_value());  // a fixed settle
  EXPECT_FALSE(punch_not_at_rest(json::object()).has_value());
}

// A fit's parameters.json with `beyond` of its three curves past NRMSE 0.10 and `identified` of
// its four parameters identified.
json fit_result(int beyond, int identified) {
  json quality = json::array();
  for (int i = 0; i < 3; ++i)
    quality.push_back({{"experiment", "e" + std::to_string(i)}, {"quantity", "force"}, {"nrmse", i < beyond ? 0.2 + 0.01 * i : 0.02}});
  json parameters = json::array();
  for (int i = 0; i < 4; ++i) parameters.push_back({{"name", "p" + std::to_string(i)}, {"fitted", true}, {"identified", i < identified}});
  return {{"fit_quality", quality}, {"parameters", parameters}};
}

SetEvidence set(const std::string& label, std::vector<FitEvidence> fits, double strength, double stiffness,
                double peak_kN, double position_mm) {
  SetEvidence e;
  e.label = label;
  e.fits = std::move(fits);
  e.punch = {{"tool", "platter"}, {"peak_force_N", 1000.0 * peak_kN}, {"displacement_at_peak_mm", position_mm}, {"status", "ok"}};
  e.strip = {{"tool", "strip_tension"}, {"strength_per_width_kN_per_m", strength}, {"secant_EA_10_50_kN_per_m", stiffness}, {"status", "ok"}};
  e.punch_step = "punch_" + label;
  e.strip_step = "strip_" + label;
  e.punch_status = e.strip_status = "done";
  return e;
}

TEST(RecommendSet, TheCalibratedSetNearestTheReferencesWinsAndPublishedSetsAreReferences) {
  std::vector<SetEvidence> sets = {
      set("thesis published", {}, 58.8, 1165.0, 45.0, 548.0),  // the punch reference, no candidate
      set("stiff", {{"fit_a", fit_result(0, 4)}}, 71.0, 1500.0, 68.0, 632.0),  // x 1.65 on geometric mean
      set("near", {{"fit_b", fit_result(2, 2)}}, 55.0, 600.0, 50.0, 560.0),    // x 1.11
      set("broken", {{"fit_c", fit_result(0, 4)}}, 50.0, 500.0, 45.0, 548.0),   // its strip failed a check
  };
  sets[3].strip["status"] = "failed";
  const Recommendation r = recommend_set(sets);
  ASSERT_EQ(r.chosen, 2);
  EXPECT_FALSE(r.sets[0].candidate);
  // Rule 3: the geometric mean of the four factors, each against its reference.
  const auto mean = [](double a, double b, double c, double d) { return std::exp((std::log(a) + std::log(b) + std::log(c) + std::log(d)) / 4); };
  EXPECT_NEAR(r.sets[1].distance, mean(71.0 / 50, 1500.0 / 500, 68.0 / 45, 632.0 / 548), 1e-12);
  EXPECT_NEAR(r.sets[2].distance, mean(55.0 / 50, 600.0 / 500, 50.0 / 45, 560.0 / 548), 1e-12);
  // A figure below its reference counts by the same factor as one above it.
  EXPECT_NEAR(recommend_set({set("low", {{"f", fit_result(0, 4)}}, 40.0, 500.0, 25.0, 530.0)}).sets[0].distance,
              mean(50.0 / 40, 1, 1, 1), 1e-12);
  EXPECT_NE(r.sets[2].farthest.find("strip stiffness 600 kN/m against 500"), std::string::npos) << r.sets[2].farthest;
  EXPECT_NE(r.sets[3].not_judged.find("strip_broken"), std::string::npos) << r.sets[3].not_judged;
  EXPECT_NE(r.punch_reference.find("45.0 kN at 548 mm"), std::string::npos) << r.punch_reference;
  // The punch figures are judged against the thesis sets' run: 50 / 45 kN, not 50 / 25 kN.
  EXPECT_NE(r.sets[2].figures[2].find("x 1.11"), std::string::npos) << r.sets[2].figures[2];
  EXPECT_TRUE(r.tie_note.empty());
}

TEST(RecommendSet, ATieAtMeshScaleGoesToTheBetterWireScaleFit) {
  const std::vector<SetEvidence> sets = {
      set("poor fit", {{"fit_a", fit_result(2, 4)}}, 55.0, 600.0, 25.0, 530.0),  // x 1.072, 2 curves beyond
      set("good fit", {{"fit_b", fit_result(0, 1)}}, 55.0, 620.0, 25.0, 530.0),  // x 1.081 (within 5 %), none beyond
      set("far", {{"fit_c", fit_result(0, 4)}}, 55.0, 900.0, 25.0, 530.0),       // x 1.186: out of the tie
  };
  const Recommendation r = recommend_set(sets);
  EXPECT_EQ(r.chosen, 1);
  EXPECT_NE(r.tie_note.find("poor fit, good fit"), std::string::npos) << r.tie_note;
  EXPECT_EQ(r.tie_note.find("far"), std::string::npos) << r.tie_note;
  EXPECT_NE(r.punch_reference.find("thesis DEM punch"), std::string::npos) << "no thesis-set run: the thesis's figures";
}

// Rule 3's punch reference follows the model variant the label names after its first ", ": a set
// with the beam's shear spring against the published sets with the same spring, the plain set
// against the plain published sets; a variant with no published run falls back to the thesis DEM.
TEST(RecommendSet, APunchIsJudgedAgainstThePublishedSetsOfTheSameModelVariant) {
  const std::vector<SetEvidence> sets = {
      set("thesis published", {}, 58.8, 1165.0, 45.0, 530.0),
      set("thesis published, beam shear spring", {}, 40.6, 280.0, 67.5, 760.0),
      set("fit", {{"fit_a", fit_result(0, 4)}}, 61.0, 3879.0, 46.9, 547.5),
      set("fit, beam shear spring", {{"fit_a", fit_result(0, 4)}}, 43.6, 272.0, 91.0, 977.5),
      set("fit, other variant", {{"fit_a", fit_result(0, 4)}}, 50.0, 500.0, 25.0, 530.0),
  };
  const Recommendation r = recommend_set(sets);
  const auto mean = [](double a, double b, double c, double d) { return std::exp((std::log(a) + std::log(b) + std::log(c) + std::log(d)) / 4); };
  EXPECT_NEAR(r.sets[2].distance, mean(61.0 / 50, 3879.0 / 500, 46.9 / 45.0, 547.5 / 530), 1e-12);
  EXPECT_NEAR(r.sets[3].distance, mean(50 / 43.6, 500 / 272.0, 91.0 / 67.5, 977.5 / 760), 1e-12);
  EXPECT_NE(r.sets[3].punch_reference.find("with the same beam shear spring (`punch_thesis published, beam shear spring`"),
            std::string::npos)
      << r.sets[3].punch_reference;
  EXPECT_NE(r.sets[4].punch_reference.find("thesis DEM punch"), std::string::npos) << r.sets[4].punch_reference;
  EXPECT_NE(r.sets[4].punch_reference.find("other variant"), std::string::npos) << r.sets[4].punch_reference;
  ASSERT_EQ(r.chosen, 4);  // 50 kN/m, 500 kN/m, and the thesis DEM's own figures: distance 1
  EXPECT_EQ(r.punch_reference, r.sets[4].punch_reference);
  const std::vector<SetEvidence> springs = {sets[0], sets[1], sets[2], sets[3]};
  const Recommendation beam = recommend_set(springs);
  ASSERT_EQ(beam.chosen, 3);  // x 1.38 against x 1.78
  const std::string md = recommendation_markdown(beam, springs);
  EXPECT_NE(md.find("in PFC7 take the same fits with the plugin's spring, the set `fit`"), std::string::npos) << md;
}

TEST(RecommendSet, NoCandidateNoRecommendation) {
  const Recommendation r = recommend_set({set("thesis published", {}, 58.8, 1165.0, 45.0, 548.0)});
  EXPECT_EQ(r.chosen, -1);
  EXPECT_NE(recommendation_markdown(r, {set("thesis published", {}, 58.8, 1165.0, 45.0, 548.0)}).find("None: this campaign calibrates no set"),
            std::string::npos);
}

void write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

// The report's first section from a small campaign's outputs (no run needed): the recommended
// set with its fits and files and why, before the summary's other sections; the WirePM punch,
// which rises to the end of its travel, is shown as not applicable, not as a result.
TEST(CampaignReport, OpensWithTheRecommendedSetAndShowsARunThatDoesNotApply) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_recommendation_report";
  std::filesystem::remove_all(out);
  const auto run = [](const std::string& name, const std::string& label, const std::string& file, const std::string& params) {
    return "[[step]]\nname = \"" + name + "\"\ncommand = [\"dem\", \"run\", \"" + file + "\"" +
           (params.empty() ? "" : ", \"--set-params\", \"sw=" + params + "\"") + ", \"--label\", \"" + label +
           "\", \"-o\", \"{out}/" + name + "\"]\ninputs = [" + (params.empty() ? "" : "\"" + params + "\"") +
           "]\noutputs = [\"{out}/" + name + "/summary.json\", \"{out}/" + name + "/curve.csv\"]\n";
  };
  const auto campaign_file = std::filesystem::temp_directory_path() / "dtwire_recommendation.toml";
  write(campaign_file,
        "name = \"r\"\n[[step]]\nname = \"sw_fit\"\ncommand = [\"fit\", \"x.toml\", \"--out\", \"{out}/fit\"]\n"
        "outputs = [\"{out}/fit/parameters.json\"]\n" +
            run("punch_thesis", "thesis published", "punch.toml", "") + run("strip_thesis", "thesis published", "strip.toml", "") +
            run("punch_wirepm", "WirePM published", "punch_wirepm.toml", "") +
            run("punch_fit", "straight-wire fit", "punch.toml", "{out}/fit/parameters.json") +
            run("strip_fit", "straight-wire fit", "strip.toml", "{out}/fit/parameters.json"));
  const Campaign campaign = read_campaign(campaign_file);
  write(out / "fit/parameters.json", fit_result(1, 3).dump());
  const std::string peaked = "tool_displacement_mm,tool_force_N\n0,0\n200,1000\n548,45000\n600,20000\n750,5000\n";
  write(out / "punch_thesis/summary.json", R"({"tool": "platter", "peak_force_N": 45000, "displacement_at_peak_mm": 548, "status": "ok"})");
  write(out / "punch_thesis/curve.csv", peaked);
  write(out / "strip_thesis/summary.json", R"({"tool": "strip_tension", "strength_per_width_kN_per_m": 58.8, "secant_EA_10_50_kN_per_m": 1165, "status": "ok"})");
  write(out / "punch_wirepm/summary.json", R"({"tool": "platter", "peak_force_N": 1770, "displacement_at_peak_mm": 750, "status": "ok"})");
  write(out / "punch_wirepm/curve.csv", "tool_displacement_mm,tool_force_N\n0,0\n250,100\n510,250\n750,1770\n");
  write(out / "punch_fit/summary.json", R"({"tool": "platter", "peak_force_N": 68000, "displacement_at_peak_mm": 632, "status": "ok"})");
  write(out / "punch_fit/curve.csv", peaked);
  write(out / "strip_fit/summary.json", R"({"tool": "strip_tension", "strength_per_width_kN_per_m": 71.4, "secant_EA_10_50_kN_per_m": 700, "status": "ok"})");
  std::vector<StepOutcome> outcomes;
  for (const auto& step : campaign.steps) outcomes.push_back({step.name, StepStatus::Done, 1.0, 0, ""});
  const std::string md = summary_markdown(campaign, outcomes, out);
  // The summary opens with the recommendation; the other sections follow.
  EXPECT_EQ(md.rfind("## Summary\n\n### Recommended parameter set\n\n**straight-wire fit**: fits [sw_fit](#sw_fit); files `fit/parameters.json`.", 0), 0u) << md;
  EXPECT_LT(md.find("### Recommended parameter set"), md.find("### Calibrated parameter sets"));
  // Why: x 1.37 on geometric mean (71.4 / 50, 700 / 500, 68 / 45, 632 / 548), farthest the punch peak.
  EXPECT_NE(md.find("x 1.37 from them on geometric mean (farthest: punch peak 68.0 kN against 45.0 (x 1.51)"), std::string::npos) << md;
  EXPECT_NE(md.find("1 of 3 fitted curves beyond NRMSE 0.10"), std::string::npos) << md;
  EXPECT_NE(md.find("| thesis published | published (no fit) | n/a | published | reference (published set) |"), std::string::npos) << md;
  // The WirePM punch is not applicable, in the recommendation's table, the run table and the mesh-scale table.
  EXPECT_NE(md.find("| [punch_wirepm](#punch_wirepm) | not applicable: no peak within the travel"), std::string::npos) << md;
  EXPECT_NE(md.find("| WirePM published | not applicable: no peak within the travel"), std::string::npos) << md;
  EXPECT_EQ(md.find("1.8 kN at 750"), std::string::npos) << "drawn as a result";
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace dtwire::app
