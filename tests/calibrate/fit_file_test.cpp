// Fit definition files: a valid file reads back; bad files give InputError at file:line with
// the field named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dtwire/calibrate/experiment.hpp"
#include "dtwire/calibrate/fit_file.hpp"
#include "fit_folder_test_support.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

class FitFileTest : public FitFolderTest {
 protected:
  // The InputError of reading `text`; fails the test if there is none.
  InputError error_of(const std::string& text, const FitReadOptions& options = {}) {
    try {
      read_fit_file(write(text), options);
    } catch (const InputError& error) {
      return error;
    }
    ADD_FAILURE() << "no InputError for:\n" << text;
    return InputError("", "");
  }

};

// Line numbers below count from 1 in this text.
const std::string kValid =
    "title = \"voce\"\n"                          // 1
    "[simulator]\n"                               // 2
    "kind = \"voce_bar\"\n"                       // 3
    "[fit]\n"                                     // 4
    "loss = \"cauchy\"\n"                         // 5
    "starts = 2\n"                                // 6
    "[[parameter]]\n"                             // 7
    "name = \"E_Pa\"\n"                           // 8
    "unit = \"Pa\"\n"                             // 9
    "initial = 150e9\n"                           // 10
    "lower = 50e9\n"                              // 11
    "upper = 400e9\n"                             // 12
    "[[experiment]]\n"                            // 13
    "name = \"mono\"\n"                           // 14
    "target = \"target.csv\"\n"                   // 15
    "abscissa = \"strain\"\n"                     // 16
    "channels = [{quantity = \"stress\", weight = 2}]\n"  // 17
    "path_strain_1 = [0, 0.02]\n";                // 18

std::string replace_line(const std::string& text, int line, const std::string& replacement) {
  std::string out;
  int current = 1;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::string row = text.substr(start, end - start);
    out += (current == line ? replacement : row) + "\n";
    ++current;
    start = end + 1;
  }
  return out;
}

TEST_F(FitFileTest, ValidFileReads) {
  const FitDefinition def = read_fit_file(write(kValid));
  EXPECT_EQ(def.simulator, "voce_bar");
  EXPECT_EQ(def.fit.loss, LossKind::Cauchy);
  EXPECT_EQ(def.fit.starts, 2);
  ASSERT_EQ(def.parameters.size(), 1u);
  EXPECT_EQ(def.parameters[0].initial, 150e9);
  ASSERT_EQ(def.experiments.size(), 1u);
  EXPECT_EQ(def.experiments[0].channels[0].weight, 2.0);
  EXPECT_EQ(def.experiments[0].target.si("stress").back(), 350e6);
}

TEST_F(FitFileTest, SyntaxErrorNamesLine) {
  const InputError e = error_of(replace_line(kValid, 10, "initial = = 150e9"));
  EXPECT_EQ(e.line(), 10);
  EXPECT_NE(std::string(e.what()).find("fit.toml"), std::string::npos);
}

TEST_F(FitFileTest, UnknownFieldNamesLineAndField) {
  const InputError e = error_of(replace_line(kValid, 11, "lowr = 50e9"));
  EXPECT_EQ(e.line(), 11);
  EXPECT_NE(std::string(e.what()).find("parameter[1].lowr"), std::string::npos) << e.what();
}

TEST_F(FitFileTest, InitialOutsideBoundsNamesLine) {
  const InputError e = error_of(replace_line(kValid, 10, "initial = 500e9"));
  EXPECT_EQ(e.line(), 10);
  EXPECT_NE(std::string(e.what()).find("parameter[1].initial"), std::string::npos) << e.what();
}

TEST_F(FitFileTest, BadLossNamesLine) {
  const InputError e = error_of(replace_line(kValid, 5, "loss = \"l1\""));
  EXPECT_EQ(e.line(), 5);
  EXPECT_NE(std::string(e.what()).find("fit.loss"), std::string::npos) << e.what();
}

TEST_F(FitFileTest, WrongTypeNamesLine) {
  const InputError e = error_of(replace_line(kValid, 6, "starts = \"two\""));
  EXPECT_EQ(e.line(), 6);
  EXPECT_NE(std::string(e.what()).find("expected an integer"), std::string::npos) << e.what();
}

