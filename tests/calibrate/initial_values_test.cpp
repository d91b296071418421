// `dtwire fit --initial FILE`: initial values from an earlier fit's parameters.json.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "dtwire/calibrate/initial_values.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

std::vector<ParameterDefinition> two_parameters() {
  ParameterDefinition a;
  a.name = "dt.N0_N";
  a.initial = 3000;
  a.lower = 500;
  a.upper = 6000;
  ParameterDefinition b = a;
  b.name = "dt.k_F";
  b.initial = 150;
  b.lower = 20;
  b.upper = 2e4;
  return {a, b};
}

TEST(InitialValues, TakesTheNamedValuesAndKeepsTheOthers) {
  auto parameters = two_parameters();
  const auto file = write("dtwire_initial_ok.json",
                          R"({"cost": 0.01, "parameters": [{"name": "dt.N0_N", "value": 2172.6, "sigma": 140},
                              {"name": "sw.EA_N", "value": 1.2e6}]})");
  EXPECT_EQ(apply_initial_values(parameters, file), 1u);
  EXPECT_DOUBLE_EQ(parameters[0].initial, 2172.6);
  EXPECT_DOUBLE_EQ(parameters[1].initial, 150);
}

TEST(InitialValues, RefusesValuesOutsideTheBoundsAndBadFilesNamingThem) {
  auto parameters = two_parameters();
  const auto outside = write("dtwire_initial_outside.json", R"({"parameters": [{"name": "dt.k_F", "value": 5}]})");
  try {
    apply_initial_values(parameters, outside);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("dtwire_initial_outside.json"), std::string::npos) << message;
    EXPECT_NE(message.find("dt.k_F"), std::string::npos) << message;
  }
  EXPECT_DOUBLE_EQ(parameters[1].initial, 150);
  EXPECT_THROW(apply_initial_values(parameters, write("dtwire_initial_nolist.json", R"({"law": "thesis"})")), InputError);
  EXPECT_THROW(apply_initial_values(parameters, write("dtwire_initial_bad.json", "{not json")), InputError);
  EXPECT_THROW(apply_initial_values(parameters, write("dtwire_initial_noval.json", R"({"parameters": [{"name": "x"}]})")),
               InputError);
  EXPECT_THROW(apply_initial_values(parameters, "/nonexistent/parameters.json"), InputError);
  EXPECT_THROW(apply_initial_values(parameters, write("dtwire_initial_other.json",
                                                      R"({"parameters": [{"name": "N0_N", "value": 2000}]})")),
               InputError);  // unprefixed: names none of them
}

}  // namespace
}  // namespace dtwire::calibrate
