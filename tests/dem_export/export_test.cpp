// Parameter files (thesis, flat, calibrate formats), parameter tables round trips, bad input,
// and the YADE script generator.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>

#include "dtwire/core/error.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/export.hpp"

namespace dtwire::dem {
namespace {

const std::string kData = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/";

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_dem_export_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

std::string input_error_of(const std::filesystem::path& file) {
  try {
    read_parameter_file(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ParameterFile, ReadsTheThesisFile) {
  const auto sets = read_parameter_file(kData + "macroelement_thesis_params.json");
  ASSERT_EQ(sets.size(), 2u);
  const ParameterSet sw = select_wire_type(sets, "single_wire", "x");
  EXPECT_EQ(sw.map().at("N0_N"), 2750.0);  // the published value, unchanged
  EXPECT_EQ(sw.map().at("m_f"), 0.0285);
  const ParameterSet dt = select_wire_type(sets, "double_twist", "x");
  EXPECT_EQ(dt.map().at("Nult_N"), 5000.0);
  for (const ParameterEntry& e : sw.entries) {
    if (e.name == "EA_N") {
      EXPECT_EQ(e.unit, "N");
    }
  }
  EXPECT_THROW(select_wire_type(sets, "", "x"), InputError);  // two sets: must choose
  EXPECT_THROW(select_wire_type(sets, "gabion", "x"), InputError);
}

TEST(ParameterFile, ReadsFlatAndCalibrateFormats) {
  const auto dir = scratch("formats");
  const auto flat = write_text(dir / "flat.json", R"({"law": "wirepm", "wire_type": "sw",
      "parameters": {"reference_length_m": 0.06, "diameter_m": 0.0027},
      "backbone": {"strain_1": [0, 0.002, 0.01], "stress_Pa": [0, 2.6e8, 3e8]}})");
  const ParameterSet a = select_wire_type(read_parameter_file(flat), "", flat);
  EXPECT_EQ(a.law, "wirepm");
  EXPECT_EQ(a.wire_type, "sw");
  EXPECT_EQ(a.map().at("backbone_2_stress_Pa"), 3e8);
  const auto calibrate = write_text(dir / "calibrate.json", R"({"law": "thesis", "parameters": [
      {"name": "N0", "value": 2750, "unit": "N", "sigma": 12.5},
      {"name": "m_f", "value": 0.0285, "unit": "1"},
      {"name": "k_F", "value": 2.39e4, "unit": "1/m", "sigma": null}]})");
  const ParameterSet b = select_wire_type(read_parameter_file(calibrate), "", calibrate);
  EXPECT_EQ(b.wire_type, "default");
  ASSERT_EQ(b.entries.size(), 3u);
  EXPECT_EQ(b.entries[0].name, "N0_N");  // unit symbol appended
  EXPECT_EQ(*b.entries[0].sigma, 12.5);
  EXPECT_EQ(b.entries[2].name, "k_F");  // "1/m" is not a column unit symbol: name kept
  EXPECT_FALSE(b.entries[2].sigma.has_value());
}

// A DT specimen fit (calibrate's dem_specimen) writes both sets with sw./dt. prefixes.
TEST(ParameterFile, SpecimenFitSplitsIntoTheSingleWireAndDoubleTwistSets) {
  const auto dir = scratch("specimen");
  const auto joint = write_text(dir / "joint.json", R"({"law": "thesis", "wire_type": "dt_specimen", "parameters": [
      {"name": "dt.N0_N", "value": 2173, "unit": "N", "sigma": 144},
      {"name": "sw.N0_N", "value": 950, "unit": "N"},
      {"name": "dt.k_F", "value": 366, "unit": "1/m"}]})");
  const auto sets = read_parameter_file(joint);
  ASSERT_EQ(sets.size(), 2u);
  const ParameterSet dt = select_wire_type(sets, "double_twist", joint);
  EXPECT_EQ(dt.law, "thesis");
  EXPECT_EQ(dt.map(), (ParameterMap{{"N0_N", 2173.0}, {"k_F", 366.0}}));
  EXPECT_EQ(*dt.entries[0].sigma, 144.0);
  EXPECT_EQ(select_wire_type(sets, "single_wire", joint).map(), (ParameterMap{{"N0_N", 950.0}}));
  // Partly prefixed names are not a specimen fit: one set, names unchanged.
  const auto mixed = write_text(dir / "mixed.json", R"({"parameters": [
      {"name": "dt.N0_N", "value": 1, "unit": "N"}, {"name": "m_f", "value": 0.1, "unit": "1"}]})");
  ASSERT_EQ(read_parameter_file(mixed).size(), 1u);
}