// Screening stages (issue 52): read in order; bad stages name their line and field.
TEST_F(FitFileTest, ScreeningStagesReadAndBadOnesNameTheirField) {
  const std::string stages = "starts = 2\nscreening_iterations = [10, 20]\nscreening_cost_ratio = [2.0, 1.5]";
  const FitDefinition def = read_fit_file(write(replace_line(kValid, 6, stages)));
  ASSERT_EQ(def.fit.screening.size(), 2u);
  EXPECT_EQ(def.fit.screening[1].iterations, 20);
  EXPECT_EQ(def.fit.screening[1].cost_ratio, 1.5);
  const struct {
    std::string lines, field, what;
  } bad[] = {
      {"screening_iterations = [20, 10]\nscreening_cost_ratio = [2.0, 1.5]", "fit.screening_iterations", "increasing"},
      {"screening_iterations = [10]\nscreening_cost_ratio = [1.0]", "fit.screening_cost_ratio", "ratios > 1"},
      {"screening_iterations = [10, 20]\nscreening_cost_ratio = [2.0]", "fit.screening_cost_ratio", "one ratio per entry"},
      {"screening_iterations = [10]", "fit.screening_iterations", "together"},
  };
  for (const auto& b : bad) {
    const InputError e = error_of(replace_line(kValid, 6, "starts = 2\n" + b.lines));
    EXPECT_NE(std::string(e.what()).find(b.field), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(b.what), std::string::npos) << e.what();
    EXPECT_GE(e.line(), 7) << e.what();
  }
}

