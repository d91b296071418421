// `dtwire dem driver` and `dtwire export` end to end: files written, exit codes, messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/contact_law.hpp"
#include "dtwire/dem/export_params.hpp"

namespace {

namespace dem = dtwire::dem;

const std::string kData = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/";

struct Outcome {
  int exit_code;
  std::string output;  // stdout and stderr
};

Outcome shell_in(const std::filesystem::path& dir, const std::string& line) {
  const std::string command = "cd '" + dir.string() + "' && " + line + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (pipe && fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

Outcome run_in(const std::filesystem::path& dir, const std::string& arguments) {
  return shell_in(dir, "'" + std::string(DTWIRE_EXECUTABLE) + "' " + arguments);
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_dem_cli_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void write_text(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

TEST(DemCli, DriverRunsEveryPathOnTheThesisParameterFile) {
  const auto dir = scratch("driver");
  const Outcome r = run_in(dir, "dem driver --law thesis --params '" + kData +
                                    "macroelement_thesis_params.json' --wire-type single_wire --path all --steps 200 --out out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* path : {"axial_pull", "compression", "bending_spin", "pull_spin", "cycles", "free_oscillation"}) {
    const dtwire::Curve curve = dtwire::read_csv(dir / "out" / (std::string(path) + ".csv"));
    EXPECT_TRUE(curve.has("moment_y") && curve.has("axial_force") && curve.has("external_work")) << path;
  }
  EXPECT_EQ(dtwire::read_results(dir / "out" / "driver.h5").curves.size(), 6u);
  // Default parameter file (the thesis sets) and no --wire-type: every set in its own folder.
  const Outcome all_sets = run_in(dir, "dem driver --law thesis --path axial_pull --steps 50 --out sets");
  ASSERT_EQ(all_sets.exit_code, 0) << all_sets.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "sets" / "single_wire" / "axial_pull.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "sets" / "double_twist" / "axial_pull.csv"));
}

TEST(DemCli, BadInputExitsWithTwoAndSaysWhere) {
  const auto dir = scratch("bad");
  write_text(dir / "broken.json", "{\"law\": \"wirepm\", \"parameters\": {\"diameter_m\": true}}");
  Outcome r = run_in(dir, "dem driver --params broken.json --path axial_pull --out out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("broken.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("parameters.diameter_m"), std::string::npos) << r.output;
  write_text(dir / "flat.json", "{\"law\": \"wirepm\", \"parameters\": {\"diameter_m\": 0.0027, \"reference_length_m\": 0.06}}");
  r = run_in(dir, "dem driver --params flat.json --backbone '" + kData + "sw_2.7mm_dem_backbone.csv' --path spiral --out out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--path"), std::string::npos) << r.output;
  r = run_in(dir, "dem driver --params flat.json --path all --out out");  // no backbone
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("backbone"), std::string::npos) << r.output;
  r = run_in(dir, "dem driver --law thesis --params flat.json --path all --out out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("field 'law'"), std::string::npos) << r.output;
  EXPECT_EQ(run_in(dir, "dem").exit_code, 2);
}

TEST(DemCli, SurfaceWritesBothCurvesOfEverySetAndRefusesOtherLaws) {
  const auto dir = scratch("surface");
  Outcome r = run_in(dir, "dem surface --params '" + kData + "macroelement_thesis_params.json' --points 51 --out out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* set : {"single_wire", "double_twist"}) {
    const dtwire::Curve table = dtwire::read_csv(dir / "out" / (std::string(set) + "_yield_surface.csv"));
    ASSERT_EQ(table.size(), 102u) << set;  // two curves of 51 points
    const auto& strength = table.channel("yield_strength").values;
    const auto& force = table.channel("axial_force").values;
    const auto& moment = table.channel("moment").values;
    EXPECT_EQ(table.channel("moment").unit.symbol, "Nm");
    EXPECT_LT(strength.front(), strength.back()) << set;  // N0, then Nult
    EXPECT_EQ(force[50], strength.front());                // each curve ends at its N_y
    EXPECT_EQ(force[101], strength.back());
    EXPECT_GT(*std::max_element(moment.begin(), moment.end()), 0.0);
    EXPECT_EQ(table.metadata("law"), "thesis");
    EXPECT_EQ(table.metadata("wire_type"), set);
  }
  // One set of the file; a law without an N-M surface is refused, naming the file.
  r = run_in(dir, "dem surface --params '" + kData + "macroelement_thesis_params.json' --wire-type double_twist --out one");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "one" / "single_wire_yield_surface.csv"));
  write_text(dir / "wirepm.json", "{\"law\": \"wirepm\", \"parameters\": {\"diameter_m\": 0.0027}}");
  r = run_in(dir, "dem surface --params wirepm.json --out bad");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("wirepm.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("thesis or macro3d"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
  // A file whose second set is broken writes nothing, not even the first set's curves.
  write_text(dir / "half.json", "{\"a_set\": {\"D_m\": 0.0027, \"EA_N\": 1e6, \"EI_Nm2_per_deg_convention\": 0.1, "
                                "\"N0_N\": 100, \"Nult_N\": 200, \"Nc_N\": 100, \"m_f\": 0.03, \"beta_f\": 0.1, "
                                "\"k_F\": 1, \"k_M\": 1, \"m_g\": 1, \"alpha_g\": 0.5, \"beta_g\": 1, \"W1_J\": 1, "
                                "\"W2_J\": 2, \"alpha_d\": 1}, \"b_set\": {\"D_m\": 0.0027}}");
  r = run_in(dir, "dem surface --params half.json --out half");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("b_set"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "half"));
  // A rerun into a folder with an earlier run keeps only the new run's curves.
  r = run_in(dir, "dem surface --params '" + kData + "macroelement_thesis_params.json' --wire-type double_twist --out out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "single_wire_yield_surface.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "double_twist_yield_surface.csv"));
}

TEST(DemCli, ExportWritesTablesScriptAndTheCAbiBundle) {
  const auto dir = scratch("export");
  write_text(dir / "flat.json", "{\"law\": \"wirepm\", \"wire_type\": \"sw\", \"parameters\": {\"diameter_m\": 0.0027, "
                                "\"reference_length_m\": 0.06}}");
  Outcome r = run_in(dir, "export --params flat.json --backbone '" + kData + "sw_2.7mm_dem_backbone.csv' --out out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"sw_parameters.h5", "sw_parameters.json", "sw_parameters.csv", "sw_wirepm_yade.py",
                           "c_abi/README.md", "c_abi/dtwire_contact.h", "c_abi/libdtwire_contact.so"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / file)) << file;
  // The bundled example program builds against the copied header and library and runs.
  if (std::filesystem::exists(dir / "out" / "c_abi" / "contact_example.c")) {
    r = shell_in(dir / "out" / "c_abi",
               "cc -std=c11 -I. contact_example.c -L. -ldtwire_contact -lm "
               "-Wl,-rpath,\"$PWD\" -o example && ./example > example.log");
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  // The thesis file has no WirePM set: tables only, and the command says so.
  r = run_in(dir, "export --params '" + kData + "macroelement_thesis_params.json' --out thesis");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("single_wire: no YADE script"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "thesis" / "double_twist_parameters.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "thesis" / "macroelement_pfc7.dat"));  // the PFC7 plugin's commands
  r = run_in(dir, "export --params '" + kData + "macroelement_thesis_params.json' --wire-type gabion --out thesis");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("gabion"), std::string::npos) << r.output;
}

// `export --beam-shear`: the files carry beam_shear = 1, and a law built from them as a DEM code
// builds it (read_parameter_file, make_contact_law) has the slender beam's shear spring 12 k_b / L^2
// (docs/dem_laws.md, "Shear spring"); a WirePM set is refused with exit 2 and nothing written.
TEST(DemCli, ExportWithTheBeamsShearSpringWritesItIntoTheFilesAsTheLawsReadThem) {
  const auto dir = scratch("export_beam_shear");
  Outcome r = run_in(dir, "export --params '" + kData + "macroelement_thesis_params.json' --beam-shear --out beam");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* type : {"single_wire", "double_twist"}) {
    const std::vector<dem::ParameterSet> sets = dem::read_parameter_file(dir / "beam" / (std::string(type) + "_parameters.json"));
    ASSERT_EQ(sets.size(), 1u) << type;
    const dem::ParameterMap values = sets.front().map();
    ASSERT_EQ(values.at("beam_shear"), 1.0) << type;
    const auto law = dem::make_contact_law("thesis", values);
    dem::Vector6 increment = dem::Vector6::Zero();
    increment[1] = 1e-6;  // a shear displacement across the bond [m]
    law->update(increment);
    const double bending_per_radian = values.at("EI_Nm2_per_deg_convention") * 57.295779513082320876798154814105;
    const double length = values.at("reference_length_m");
    EXPECT_NEAR(law->forces()[1] / 1e-6, 12.0 * bending_per_radian / (length * length),
                1e-9 * 12.0 * bending_per_radian / (length * length)) << type;
  }
  r = run_in(dir, "export --params '" + kData + "wirepm_sw_2.7mm.json' --beam-shear --out wirepm");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--beam-shear applies to macro-element sets"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "wirepm"));
}

}  // namespace