TEST(ParameterFile, BadInputNamesTheFileAndTheField) {
  const auto dir = scratch("bad");
  EXPECT_NE(input_error_of(write_text(dir / "a.json", "{\"parameters\": {\"x\": 1,}}")).find("not valid JSON"),
            std::string::npos);
  const std::string text = input_error_of(write_text(dir / "b.json", R"({"parameters": {"N0_N": "lots"}})"));
  EXPECT_NE(text.find("b.json"), std::string::npos);
  EXPECT_NE(text.find("parameters.N0_N"), std::string::npos);
  EXPECT_NE(input_error_of(write_text(dir / "c.json", R"({"parameters": [{"name": "N0", "unit": "N"}]})"))
                .find("parameters[0].value"),
            std::string::npos);
  EXPECT_NE(input_error_of(write_text(dir / "d.json", R"({"single_wire": {"N0_N": 1, "D_m": [1]}})"))
                .find("single_wire.D_m"),
            std::string::npos);
  EXPECT_NE(input_error_of(write_text(dir / "e.json", R"({"source": "nothing here"})")).find("no parameters"),
            std::string::npos);
  EXPECT_NE(input_error_of(write_text(dir / "f.json", R"({"parameters": {"a": 1}, "backbone": {"strain_1": [0]}})"))
                .find("backbone"),
            std::string::npos);
  EXPECT_NE(input_error_of(dir / "missing.json").find("cannot open"), std::string::npos);
}

TEST(ParameterTables, RoundTripThroughJsonCsvAndHdf5) {
  auto sets = read_parameter_file(kData + "macroelement_thesis_params.json");
  sets[0].entries[0].sigma = 0.25;  // a calibrated uncertainty must survive too
  const auto dir = scratch("tables");
  const auto written = export_parameter_tables(sets, dir, make_provenance("test"));
  EXPECT_EQ(written.size(), 6u);  // three files per wire type
  for (const ParameterSet& set : sets) {
    const auto json_back = read_parameter_file(dir / (set.wire_type + "_parameters.json"));
    ASSERT_EQ(json_back.size(), 1u);
    EXPECT_EQ(json_back[0].wire_type, set.wire_type);
    ASSERT_EQ(json_back[0].entries.size(), set.entries.size());
    for (std::size_t i = 0; i < set.entries.size(); ++i) {
      EXPECT_EQ(json_back[0].entries[i].name, set.entries[i].name);
      EXPECT_EQ(json_back[0].entries[i].value, set.entries[i].value);  // exact
      EXPECT_EQ(json_back[0].entries[i].unit, set.entries[i].unit);
      EXPECT_EQ(json_back[0].entries[i].sigma, set.entries[i].sigma);
    }
    const Results h5 = read_results(dir / (set.wire_type + "_parameters.h5"));
    ASSERT_EQ(h5.parameters.size(), set.entries.size());
    for (const Parameter& p : h5.parameters) EXPECT_EQ(p.value, set.map().at(p.name));
    std::ifstream csv(dir / (set.wire_type + "_parameters.csv"));
    std::string line;
    std::size_t rows = 0;
    while (std::getline(csv, line))
      if (!line.empty() && line[0] != '#' && line != "name,value,unit,sigma") ++rows;
    EXPECT_EQ(rows, set.entries.size());
  }
}