// The bounded solve's line search (issue 52): "gradients" (default) or "values"; anything else
// names its line and field.
TEST_F(FitFileTest, LineSearchReadAndABadOneNamesItsField) {
  EXPECT_FALSE(read_fit_file(write(kValid)).fit.value_only_line_search);
  EXPECT_TRUE(read_fit_file(write(replace_line(kValid, 6, "starts = 2\nline_search = \"values\""))).fit.value_only_line_search);
  const InputError e = error_of(replace_line(kValid, 6, "starts = 2\nline_search = \"cubic\""));
  EXPECT_NE(std::string(e.what()).find("fit.line_search"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("gradients or values"), std::string::npos) << e.what();
  EXPECT_EQ(e.line(), 7) << e.what();
}

// The polish's step (FitOptions::polish_relative_step): none by default; one at or below the
// fit's own step, or 1 and more, names its line and field.
TEST_F(FitFileTest, PolishStepReadAndABadOneNamesItsField) {
  EXPECT_EQ(read_fit_file(write(kValid)).fit.polish_relative_step, 0.0);
  EXPECT_EQ(read_fit_file(write(replace_line(kValid, 6, "starts = 2\npolish_relative_step = 0.01"))).fit.polish_relative_step,
            0.01);
  for (const std::string lines : {"relative_step = 1e-3\npolish_relative_step = 1e-3", "polish_relative_step = 1.5",
                                  "polish_relative_step = -0.01"}) {
    const InputError e = error_of(replace_line(kValid, 6, "starts = 2\n" + lines));
    EXPECT_NE(std::string(e.what()).find("fit.polish_relative_step"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("above relative_step"), std::string::npos) << e.what();
    EXPECT_GE(e.line(), 7) << e.what();
  }
}

TEST_F(FitFileTest, MissingChannelInTargetNamesLine) {
  const InputError e = error_of(replace_line(kValid, 17, "channels = [\"force\"]"));
  EXPECT_EQ(e.line(), 17);
  EXPECT_NE(std::string(e.what()).find("no channel 'force'"), std::string::npos) << e.what();
}

// Peak rows (an [[experiment]]'s `peak`): read with their weights; bad entries name their line.
TEST_F(FitFileTest, PeakRowsReadAndBadOnesNameTheirLine) {
  const FitDefinition def = read_fit_file(write(kValid + "peak = [{quantity = \"stress\", weight = 0.5}]\n"));
  ASSERT_EQ(def.experiments[0].peaks.size(), 1u);
  EXPECT_EQ(def.experiments[0].peaks[0].quantity, "stress");
  EXPECT_EQ(def.experiments[0].peaks[0].weight, 0.5);
  EXPECT_EQ(residual_count(def.experiments[0]), def.experiments[0].target.size() + 1);
  for (const auto& [line, part] : std::vector<std::pair<std::string, std::string>>{
           {"peak = \"stress\"", "expected a non-empty array"},
           {"peak = [\"force\"]", "no channel 'force'"},
           {"peak = [{quantity = \"stress\", weight = 0}]", "expected a number > 0"},
           {"peak = [{quantity = \"stress\", wieght = 1}]", "wieght"},
           {"peak = [\"stress\", \"stress\"]", "'stress' given twice"}}) {
    const InputError e = error_of(kValid + line + "\n");
    EXPECT_EQ(e.line(), 19) << line;
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST_F(FitFileTest, MissingTargetFileIsAnInputError) {
  const InputError e = error_of(replace_line(kValid, 15, "target = \"absent.csv\""));
  EXPECT_NE(std::string(e.what()).find("absent.csv"), std::string::npos) << e.what();
}

// `fit --experiments`: a fit of part of a file reads only those experiments, so the others'
// target files need not exist (the default campaign fits the SW segment set without the study's
// pull-spin curves); a name the file lacks is an InputError listing the file's experiments.
TEST_F(FitFileTest, OnlyTheChosenExperimentsAreRead) {
  const std::string text = kValid +
                           "[[experiment]]\n"
                           "name = \"elsewhere\"\n"
                           "target = \"absent.csv\"\n"
                           "abscissa = \"strain\"\n"
                           "channels = [\"stress\"]\n"
                           "path_strain_1 = [0, 0.01]\n";
  FitReadOptions only_mono;
  only_mono.only_experiments = {"mono"};
  const FitDefinition def = read_fit_file(write(text), only_mono);
  ASSERT_EQ(def.experiments.size(), 1u);
  EXPECT_EQ(def.experiments[0].name, "mono");
  EXPECT_NE(std::string(error_of(text).what()).find("absent.csv"), std::string::npos);
  FitReadOptions unknown;
  unknown.only_experiments = {"mono", "monotonic"};
  const std::string message = error_of(text, unknown).what();
  EXPECT_NE(message.find("no experiment 'monotonic' in the file (it has: mono, elsewhere)"), std::string::npos) << message;
}

TEST_F(FitFileTest, BadTargetCsvNamesItsOwnLine) {
  std::ofstream(dir_ / "target.csv") << "strain_1,stress_MPa\n0,0\n0.001,abc\n0.01,320\n";
  const InputError e = error_of(kValid);
  EXPECT_EQ(e.line(), 3);
  EXPECT_NE(std::string(e.what()).find("target.csv"), std::string::npos) << e.what();
}

TEST_F(FitFileTest, BadPathUnitNamesLine) {
  std::string text = replace_line(kValid, 3, "kind = \"law_replay\"\nlaw = \"thesis\"");
  // After the insertion the path line is 19.
  text = replace_line(text, 19, "path_displacement_furlong = [0, 1]");
  const InputError e = error_of(text);
  EXPECT_EQ(e.line(), 19);
  EXPECT_NE(std::string(e.what()).find("path_displacement_furlong"), std::string::npos) << e.what();
}

// A law replay against an FE-like curve below a targets directory (a half model: its rotation
// is half the driver's, its generalised axial force is axial_force_N). Lines count from 1.
const std::string kReplay =
    "[simulator]\n"                                          // 1
    "kind = \"law_replay\"\n"                                // 2
    "law = \"thesis\"\n"                                     // 3
    "[[parameter]]\n"                                        // 4
    "name = \"N0_N\"\n"                                      // 5
    "initial = 2000\n"                                       // 6
    "lower = 500\n"                                          // 7
    "upper = 5000\n"                                         // 8
    "[[experiment]]\n"                                       // 9
    "name = \"bend\"\n"                                      // 10
    "target = \"{targets}/bend/curve.csv\"\n"                // 11
    "abscissa = \"rotation\"\n"                              // 12
    "channels = [\"force\", \"moment\"]\n"                   // 13
    "path_rotation_deg = [0, 20]\n"                          // 14
    "[experiment.target_columns]\n"                          // 15
    "force = \"axial_force\"\n"                              // 16
    "rotation = {column = \"rotation\", factor = 2}\n";      // 17

class TargetsTest : public FitFileTest {
 protected:
  void SetUp() override {
    FitFileTest::SetUp();
    std::filesystem::create_directories(dir_ / "fe/bend");
    std::ofstream(dir_ / "fe/bend/curve.csv") << "displacement_mm,force_N,axial_force_N,moment_Nm,rotation_rad\n"
                                                  "0,0,0,0,0\n-0.001,1,-2,0.1,0.05\n-0.003,3,-4,0.2,0.1\n";
    options_.targets_directory = dir_ / "fe";
  }
  FitReadOptions options_;
};

TEST_F(TargetsTest, PlaceholderAndColumnMappingRead) {
  const FitDefinition def = read_fit_file(write(kReplay), options_);
  ASSERT_EQ(def.experiments.size(), 1u);
  const Curve& target = def.experiments[0].target;
  EXPECT_EQ(target.si("force"), (std::vector<double>{0.0, -2.0, -4.0}));  // axial_force_N, not force_N
  EXPECT_EQ(target.si("rotation"), (std::vector<double>{0.0, 0.1, 0.2}));
  EXPECT_EQ(def.experiment_targets[0], dir_ / "fe/bend/curve.csv");
  EXPECT_EQ(def.experiment_target_names[0], std::filesystem::path("bend/curve.csv"));
  ASSERT_EQ(def.experiment_columns[0].size(), 2u);
  EXPECT_EQ(def.experiment_columns[0][1].factor, 2.0);
  EXPECT_EQ(def.inputs.back(), dir_ / "fe/bend/curve.csv");
}

TEST_F(TargetsTest, PlaceholderWithoutDirectoryNamesLine) {
  const InputError e = error_of(kReplay);
  EXPECT_EQ(e.line(), 11);
  EXPECT_NE(std::string(e.what()).find("--targets"), std::string::npos) << e.what();
  FitReadOptions synthesize;  // writing synthetic targets needs no directory
  synthesize.read_targets = false;
  EXPECT_EQ(read_fit_file(write(kReplay), synthesize).experiment_target_names[0], std::filesystem::path("bend/curve.csv"));
}

TEST_F(TargetsTest, PlaceholderInsideThePathNamesLine) {
  const InputError e = error_of(replace_line(kReplay, 11, "target = \"runs/{targets}/curve.csv\""), options_);
  EXPECT_EQ(e.line(), 11);
  EXPECT_NE(std::string(e.what()).find("must begin the path"), std::string::npos) << e.what();
}

TEST_F(TargetsTest, MissingMappedColumnNamesLineAndColumns) {
  const InputError e = error_of(replace_line(kReplay, 16, "force = \"axial_forse\""), options_);
  EXPECT_EQ(e.line(), 16);
  const std::string what = e.what();
  EXPECT_NE(what.find("target_columns.force"), std::string::npos) << what;
  EXPECT_NE(what.find("no column 'axial_forse_<unit>'"), std::string::npos) << what;
  EXPECT_NE(what.find("axial_force_N"), std::string::npos) << what;  // the columns present
}

TEST_F(TargetsTest, MappingOfTheWrongDimensionNamesLine) {
  const InputError e = error_of(replace_line(kReplay, 16, "force = \"moment\""), options_);
  EXPECT_EQ(e.line(), 13);  // where 'force' is compared
  const std::string what = e.what();
  EXPECT_NE(what.find("is a moment"), std::string::npos) << what;
  EXPECT_NE(what.find("target_columns"), std::string::npos) << what;
}

TEST_F(TargetsTest, BadMappingEntriesNameLine) {
  InputError e = error_of(replace_line(kReplay, 17, "rotation = {column = \"rotation\", factr = 2}"), options_);
  EXPECT_EQ(e.line(), 17);
  EXPECT_NE(std::string(e.what()).find("unknown field"), std::string::npos) << e.what();
  e = error_of(replace_line(kReplay, 17, "rotation = {column = \"rotation\", factor = 0}"), options_);
  EXPECT_EQ(e.line(), 17);
  EXPECT_NE(std::string(e.what()).find("other than 0"), std::string::npos) << e.what();
  e = error_of(replace_line(kReplay, 17, "rotation = 2"), options_);
  EXPECT_EQ(e.line(), 17);
  EXPECT_NE(std::string(e.what()).find("target_columns.rotation"), std::string::npos) << e.what();
}

TEST_F(TargetsTest, ChannelTheSimulatorLacksNamesLine) {
  const InputError e = error_of(replace_line(kReplay, 13, "channels = [\"displacement\", \"axial_force\"]"), options_);
  EXPECT_EQ(e.line(), 13);
  EXPECT_NE(std::string(e.what()).find("has no channel 'axial_force' (it gives time, displacement"), std::string::npos)
      << e.what();
}

// Issue 20: a fitted parameter no simulator reads used to be fitted (zero sensitivity) and
// written with a zero sigma.
TEST_F(TargetsTest, FittedParameterTheLawDoesNotReadNamesLineAndClosestName) {
  const InputError e = error_of(replace_line(kReplay, 5, "name = \"m_ff\""), options_);
  EXPECT_EQ(e.line(), 5);
  EXPECT_NE(std::string(e.what()).find("parameter[1].name"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("did you mean 'm_f'"), std::string::npos) << e.what();
}

TEST_F(TargetsTest, FixedValueTheLawDoesNotReadNamesLine) {
  const InputError e = error_of(replace_line(kReplay, 3, "law = \"thesis\"\n[simulator.fixed]\nslideb = 0"), options_);
  EXPECT_EQ(e.line(), 5);
  EXPECT_NE(std::string(e.what()).find("did you mean 'slide_b'"), std::string::npos) << e.what();
  const InputError law = error_of(replace_line(kReplay, 3, "law = \"thesys\""), options_);
  EXPECT_EQ(law.line(), 3);
}

TEST_F(FitFileTest, FittedParameterTheVoceBarDoesNotReadIsRefused) {
  const InputError e = error_of(replace_line(kValid, 8, "name = \"E_GPa\""));
  EXPECT_EQ(e.line(), 8);
  EXPECT_NE(std::string(e.what()).find("did you mean 'E_Pa'"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace dtwire::calibrate
