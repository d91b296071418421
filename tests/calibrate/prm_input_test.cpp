// A `command` experiment of a fit file built from an experiment .prm (`input_prm` + `prm_set`)
// instead of a hand-kept template copy: the entries are set in the typed document, names are
// checked against `dtwire parameters`, and mistakes are errors at the fit file's field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dtwire/calibrate/command_simulator.hpp"
#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

namespace fs = std::filesystem;

fs::path write_fit(const std::string& name, const std::string& experiment_fields) {
  const fs::path dir = fs::temp_directory_path() / "dtwire_prm_input_test";
  fs::create_directories(dir);
  const fs::path source = fs::path(DTWIRE_SOURCE_DIR) / "experiments/dt";
  std::ofstream(dir / (name + ".toml"))
      << "title = \"t\"\n[simulator]\nkind = \"command\"\nprogram = \"" << DTWIRE_EXECUTABLE_PATH << "\"\n"
      << "arguments = [\"run\", \"{input}\", \"--out\", \"{output}\", \"-q\"]\n"
      << "[[parameter]]\nname = \"mu\"\nunit = \"1\"\ninitial = 0.3\nlower = 0.1\nupper = 0.5\n"
      << "[[experiment]]\nname = \"dt\"\ntarget = \"t.csv\"\nabscissa = \"displacement\"\nchannels = [\"force\"]\n"
      << "input_prm = \"" << (source / "dt_tension.prm").string() << "\"\n"
      << experiment_fields;
  return dir / (name + ".toml");
}

FitReadOptions without_targets() {
  FitReadOptions options;
  options.read_targets = false;
  return options;
}

TEST(PrmInput, EntriesAreSetInTheExperimentPrm) {
  const fs::path fit = write_fit("good", "[experiment.prm_set]\n\"Wire contact/Friction coefficient\" = \"{mu}\"\n"
                                         "\"Boundary conditions/Load path (mm)\" = \"0:0, 1:5\"\n"
                                         "\"Output/Fields\" = false\n\"Newton/Maximum iterations\" = 20\n");
  FitDefinition def;
  ASSERT_NO_THROW(def = read_fit_file(fit, without_targets()));
  const auto* simulator = dynamic_cast<const CommandSimulator*>(def.experiments.at(0).simulator.get());
  ASSERT_NE(simulator, nullptr);
  const PrmDocument input = PrmDocument::parse(simulator->instantiate({{"mu", 0.25}}), "input");
  EXPECT_EQ(input.get("Wire contact/Friction coefficient").value(), "0.25");
  EXPECT_EQ(input.get("Boundary conditions/Load path (mm)").value(), "0:0, 1:5");
  EXPECT_EQ(input.get("Output/Fields").value(), "false");
  EXPECT_EQ(input.get("Newton/Maximum iterations").value(), "20");
  // The mesh is found from the .prm's folder, wherever the copy runs.
  EXPECT_EQ(fs::path(input.get("Geometry/Mesh file").value()),
            fs::path(DTWIRE_SOURCE_DIR) / "experiments/dt" / "dt_level0.msh");
  // Everything else as in the experiment file.
  const PrmDocument original = PrmDocument::read(fs::path(DTWIRE_SOURCE_DIR) / "experiments/dt/dt_tension.prm");
  EXPECT_EQ(input.get("Wire contact/Normal penalty factor"), original.get("Wire contact/Normal penalty factor"));
  EXPECT_EQ(input.get("Material/Hardening table"), original.get("Material/Hardening table"));
}

TEST(PrmInput, UnknownEntryIsAnErrorAtItsFieldWithTheClosestName) {
  const fs::path fit = write_fit("typo", "[experiment.prm_set]\n\"Wire contact/Friction coeficient\" = \"{mu}\"\n");
  try {
    read_fit_file(fit, without_targets());
    ADD_FAILURE() << "an unknown entry was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), fit.string());
    EXPECT_EQ(e.line(), 19) << e.what();  // the key's line
    EXPECT_NE(std::string(e.what()).find("Wire contact/Friction coefficient"), std::string::npos) << e.what();
  }
}

TEST(PrmInput, TemplateAndPrmTogetherOrAPlaceholderWithoutValueAreRefused) {
  const auto message = [](const fs::path& fit) {
    try {
      read_fit_file(fit, without_targets());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(write_fit("both", "input_template = \"x.prm.in\"\n")).find("either input_prm"), std::string::npos);
  EXPECT_NE(message(write_fit("unfilled", "[experiment.prm_set]\n\"Wire contact/Friction coefficient\" = \"{nu}\"\n"))
                .find("{nu}"),
            std::string::npos);
}

}  // namespace
}  // namespace dtwire::calibrate