// The PFC7 plugin's commands read back to every value of the thesis file, and the published
// load_properties.dat of the plugin's punch example (marcoprevitali/macroelement-doubletwist-PFC7)
// as the independent reference for property names, groups and rgap = reference length - D.
TEST(Pfc7Commands, ThesisSetsReadBackToEveryValueUnderThePluginsNames) {
  const std::vector<ParameterSet> sets = read_parameter_file(kData + "macroelement_thesis_params.json");
  const auto commands = read_pfc7_macroelement_commands(pfc7_macroelement_commands(sets, make_provenance("test")));
  ASSERT_EQ(commands.size(), 2u);
  const std::map<std::string, std::string> names = {
      {"me_ea", "EA_N"},      {"me_ei", "EI_Nm2_per_deg_convention"}, {"me_nzero", "N0_N"}, {"me_nult", "Nult_N"},
      {"me_ntens", "Nc_N"},   {"me_mff", "m_f"},   {"me_betaf", "beta_f"}, {"me_kf", "k_F"},   {"me_km", "k_M"},
      {"me_wpl1", "W1_J"},    {"me_wpl2", "W2_J"}, {"me_dalpha", "alpha_d"}, {"me_mfg", "m_g"}, {"me_alphag", "alpha_g"},
      {"me_betag", "beta_g"}, {"me_rata", "slide_a"}, {"me_ratb", "slide_b"}, {"me_ref_l", "reference_length_m"},
      {"me_d", "D_m"}};
  for (const ParameterSet& set : sets) {
    const int cmat = set.wire_type == "single_wire" ? 1 : 2;
    const auto& read = commands.at(cmat);
    const ParameterMap values = set.map();
    for (const auto& [property, key] : names) EXPECT_EQ(read.at(property), values.at(key)) << set.wire_type << " " << property;
    EXPECT_EQ(read.at("pb_ten"), 1e99);
  }
  // Published (load_properties.dat): SW me_ea 1.6e7, me_nzero 2.75e3, rgap 0.06 - 2.7e-3; DT me_nult
  // 5.0e3, me_km 1.12e-1, me_ratb 0.0015, rgap 0.035 - 2.7e-3 (the example's DT gap is 5 mm shorter than
  // its me_ref_l 0.04; we write reference length - D for both).
  EXPECT_EQ(commands.at(1).at("me_ea"), 1.6e7);
  EXPECT_EQ(commands.at(1).at("me_nzero"), 2.75e3);
  EXPECT_NEAR(commands.at(1).at("rgap"), 0.06 - 2.7e-3, 1e-15);
  EXPECT_EQ(commands.at(2).at("me_nult"), 5.0e3);
  EXPECT_EQ(commands.at(2).at("me_km"), 1.12e-1);
  EXPECT_EQ(commands.at(2).at("me_ratb"), 0.0015);
  EXPECT_NEAR(commands.at(2).at("rgap"), 0.04 - 2.7e-3, 1e-15);
}

// The plugin has no shear-spring property: a set asking for another spring is written with the
// plugin's properties and a note that PFC7 runs it with me_ea / 2.6 (docs/dem_laws.md, "Shear spring").
TEST(Pfc7Commands, ASetWithTheBeamsShearSpringIsWrittenWithANoteThatThePluginCannotCarryIt) {
  std::vector<ParameterSet> sets = read_parameter_file(kData + "macroelement_thesis_params.json");
  for (ParameterSet& set : sets) set.set("beam_shear", 1.0);
  const std::string text = pfc7_macroelement_commands(sets, make_provenance("test"));
  std::size_t notes = 0;
  for (std::size_t at = text.find("NOTE: this set asks for the slender beam's shear spring"); at != std::string::npos;
       at = text.find("NOTE: this set asks for the slender beam's shear spring", at + 1))
    ++notes;
  EXPECT_EQ(notes, 2u);
  const auto commands = read_pfc7_macroelement_commands(text);
  EXPECT_EQ(commands.at(1).at("me_ea"), 1.6e7);
  EXPECT_EQ(commands.at(1).count("beam_shear"), 0u);
}

TEST(Pfc7Commands, OtherLawsAreLeftOutAndNoThesisSetIsAnError) {
  ParameterSet wirepm;
  wirepm.wire_type = "single_wire";
  wirepm.law = "wirepm";
  EXPECT_FALSE(is_pfc7_macroelement_set(wirepm));
  EXPECT_THROW(pfc7_macroelement_commands({wirepm}, make_provenance("test")), std::invalid_argument);
}

