// Parameters fitted as offsets from others (parameter.hpp, `offset_from` in a fit file): the
// values the simulator reads, the resolved bounds and references, the covariance carried over
// (var(a + b) = var a + var b + 2 cov), a fit whose answer does not depend on the choice of
// coordinates, the outputs in the parameters' own names and values, the start from an earlier
// fit, and bad input named at its field.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "dtwire/calibrate/fit_file.hpp"
#include "fit_folder_test_support.hpp"
#include "dtwire/calibrate/fit_output.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/calibrate/initial_values.hpp"
#include "dtwire/calibrate/voce_bar.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

ParameterDefinition parameter(const std::string& name, double initial, double lower, double upper,
                              const std::string& offset_from = "", std::optional<double> reference = std::nullopt) {
  ParameterDefinition p;
  p.name = name;
  p.unit = "N";
  p.initial = initial, p.lower = lower, p.upper = upper;
  p.offset_from = offset_from;
  p.reference = reference;
  return p;
}

// N0, Nult as N0 + reserve, and a third one chained on Nult (c = Nult + d).
std::vector<ParameterDefinition> chain() {
  return {parameter("c_N", 10, 0, 100, "Nult_N", 20.0), parameter("N0_N", 2800, 500, 6000, "", 2750.0),
          parameter("Nult_N", 400, 0, 7000, "N0_N", 450.0), parameter("k_F", 150, 20, 2e4)};
}

TEST(ParameterOffsets, ValuesBoundsAndReferencesResolveAlongTheChain) {
  const auto p = chain();
  validate(p);
  const std::vector<double> fitted{10, 2800, 400, 150};
  const std::vector<double> resolved = resolve_offsets(p, fitted);
  EXPECT_EQ(resolved, (std::vector<double>{3210, 2800, 3200, 150}));
  EXPECT_EQ(offsets_from_resolved(p, resolved), fitted);
  const ParameterValues named = to_values(p, fitted);
  EXPECT_EQ(named.at("Nult_N"), 3200);
  EXPECT_EQ(named.at("c_N"), 3210);
  EXPECT_EQ(resolved_lower(p), (std::vector<double>{500, 500, 500, 20}));
  EXPECT_EQ(resolved_upper(p), (std::vector<double>{13100, 6000, 13000, 2e4}));
  const auto references = resolved_references(p);
  EXPECT_EQ(references[0], std::optional<double>(3220));
  EXPECT_EQ(references[1], std::optional<double>(2750));
  EXPECT_EQ(references[2], std::optional<double>(3200));
  EXPECT_FALSE(references[3]);
  EXPECT_EQ(reference_point(p), (std::vector<double>{20, 2750, 450, 150}));
  // A base without a reference leaves its offsets without one.
  auto q = p;
  q[1].reference.reset();
  EXPECT_FALSE(resolved_references(q)[2]);
  EXPECT_FALSE(resolved_references(q)[0]);
  EXPECT_EQ(coordinate_name(p[2]), "Nult_N - N0_N");
  EXPECT_EQ(coordinate_name(p[1]), "N0_N");
}

TEST(ParameterOffsets, CovarianceOfTheSumIsCarriedOver) {
  const auto p = chain();
  // A covariance of the fitted values (c, N0, reserve, k_F) with known entries.
  Eigen::MatrixXd c(4, 4);
  c << 4, 1, 2, 0,  //
      1, 9, -3, 1,  //
      2, -3, 16, 2,  //
      0, 1, 2, 25;
  const Eigen::MatrixXd r = resolve_covariance(p, c);
  // var(Nult) = var N0 + var reserve + 2 cov(N0, reserve) = 9 + 16 - 6.
  EXPECT_DOUBLE_EQ(r(2, 2), 19.0);
  // cov(Nult, N0) = var N0 + cov(reserve, N0) = 9 - 3.
  EXPECT_DOUBLE_EQ(r(2, 1), 6.0);
  EXPECT_DOUBLE_EQ(r(1, 2), 6.0);
  // var(c) with c = d + reserve + N0: the sum of the block c(0..2, 0..2).
  EXPECT_DOUBLE_EQ(r(0, 0), 4 + 9 + 16 + 2 * (1 + 2 - 3));
  // cov(Nult, k_F) = cov(N0, k) + cov(reserve, k) = 1 + 2; k_F itself unchanged.
  EXPECT_DOUBLE_EQ(r(2, 3), 3.0);
  EXPECT_DOUBLE_EQ(r(3, 3), 25.0);
  EXPECT_DOUBLE_EQ(r(1, 1), 9.0);
  // The map itself: row i has a 1 at i and at every base along i's chain.
  const Eigen::MatrixXd a = offset_map(p);
  EXPECT_EQ(a, (Eigen::MatrixXd(4, 4) << 1, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1).finished());
  EXPECT_THROW(resolve_covariance(p, Eigen::MatrixXd::Identity(3, 3)), std::invalid_argument);
}

