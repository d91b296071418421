// `dtwire dem run`: the input's bad-input errors (exit 2 naming the field), a small punch run
// through the library (outputs, energy balance, 1 vs 2 threads) and the YADE export.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/punch_figures.hpp"
#include "dtwire/dem/run.hpp"
#include "dtwire/dem/run_checks.hpp"

#include "run_cli.hpp"

namespace dtwire::dem {
namespace {

const std::string kData = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/";

std::string small_punch(const std::string& replace_from = "", const std::string& replace_to = "") {
  std::string text = "title = \"small punch\"\n"
                     "[mesh]\npattern = \"8x10_2.7mm\"\nwidth_m = 0.6\nheight_m = 0.6\n"
                     "[links.sw]\nparams = \"" + kData + "wirepm_sw_2.7mm.json\"\nbackbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n"
                     "[links.dt]\nparams = \"" + kData + "wirepm_dt_2.7mm.json\"\nbackbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n"
                     "[boundary]\npinned = [\"left\", \"right\", \"bottom\", \"top\"]\npretension_strain = 1e-4\n"
                     "[dynamics]\nlocal_damping = 0.5\nmass_scale = 100\nsettle_s = 0.05\n"
                     "[tool]\nkind = \"platter\"\nbase_radius_m = 0.12\nheight_m = 0.05\ngap_m = 0.002\n"
                     "speed_m_per_s = 0.5\ntravel_m = 0.2\n"
                     "[output]\ninterval_s = 0.01\nframes = 2\n";
  if (!replace_from.empty()) {
    const auto at = text.find(replace_from);
    if (at == std::string::npos) throw std::logic_error("test text has no " + replace_from);
    text.replace(at, replace_from.size(), replace_to);
  }
  return text;
}

std::filesystem::path write_input(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_dem_run_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

using Outcome = test::CliOutcome;
Outcome run_cli(const std::string& arguments) { return test::run_dtwire(arguments); }

void expect_bad_input(const std::string& name, const std::string& text, const std::string& field) {
  const auto path = write_input(name, text);
  const Outcome o = run_cli("dem run " + path.string() + " -q -o " + (path.parent_path() / "out_bad").string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(field), std::string::npos) << o.output;
}

TEST(DemRun, BadInputsExitTwoNamingTheField) {
  expect_bad_input("small.toml", small_punch("width_m = 0.6", "width_m = 0.05"), "mesh.width_m");
  expect_bad_input("nodt.toml", small_punch("[links.dt]", "[links.xx]"), "links.xx");
  {
    std::string text = small_punch();
    const auto at = text.find("[links.dt]");
    const auto end = text.find("[boundary]");
    text.erase(at, end - at);
    expect_bad_input("nodt2.toml", text, "links.dt");
  }
  expect_bad_input("dt.toml", small_punch("settle_s = 0.05", "settle_s = 0.05\ntime_step_s = 0.01"), "dynamics.time_step_s");
  expect_bad_input("inside.toml", small_punch("gap_m = 0.002", "gap_m = -0.01"), "tool.gap_m");
  expect_bad_input("law.toml", small_punch("[links.sw]\n", "[links.sw]\nlaw = \"thesis\"\n"), "links.sw.law");
  expect_bad_input("key.toml", small_punch("frames = 2", "frames = 2\nfrmes = 3"), "output.frmes");
  // Supports and initial state (docs/dem_engine.md, "Supports and initial state").
  expect_bad_input("support.toml", small_punch("pretension_strain = 1e-4", "support = \"rollers\""), "boundary.support");
  expect_bad_input("presag.toml", small_punch("pretension_strain = 1e-4", "presag_m = -0.01"), "boundary.presag_m");
  expect_bad_input("presag2.toml", small_punch("pretension_strain = 1e-4", "pretension_strain = 1e-4\npresag_m = 0.01"), "boundary.presag_m");
  expect_bad_input("wall.toml", small_punch("pretension_strain = 1e-4", "pretension_strain = 1e-4\nwall_below_m = 0.1"), "boundary.wall_below_m");
  {
    std::string text = small_punch("pretension_strain = 1e-4", "wall_below_m = 0.1");
    text.replace(text.find("settle_s = 0.05"), 15, "settle_s = 0.0");
    expect_bad_input("nosettle.toml", text, "dynamics.settle_s");
  }
  expect_bad_input("rest.toml", small_punch("settle_s = 0.05", "settle_s = 0.05\nsettle_rest_ratio = -1e-5"), "dynamics.settle_rest_ratio");
  expect_bad_input("restnan.toml", small_punch("settle_s = 0.05", "settle_s = 0.05\nsettle_rest_ratio = nan"), "dynamics.settle_rest_ratio");
  expect_bad_input("resttime.toml", small_punch("settle_s = 0.05", "settle_s = 0.0\nsettle_rest_ratio = 1e-5"), "dynamics.settle_rest_ratio");
  // Per-link-set options: the length mode, parameter overrides checked against the law's names.
  expect_bad_input("length.toml", small_punch("[links.dt]\n", "[links.dt]\nlength = \"link\"\n"), "links.dt.length");
  expect_bad_input("override.toml", small_punch("[links.dt]\n", "[links.dt]\nparameters = { slideb = 1.0 }\n"),
                   "links.dt.parameters.slideb");
}

// `[mesh] nodes_per_wire`: 2 or 3, an integer; 3 with WirePM links (axial only: each middle node
// a hinge) is refused; nothing is written for a refused input.
TEST(DemRun, NodesPerWireIsCheckedWhereItIsRead) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_dem_run_test" / "out_nodes_per_wire";
  for (const std::string value : {"4", "2.5", "1", "\"3\""}) {
    std::filesystem::remove_all(out);
    const auto path = write_input("nodes_per_wire.toml", small_punch("height_m = 0.6\n", "height_m = 0.6\nnodes_per_wire = " + value + "\n"));
    const Outcome o = run_cli("dem run " + path.string() + " -q -o " + out.string());
    EXPECT_EQ(o.code, 2) << value << ": " << o.output;
    EXPECT_NE(o.output.find("nodes_per_wire.toml:6:18: mesh.nodes_per_wire: expected an integer in [2, 3]"), std::string::npos)
        << value << ": " << o.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << value;
  }
  const auto wirepm = write_input("nodes_per_wire_wirepm.toml", small_punch("height_m = 0.6\n", "height_m = 0.6\nnodes_per_wire = 3\n"));
  const Outcome o = run_cli("dem run " + wirepm.string() + " -q -o " + out.string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("mesh.nodes_per_wire: 3 needs links with bending stiffness"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The small punch with the thesis sets.
std::string thesis_punch(const std::string& mesh_extra, const std::string& link_extra = "") {
  std::string text = small_punch("height_m = 0.6\n", "height_m = 0.6\n" + mesh_extra);
  for (const char* tag : {"sw", "dt"}) {
    const std::string file = std::string("wirepm_") + tag + "_2.7mm.json";
    const std::string backbone = "backbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n";
    text.replace(text.find(kData + file), (kData + file).size(), kData + "macroelement_thesis_params.json");
    text.replace(text.find(backbone), backbone.size(),
                 std::string("law = \"thesis\"\nwire_type = \"") + (std::string(tag) == "sw" ? "single_wire" : "double_twist") +
                     "\"\n" + link_extra);
  }
  return text;
}

// Three nodes per wire in the run: each half-link takes the whole wire's set (as calibrated with
// length = "set", rescaled to the wire's length with "link") at twice its stiffness, so that the
// two halves in series are the two-node mesh's link; the YADE export refuses it.
TEST(DemRun, HalfLinksTakeTheWholeWiresSetInEitherLengthMode) {
  for (const std::string length : {"set", "link"}) {
    const RunInput input = read_run_input(write_input("three_" + length + ".toml",
                                                      thesis_punch("nodes_per_wire = 3\n", "length = \"" + length + "\"\n")));
    ASSERT_EQ(input.mesh.nodes_per_wire, 3);
    const BuiltNet built = build_net(input);
    std::size_t checked = 0;
    for (const EngineLink& link : built.links) {
      ASSERT_EQ(link.link.parts, 2);  // no selvedge in this panel
      const auto& set = input.link_sets.at(link.link.tag).parameters;
      const double wire_length = link.link.tag == LinkTag::SingleWire ? 0.05 : 0.04;
      const double whole_EA = set.at("EA_N") * (length == "link" ? set.at("reference_length_m") / wire_length : 1.0);
      std::unique_ptr<ContactLaw> probe = link.law->clone();
      probe->update((Vector6() << 1e-8, 0, 0, 0, 0, 0).finished());
      EXPECT_NEAR(probe->forces()[0], 2.0 * whole_EA * 1e-8, 1e-9 * whole_EA * 1e-8) << length;
      ++checked;
    }
    EXPECT_EQ(checked, built.links.size());
    EXPECT_EQ(built.mesh.net.nodes.size(), built.mesh.twist_end_nodes + built.links.size() / 2);
    try {
      yade_run_script(input);
      ADD_FAILURE() << "the YADE export took three nodes per wire";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("mesh.nodes_per_wire"), std::string::npos) << e.what();
    }
  }
}

// `dem run --set TABLE.KEY=VALUE` replaces an entry; the value is TOML and is checked as the
// file's; a malformed entry names --set.
TEST(DemRun, SetEntriesOverrideTheFileAndAreChecked) {
  const auto path = write_input("set.toml", small_punch());
  const RunInput in = read_run_input(path, {"boundary.support=\"slider\"", "boundary.pinned=[\"bottom\", \"top\"]",
                                            "links.dt.parameters.poisson_1=0.3", "tool.speed_m_per_s=0.25"});
  EXPECT_EQ(in.support, EdgeSupport::Slider);
  EXPECT_EQ(in.pinned_sides, unsigned(kBottom | kTop));
  EXPECT_DOUBLE_EQ(in.speed, 0.25);
  for (const char* bad : {"boundary.support=slider", "nokey", "boundary.support=\"rollers\"", "tool.sped_m_per_s=1.0"}) {
    const Outcome o = run_cli("dem run " + path.string() + " -q --set '" + bad + "' -o " + (path.parent_path() / "out_set").string());
    EXPECT_EQ(o.code, 2) << bad << ": " << o.output;
    EXPECT_NE(o.output.find("--set"), std::string::npos) << bad << ": " << o.output;
  }
}

TEST(DemRun, SmallPunchWritesItsFilesBalancesEnergyAndIsThreadIndependent) {
  const auto path = write_input("punch.toml", small_punch());
  RunOptions options;
  options.quiet = true;
  options.out = path.parent_path() / "out1";
  options.threads = 1;
  const RunSummary one = run_simulation(read_run_input(path), options);
  // 1 vs 2 threads (threading forced on this small net) on the first 6 cm of the push.
  const auto short_path = write_input("short.toml", small_punch("travel_m = 0.2", "travel_m = 0.06"));
  options.write_frames = false;
  options.parallel_threshold = 0;
  options.out = path.parent_path() / "out_serial";
  const RunSummary serial = run_simulation(read_run_input(short_path), options);
  options.out = path.parent_path() / "out_threads";
  options.threads = 2;
  const RunSummary threaded = run_simulation(read_run_input(short_path), options);
  Curve serial_history = serial.history, threaded_history = threaded.history;
  EXPECT_NE(serial_history.metadata("run_id"), threaded_history.metadata("run_id"));  // two runs
  serial_history.set_metadata("run_id", "");
  threaded_history.set_metadata("run_id", "");
  EXPECT_TRUE(serial_history == threaded_history);  // the same curve, bit for bit
  EXPECT_GT(serial.peak_force, 100.0);
  EXPECT_GT(one.peak_force, 100.0);
  EXPECT_LT(one.largest_balance_error, 0.02);  // issue: < 2 % of the work on the mesh
  for (const char* file : {"curve.csv", "results.h5", "link_force_histogram.csv", "pulling_angle_histogram.csv",
                           "membrane_at_peak.csv", "net.pvd", "frames/net_0.vtu"})
    EXPECT_TRUE(std::filesystem::exists(path.parent_path() / "out1" / file)) << file;
  const Curve curve = read_csv(path.parent_path() / "out1" / "curve.csv");
  for (const char* column : {"tool_displacement", "tool_velocity", "tool_force", "plastic_work", "damping_work", "balance_error"})
    EXPECT_TRUE(curve.has(column)) << column;
  // Pulling angles start at atan(40/30) = 53.13 deg; the histogram counts every SW-DT pair.
  const Curve angles = read_csv(path.parent_path() / "out1" / "pulling_angle_histogram.csv");
  double total = 0.0;
  for (double c : angles.channel("count_at_end").values) total += c;
  EXPECT_GT(total, 0.0);
  // One run id in every file of the run (issue 20).
  const std::string id = curve.metadata("run_id");
  EXPECT_FALSE(id.empty());
  EXPECT_EQ(read_results(path.parent_path() / "out1" / "results.h5").provenance.run_id, id);
  EXPECT_EQ(angles.metadata("run_id"), id);
  // The platter's radial sections at the peak (their sums against closed forms:
  // membrane_sections_test.cpp): one section on this 0.6 m panel, links crossing it in tension.
  // (One row: read_csv wants a curve of at least 3.)
  std::ifstream sections_file(path.parent_path() / "out1" / "membrane_at_peak.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(sections_file, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);  // run id, two forces, header, one row
  EXPECT_EQ(lines[0], "# run_id: " + id);
  EXPECT_EQ(lines[3].rfind("radius_m,crossing_links_1,vertical_force_N,radial_force_N,radial_tension_Npm,", 0), 0u) << lines[3];
  std::vector<double> row;
  std::stringstream cells(lines[4]);
  for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
  ASSERT_GE(row.size(), 5u);
  EXPECT_NEAR(row[0], 0.17, 1e-12);
  EXPECT_GT(row[1], 0.0);  // crossing links
  EXPECT_GT(row[2], 0.0);  // the outer net pulls the inside down
  EXPECT_GT(row[4], 0.0);  // in tension
  std::ifstream summary(path.parent_path() / "out1" / "summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"run_id\": \"" + id + "\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"rim_tension_at_peak_kN_per_m\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"damping_share_to_peak_percent\""), std::string::npos) << text;
  EXPECT_FALSE(one.failed);
  EXPECT_NE(text.find("\"status\": \"ok\""), std::string::npos) << text;
}

// A check that leaves its bound (issue 37) stops the run at that row: the partial curve stays,
// marked failed in curve.csv, results.h5 and summary.json, with the check, time and bound.
TEST(DemRun, FailedCheckStopsTheRunAndMarksItsPartialResults) {
  const auto path = write_input("failing.toml", small_punch("[output]", "[checks]\nmax_balance_error_percent = 1e-9\n[output]"));
  RunOptions options;
  options.quiet = true;
  options.write_frames = false;
  options.out = path.parent_path() / "out_failed";
  const RunSummary run = run_simulation(read_run_input(path), options);
  ASSERT_TRUE(run.failed);
  EXPECT_EQ(run.failed->check, "energy_balance");
  EXPECT_EQ(run.failed->key, "checks.max_balance_error_percent");
  EXPECT_GT(run.failed->value, run.failed->bound);
  EXPECT_GT(run.failed->step, 0);
  EXPECT_LT(run.history.size(), 40u);  // stopped early: the whole push is 0.4 s at 0.01 s
  EXPECT_EQ(run.history.metadata("status").rfind("failed: check 'energy_balance' failed at t = ", 0), 0u)
      << run.history.metadata("status");
  std::ifstream csv(options.out / "curve.csv");
  const std::string rows((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_NE(rows.find("# status: failed: check 'energy_balance'"), std::string::npos) << rows;
  std::ifstream summary(options.out / "summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"status\": \"failed\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"bound_key\": \"checks.max_balance_error_percent\""), std::string::npos) << text;
}

// The punch's headline figures from a curve whose values are known by hand: the onset between
// the samples that bracket 1 kN, the force at 0.42 m interpolated, and -1 for a travel that stops
// short of it (summary.json writes null there, never a force the run did not reach).
TEST(PunchFigures, OnsetProbeAndPeakByHandAndAProbeNotReached) {
  const std::vector<double> x{0.0, 0.1, 0.2, 0.3}, f{0.0, 500.0, 1500.0, 3000.0};
  const PunchFigures short_travel = punch_figures(x, f);
  EXPECT_DOUBLE_EQ(short_travel.onset, 0.15);
  EXPECT_DOUBLE_EQ(short_travel.peak_force, 3000.0);
  EXPECT_DOUBLE_EQ(short_travel.displacement_at_peak, 0.3);
  EXPECT_EQ(short_travel.force_at_probe, -1.0);
  const PunchFigures long_travel = punch_figures({0.0, 0.1, 0.2, 0.3, 0.5}, {0.0, 500.0, 1500.0, 3000.0, 5000.0});
  EXPECT_NEAR(long_travel.force_at_probe, 3000.0 + 0.6 * 2000.0, 1e-9);
}

// A check that fails on the loading's first row fails in the state the settle left: the message
// says the settle failed, not the loading; on a later row it does not.
TEST(DemRun, AFailedCheckOnTheFirstRowNamesTheSettle) {
  EnergySplit balanced;
  balanced.gravity_work = 10.0;  // J
  balanced.link_elastic = 10.0;
  EnergySplit runaway = balanced;
  runaway.kinetic = 5.0;  // 5 J from nowhere: a balance error of 50 % of the work
  RunGuard at_start(RunChecks{}, true);
  const auto first = at_start.check(runaway, 0.0, 1200);
  ASSERT_TRUE(first);
  EXPECT_TRUE(first->before_loading);
  EXPECT_NE(first->message().find("the settle failed, not the loading"), std::string::npos) << first->message();
  RunGuard later(RunChecks{}, true);
  ASSERT_FALSE(later.check(balanced, 0.0, 1200));
  const auto second = later.check(runaway, 0.01, 1300);
  ASSERT_TRUE(second);
  EXPECT_FALSE(second->before_loading);
  EXPECT_EQ(second->message().find("settle"), std::string::npos) << second->message();
}

// Cyclic punch: the platter reverses when the (interval-averaged) force reaches each level and
// reloads below the unload force, so the recorded force peaks once near each level, in order.
// The chattering instantaneous force once reversed it at a fraction of the first level.
TEST(DemRun, CyclicPunchReversesAtEachForceLevel) {
  const auto path = write_input("cyclic.toml", small_punch("travel_m = 0.2", "travel_m = 0.3\nforce_levels_N = [300.0, 800.0]\nunload_force_N = 50.0"));
  RunOptions options;
  options.quiet = true;
  options.write_frames = false;
  options.out = path.parent_path() / "out_cyclic";
  const RunSummary run = run_simulation(read_run_input(path), options);
  const auto& velocity = run.history.channel("tool_velocity").values;
  const auto& force = run.history.channel("tool_force").values;
  std::vector<double> peaks;  // largest force of each loading phase
  double phase_peak = 0.0;
  for (std::size_t i = 1; i < velocity.size(); ++i) {
    phase_peak = std::max(phase_peak, force[i]);
    if (velocity[i - 1] > 0.0 && velocity[i] < 0.0) {
      peaks.push_back(phase_peak);
      phase_peak = 0.0;
    }
  }
  ASSERT_EQ(peaks.size(), 2u);
  // The recorded mean lags the control average by up to an interval: within 25 % of each level.
  EXPECT_NEAR(peaks[0] / 300.0, 1.0, 0.25);
  EXPECT_NEAR(peaks[1] / 800.0, 1.0, 0.25);
}

TEST(DemRun, YadeScriptOfThePunchNamesTheSameNet) {
  const auto path = write_input("punch_yade.toml", small_punch());
  const RunInput input = read_run_input(path);
  const std::string script = yade_run_script(input);
  const BuiltNet built = build_net(input);
  EXPECT_NE(script.find("if links != " + std::to_string(built.mesh.net.links.size())), std::string::npos);
  EXPECT_NE(script.find("Law2_ScGeom_WirePhys_WirePM"), std::string::npos);
  // Macro-element sets cannot go to YADE.
  std::string macro = small_punch("[links.sw]\n", "[links.sw]\nlaw = \"thesis\"\nwire_type = \"single_wire\"\n");
  macro.replace(macro.find(kData + "wirepm_sw_2.7mm.json"), (kData + "wirepm_sw_2.7mm.json").size(),
                kData + "macroelement_thesis_params.json");
  macro.erase(macro.find("backbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n"),
              ("backbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n").size());
  EXPECT_THROW(yade_run_script(read_run_input(write_input("macro.toml", macro))), InputError);
}

// young= and poisson= of the material appended as `name = O.materials.append(...)`.
std::pair<double, double> script_material(const std::string& script, const std::string& name) {
  const auto at = script.find(name + " = O.materials.append(");
  if (at == std::string::npos) throw std::logic_error("no material " + name);
  const auto young = script.find("young=", at), poisson = script.find("poisson=", at);
  return {std::stod(script.substr(young + 6)), std::stod(script.substr(poisson + 8))};
}

// A hemisphere goes to YADE as one sphere whose material gives, through YADE's
// Ip2_FrictMat_FrictMat_FrictPhys (kn = 2 Ea Ra Eb Rb / (Ea Ra + Eb Rb), ks the same with E V),
// the input's node-platter stiffnesses; any other height as facets; a sphere asked for a
// semi-spheroid is refused naming tool.height_m.
TEST(DemRun, YadeScriptPlatterIsTheExactSphereForAHemisphere) {
  const RunInput flat = read_run_input(write_input("platter_flat.toml", small_punch()));
  EXPECT_NE(yade_run_script(flat).find("facet(["), std::string::npos);
  YadeScriptOptions sphere;
  sphere.platter = YadePlatter::Sphere;
  try {
    yade_run_script(flat, sphere);
    ADD_FAILURE() << "a sphere platter was exported for a semi-spheroid";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tool.height_m"), std::string::npos) << e.what();
  }
  const RunInput round = read_run_input(write_input("platter_round.toml", small_punch("height_m = 0.05", "height_m = 0.12")));
  const std::string script = yade_run_script(round);
  EXPECT_EQ(script.find("facet(["), std::string::npos);
  EXPECT_NE(script.find("sphere((cx, cy, base_z), base_radius, material=plate"), std::string::npos);
  EXPECT_NE(yade_run_script(round, YadeScriptOptions{YadePlatter::Facets}).find("facet(["), std::string::npos);
  const auto [node_young, node_poisson] = script_material(script, "wire");
  const auto [plate_young, plate_poisson] = script_material(script, "plate");
  const double a = plate_young * round.platter_base_radius, b = node_young * round.mesh.node_radius;
  const double kn = 2.0 * a * b / (a + b);
  const double ks = 2.0 * a * plate_poisson * b * node_poisson / (a * plate_poisson + b * node_poisson);
  EXPECT_NEAR(kn / round.contact.normal_stiffness, 1.0, 1e-9);
  EXPECT_NEAR(ks / round.contact.shear_stiffness, 1.0, 1e-9);
}

// tool.stop_below_peak_fraction: the push ends at the first recorded row where a link has broken
// and the force is below the fraction of the largest recorded force; every row up to it is the
// full push's, bit for bit (the small punch breaks 3 links and drops to 3.4 kN from 10.4 kN).
TEST(DemRun, PunchStopsAtTheNetsFailureWithTheCurveUpToItUnchanged) {
  RunOptions options;
  options.quiet = true;
  options.write_frames = false;
  options.threads = 1;
  const auto full_path = write_input("stop_full.toml", small_punch());
  options.out = full_path.parent_path() / "out_stop_full";
  const RunSummary full = run_simulation(read_run_input(full_path), options);
  const double fraction = 0.5;
  const auto stop_path = write_input("stop.toml", small_punch("travel_m = 0.2", "travel_m = 0.2\nstop_below_peak_fraction = 0.5"));
  options.out = full_path.parent_path() / "out_stop";
  const RunSummary stopped = run_simulation(read_run_input(stop_path), options);
  EXPECT_FALSE(full.stopped_at_failure);
  EXPECT_TRUE(stopped.stopped_at_failure);
  // The row the criterion picks in the full run's curve.
  const std::vector<double> force = full.history.channel("tool_force").values;
  const std::vector<double> broken = full.history.channel("broken_links").values;
  std::size_t stop_row = force.size();
  double peak = 0.0;
  for (std::size_t r = 0; r < force.size() && stop_row == force.size(); ++r) {
    peak = std::max(peak, force[r]);
    if (broken[r] > 0.0 && force[r] < fraction * peak) stop_row = r;
  }
  ASSERT_LT(stop_row + 1, force.size()) << "the full push must go on past the failure";
  ASSERT_EQ(stopped.history.size(), stop_row + 1);
  for (const Channel& column : full.history.channels()) {
    const std::vector<double>& b = stopped.history.channel(column.quantity).values;
    for (std::size_t r = 0; r <= stop_row; ++r) ASSERT_EQ(column.values[r], b[r]) << column.quantity << " row " << r;
  }
  EXPECT_EQ(stopped.peak_force, full.peak_force);
  EXPECT_EQ(stopped.displacement_at_peak, full.displacement_at_peak);
  EXPECT_EQ(stopped.onset, full.onset);
  EXPECT_LT(stopped.steps, full.steps);
  // Only for a monotonic punch, a fraction in [0, 0.99].
  expect_bad_input("stop_range.toml", small_punch("travel_m = 0.2", "travel_m = 0.2\nstop_below_peak_fraction = 1.5"),
                   "tool.stop_below_peak_fraction");
  expect_bad_input("stop_cyclic.toml",
                   small_punch("travel_m = 0.2", "travel_m = 0.2\nstop_below_peak_fraction = 0.5\nforce_levels_N = [500.0]"),
                   "tool.stop_below_peak_fraction");
}

}  // namespace
}  // namespace dtwire::dem