// macro3d's optional bending-axial parameters: accepted by the schema, passed through the
// tables (JSON, CSV, HDF5, unit "1"), never written for the PFC7 plugin (it exports thesis sets
// only; a macro3d set is left out whatever it holds).
TEST(Pfc7Commands, Macro3dCouplingParametersPassThroughTheTablesButNotToPfc7) {
  std::vector<ParameterSet> sets = read_parameter_file(kData + "macroelement_thesis_params.json");
  ASSERT_EQ(sets.size(), 2u);
  ParameterSet& sw = sets[0].wire_type == "single_wire" ? sets[0] : sets[1];
  sw.law = "macro3d";
  sw.set("bending_axial_coupling", 1.0);
  sw.set("moment_hardening_ratio", 1.7);
  EXPECT_NO_THROW(check_parameter_names(sw, "macro3d", "x.json"));
  EXPECT_THROW(check_parameter_names(sw, "thesis", "x.json"), InputError);
  const auto dir = scratch("macro3d_coupling");
  export_parameter_tables({sw}, dir, make_provenance("test"));
  const auto back = read_parameter_file(dir / "single_wire_parameters.json");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].map().at("bending_axial_coupling"), 1.0);
  EXPECT_EQ(back[0].map().at("moment_hardening_ratio"), 1.7);
  for (const ParameterEntry& e : back[0].entries) {
    if (e.name == "bending_axial_coupling" || e.name == "moment_hardening_ratio") {
      EXPECT_EQ(e.unit, "1");
    }
  }
  const Results h5 = read_results(dir / "single_wire_parameters.h5");
  int found = 0;
  for (const Parameter& p : h5.parameters)
    if (p.name == "bending_axial_coupling" || p.name == "moment_hardening_ratio") ++found;
  EXPECT_EQ(found, 2);
  std::ifstream csv(dir / "single_wire_parameters.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("bending_axial_coupling,1,1,"), std::string::npos);
  EXPECT_NE(text.find("moment_hardening_ratio,1.7,1,"), std::string::npos);
  // PFC7: only the thesis set (double twist, cmat 2) is written; none of the new names.
  EXPECT_FALSE(is_pfc7_macroelement_set(sw));
  const std::string commands = pfc7_macroelement_commands(sets, make_provenance("test"));
  EXPECT_EQ(read_pfc7_macroelement_commands(commands).count(1), 0u);
  EXPECT_EQ(read_pfc7_macroelement_commands(commands).count(2), 1u);
  EXPECT_EQ(commands.find("coupling"), std::string::npos);
  EXPECT_EQ(commands.find("hardening_ratio"), std::string::npos);
  EXPECT_THROW(pfc7_macroelement_commands({sw}, make_provenance("test")), std::invalid_argument);
}

TEST(YadeScript, DescribesTheMaterialAndRefusesWhatYadeCannotDo) {
  ParameterSet set{"sw", "wirepm", {}};
  set.set("reference_length_m", 0.06);
  set.set("diameter_m", 0.0027);
  add_backbone(set, read_backbone_csv(kData + "sw_2.7mm_dem_backbone.csv"));
  const std::string script = yade_wirepm_script(set.map(), PathOptions{}, "out.csv");
  EXPECT_NE(script.find("WireMat("), std::string::npos);
  EXPECT_NE(script.find("(0.35, 565850000)"), std::string::npos);  // the last backbone point
  EXPECT_EQ(script.find("(0, 0)"), std::string::npos);              // YADE curves start past the origin
  EXPECT_NE(script.find("type=0"), std::string::npos);
  set.set("double_twist", 1);
  set.set("lambda_u", 0.2);
  EXPECT_THROW(yade_wirepm_script(set.map(), PathOptions{}, "out.csv"), std::invalid_argument);
  set.set("double_twist_model", 1);
  EXPECT_NE(yade_wirepm_script(set.map(), PathOptions{}, "out.csv").find("type=2"), std::string::npos);
}

}  // namespace
}  // namespace dtwire::dem