TEST(ParameterOffsets, UnknownBaseSelfAndCycleAreRefused) {
  auto p = chain();
  p[2].offset_from = "N0";
  EXPECT_THROW(validate(p), std::invalid_argument);
  p[2].offset_from = "Nult_N";
  EXPECT_THROW(validate(p), std::invalid_argument);
  p = chain();
  p[1].offset_from = "c_N";  // N0 -> c -> Nult -> N0
  try {
    validate(p);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cycle"), std::string::npos) << e.what();
  }
}

// The Voce bar fitted twice to one target: with Q itself, and with Q as an offset from sigma_y0
// (a reparametrisation chosen only because it is linear: the simulator reads Q = d + sigma_y0).
// The minimum is the same point, so the resolved values agree, and the covariance carried over
// equals the one of the direct fit (both are (J^T J)^-1 s^2 of one model in two linear
// coordinates); to the finite differences' precision.
TEST(ParameterOffsets, AFitInOffsetsEndsWhereTheDirectFitEnds) {
  auto simulator = std::make_shared<VoceBarSimulator>(std::vector<double>{0.0, 0.02, 0.005, 0.04}, 40);
  Experiment e;
  e.name = "cyclic";
  e.simulator = simulator;
  const Curve clean = simulator->simulate({{"E_Pa", 200e9}, {"sigma_y0_Pa", 300e6}, {"Q_Pa", 150e6}, {"b_1", 20.0}});
  std::vector<double> stress = clean.channel("stress").values;
  for (std::size_t i = 0; i < stress.size(); ++i) stress[i] += 3e6 * std::sin(1.7 * static_cast<double>(i));
  e.target.add_channel("strain", *find_unit("1"), clean.channel("strain").values);
  e.target.add_channel("stress", *find_unit("Pa"), stress);
  e.abscissa = "strain";
  e.channels = {{"stress", 1.0, 0.0}};

  const auto voce = [](const std::string& q_offset_from) {
    std::vector<ParameterDefinition> p = {
        {"E_Pa", "Pa", 150e9, 50e9, 400e9, 0.0, 200e9},
        {"sigma_y0_Pa", "Pa", 250e6, 50e6, 800e6, 0.0, 300e6},
        {"Q_Pa", "Pa", 100e6, 0.0, 500e6, 0.0, 150e6},
        {"b_1", "1", 10.0, 0.5, 200.0, 0.0, std::nullopt}};
    if (!q_offset_from.empty()) {
      p[2].offset_from = q_offset_from;
      p[2].initial = 100e6 - 250e6, p[2].lower = -800e6, p[2].upper = 500e6;  // the same start
      p[2].reference = 150e6 - 300e6;
    }
    return p;
  };
  FitOptions options;
  options.function_tolerance = options.parameter_tolerance = 1e-14;
  ProblemEvaluator direct_evaluator({e}, voce(""), EvaluationOptions{});
  const FitResult direct = run_fit(direct_evaluator, options);
  ProblemEvaluator offset_evaluator({e}, voce("sigma_y0_Pa"), EvaluationOptions{});
  const FitResult offset = run_fit(offset_evaluator, options);
  ASSERT_TRUE(direct.covariance && offset.covariance);
  EXPECT_NEAR(offset.cost / direct.cost, 1.0, 1e-9);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(offset.values[i] / direct.values[i], 1.0, 1e-6) << i;
    EXPECT_NEAR(offset.sigma[i] / direct.sigma[i], 1.0, 1e-3) << i;
    for (std::size_t j = 0; j < 4; ++j)
      EXPECT_NEAR((*offset.correlation)(i, j), (*direct.correlation)(i, j), 1e-3) << i << ", " << j;
  }
  // The fitted coordinate is the offset, its sigma that of Q - sigma_y0.
  EXPECT_NEAR(offset.fitted_values[2], offset.values[2] - offset.values[1], 1e-6 * offset.values[2]);
  const Eigen::MatrixXd& c = *direct.covariance;
  EXPECT_NEAR(offset.fitted_sigma[2], std::sqrt(c(2, 2) + c(1, 1) - 2 * c(1, 2)), 1e-3 * offset.fitted_sigma[2]);
  EXPECT_EQ(direct.fitted_values, direct.values);
  // Identification judges the resolved values (relative sigma of Q itself, the wider of the
  // tangent's and the secant's); on this smooth curve the two differ by the curvature over
  // +-2.5 % only (up to 1.7 % here).
  ASSERT_EQ(offset.secant_sigma.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(offset.secant_sigma[i] / offset.sigma[i], 1.0, 0.05) << i;
  EXPECT_NEAR(offset.identification[2].relative_sigma,
              std::max(offset.sigma[2], offset.secant_sigma[2]) / offset.values[2], 1e-12);

  // The outputs give the law's names and values; the offset under "offset".
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_parameter_offset_test";
  std::filesystem::remove_all(dir);
  FitDefinition def;
  def.file = dir / "fit.toml";
  def.law = "voce_bar";
  def.parameters = voce("sigma_y0_Pa");
  def.experiments = {e};
  write_fit_outputs(def, offset, make_provenance("test"), dir);
  std::ifstream in(dir / "parameters.json");
  const auto json = nlohmann::json::parse(in);
  const auto& q = json["parameters"][2];
  EXPECT_EQ(q["name"], "Q_Pa");
  EXPECT_EQ(q["value"].get<double>(), offset.values[2]);
  EXPECT_EQ(q["sigma"].get<double>(), offset.sigma[2]);
  EXPECT_EQ(q["reference"].get<double>(), 150e6);  // -150e6 + 300e6
  EXPECT_EQ(q["initial"].get<double>(), 100e6);
  EXPECT_EQ(q["lower"].get<double>(), -800e6 + 50e6);
  EXPECT_EQ(q["upper"].get<double>(), 500e6 + 800e6);
  EXPECT_EQ(q["offset_from"], "sigma_y0_Pa");
  EXPECT_EQ(q["offset"]["value"].get<double>(), offset.fitted_values[2]);
  EXPECT_EQ(q["offset"]["sigma"].get<double>(), offset.fitted_sigma[2]);
  EXPECT_EQ(q["offset"]["lower"].get<double>(), -800e6);
  EXPECT_EQ(q["offset"]["reference"].get<double>(), -150e6);
  EXPECT_EQ(json["covariance"][2][2].get<double>(), (*offset.covariance)(2, 2));
  EXPECT_NEAR(json["starts"][0]["end"][2].get<double>(), offset.values[2], 1e-9 * offset.values[2]);
  std::ifstream report(dir / "fit_report.md");
  const std::string text((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Q_Pa was fitted as its offset from sigma_y0_Pa: Q_Pa - sigma_y0_Pa = "), std::string::npos) << text;
  std::filesystem::remove_all(dir);
}

TEST(ParameterOffsets, AnEarlierFitsValuesStartTheOffset) {
  const auto file = std::filesystem::temp_directory_path() / "dtwire_offset_initial.json";
  std::vector<ParameterDefinition> p = {parameter("N0_N", 2800, 500, 6000), parameter("Nult_N", 400, 0, 7000, "N0_N")};
  std::ofstream(file) << R"({"parameters": [{"name": "N0_N", "value": 2000}, {"name": "Nult_N", "value": 5000}]})";
  EXPECT_EQ(apply_initial_values(p, file), 2u);
  EXPECT_EQ(p[0].initial, 2000);
  EXPECT_EQ(p[1].initial, 3000);  // 5000 - 2000
  // Only Nult named: its offset from the base's initial value.
  p = {parameter("N0_N", 2800, 500, 6000), parameter("Nult_N", 400, 0, 7000, "N0_N")};
  std::ofstream(file) << R"({"parameters": [{"name": "Nult_N", "value": 5000}]})";
  EXPECT_EQ(apply_initial_values(p, file), 1u);
  EXPECT_EQ(p[1].initial, 2200);
  // An earlier answer below the base gives a negative reserve: outside the bounds, named.
  std::ofstream(file) << R"({"parameters": [{"name": "Nult_N", "value": 2000}]})";
  try {
    apply_initial_values(p, file);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Nult_N - N0_N = -800"), std::string::npos) << e.what();
  }
  std::filesystem::remove(file);
}

class OffsetFitFileTest : public FitFolderTest {
 protected:
  // The text of the InputError of reading a file whose Q parameter has these lines (line 14 on).
  std::string error_of(const std::string& q_lines) {
    try {
      read_fit_file(write(file(q_lines)));
    } catch (const InputError& error) {
      line_ = error.line();
      return error.what();
    }
    ADD_FAILURE() << "no InputError for:\n" << q_lines;
    return "";
  }
  static std::string file(const std::string& q_lines) {
    return "[simulator]\n"                      // 1
           "kind = \"voce_bar\"\n"              // 2
           "[[parameter]]\n"                    // 3
           "name = \"sigma_y0_Pa\"\n"           // 4
           "initial = 250e6\n"                  // 5
           "lower = 50e6\n"                     // 6
           "upper = 800e6\n"                    // 7
           "reference = 300e6\n"                // 8
           "[[parameter]]\n"                    // 9
           "name = \"Q_Pa\"\n"                  // 10
           "initial = 100e6\n"                  // 11
           "lower = 0\n"                        // 12
           "upper = 500e6\n" +                  // 13
           q_lines +                            // 14...
           "\n[[experiment]]\n"
           "name = \"mono\"\n"
           "target = \"target.csv\"\n"
           "abscissa = \"strain\"\n"
           "channels = [\"stress\"]\n"
           "path_strain_1 = [0, 0.02]\n";
  }
  int line_ = 0;
};

TEST_F(OffsetFitFileTest, AnOffsetReadsAndResolves) {
  const FitDefinition def = read_fit_file(write(file("offset_from = \"sigma_y0_Pa\"\nreference = 150e6")));
  ASSERT_EQ(def.parameters.size(), 2u);
  EXPECT_EQ(def.parameters[1].offset_from, "sigma_y0_Pa");
  EXPECT_EQ(resolved_references(def.parameters)[1], std::optional<double>(450e6));
  EXPECT_EQ(to_values(def.parameters, {250e6, 100e6}).at("Q_Pa"), 350e6);
}

TEST_F(OffsetFitFileTest, UnknownBaseIsNamedWithTheClosestName) {
  const std::string e = error_of("offset_from = \"sigma_y_Pa\"");
  EXPECT_EQ(line_, 14);
  EXPECT_NE(e.find("fit.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("parameter[2].offset_from': 'sigma_y_Pa' names no other [[parameter]] of this file"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'sigma_y0_Pa'"), std::string::npos) << e;
}

TEST_F(OffsetFitFileTest, SelfEmptyAndCycleAreNamed) {
  EXPECT_NE(error_of("offset_from = \"Q_Pa\"").find("parameter[2].offset_from': names the parameter itself"),
            std::string::npos);
  EXPECT_EQ(line_, 14);
  EXPECT_NE(error_of("offset_from = \"\"").find("parameter[2].offset_from'"), std::string::npos);
  // sigma_y0 from Q and Q from sigma_y0.
  std::string text = file("offset_from = \"sigma_y0_Pa\"");
  text.replace(text.find("reference = 300e6"), 17, "offset_from = \"Q_Pa\"");
  try {
    read_fit_file(write(text));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("offset_from closes a cycle (sigma_y0_Pa -> Q_Pa -> sigma_y0_Pa)"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("parameter[1].offset_from"), std::string::npos) << e.what();
  }
}

TEST_F(OffsetFitFileTest, ReferenceAndInitialOutsideTheOffsetsBoundsAreNamed) {
  // The parameter's own reference (450e6) written where the offset's belongs, outside [0, 300e6].
  std::string text = file("offset_from = \"sigma_y0_Pa\"\nreference = 450e6");
  text.replace(text.find("upper = 500e6"), 13, "upper = 300e6");
  try {
    read_fit_file(write(text));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 15);
    EXPECT_NE(std::string(e.what()).find("parameter[2].reference': expected the reference of the offset Q_Pa - "
                                         "sigma_y0_Pa, within [lower, upper]"),
              std::string::npos)
        << e.what();
  }
  // A negative order (Q below sigma_y0) is outside a lower bound of 0.
  EXPECT_NE(error_of("offset_from = \"sigma_y0_Pa\"\nreference = -1e6").find("parameter[2].reference'"),
            std::string::npos);
  // An offset with a reference, its base without one: the parameter's own reference is unknown.
  text = file("offset_from = \"sigma_y0_Pa\"\nreference = 150e6");
  text.erase(text.find("reference = 300e6\n"), 18);
  try {
    read_fit_file(write(text));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs one of 'sigma_y0_Pa' too"), std::string::npos) << e.what();
  }
  text = file("offset_from = \"sigma_y0_Pa\"");
  text.replace(text.find("initial = 100e6"), 15, "initial = -1e6");
  try {
    read_fit_file(write(text));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 11);
    EXPECT_NE(std::string(e.what()).find("parameter[2].initial': expected a value within [lower, upper] (of the "
                                         "offset Q_Pa - sigma_y0_Pa)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace dtwire::calibrate
