// The command simulator (external program per evaluation, e.g. `dtwire run`), exercised with
// /bin/sh so the unit test needs no FE build.
#include <gtest/gtest.h>

#include <filesystem>

#include "dtwire/calibrate/command_simulator.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

CommandSpecification shell(const std::string& script) {
  CommandSpecification spec;
  spec.program = "/bin/sh";
  spec.arguments = {"-c", script};
  spec.input_template = "displacement_m,force_N\n0,0\n1,{a_N}\n2,{b_N}\n";
  spec.input_name = "input.csv";
  // One fresh folder per test: failed runs keep their directory for diagnosis.
  spec.work_directory = std::filesystem::temp_directory_path() / "dtwire_command_simulator_test" /
                        ::testing::UnitTest::GetInstance()->current_test_info()->name();
  std::filesystem::remove_all(spec.work_directory);
  spec.fixed = {{"b_N", 7.0}};
  return spec;
}

// The template is filled in (parameters and fixed values, exact round-trip text), the program
// runs in its own directory, the result is read back, the run directory is removed.
TEST(CommandSimulator, FillsTemplateRunsProgramReadsResult) {
  const CommandSimulator simulator(shell("cp {input} {output}/curve.csv"));
  const Curve curve = simulator.simulate({{"a_N", 0.1}});
  EXPECT_EQ(curve.channel("force").values, (std::vector<double>{0.0, 0.1, 7.0}));
  EXPECT_TRUE(std::filesystem::is_empty(std::filesystem::temp_directory_path() / "dtwire_command_simulator_test" /
                                        "FillsTemplateRunsProgramReadsResult"));
}

TEST(CommandSimulator, NonZeroExitIsAComputationError) {
  const CommandSimulator simulator(shell("exit 3"));
  try {
    simulator.simulate({{"a_N", 1.0}});
    FAIL() << "no error";
  } catch (const ComputationError& error) {
    EXPECT_NE(std::string(error.what()).find("exit 3"), std::string::npos) << error.what();
  }
}

TEST(CommandSimulator, MissingResultIsAComputationError) {
  const CommandSimulator simulator(shell("true"));
  EXPECT_THROW(simulator.simulate({{"a_N", 1.0}}), ComputationError);
}

TEST(CommandSimulator, PlaceholderWithoutValueIsAComputationError) {
  const CommandSimulator simulator(shell("true"));
  EXPECT_THROW(simulator.instantiate({}), ComputationError);  // {a_N} has no value
}

}  // namespace
}  // namespace dtwire::calibrate
