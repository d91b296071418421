// Load paths and the two-node driver (on the WirePM law, whose closed form is known).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/driver.hpp"
#include "dtwire/dem/export_params.hpp"
#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

ParameterMap wirepm_parameters() {
  ParameterSet set{"sw", "wirepm", {}};
  set.set("reference_length_m", 0.06);
  set.set("diameter_m", 0.0027);
  add_backbone(set, read_backbone_csv(std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/sw_2.7mm_dem_backbone.csv"));
  return set.map();
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_dem_driver_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(Paths, PrescribedPathsReachTheirTargets) {
  PathOptions o;
  o.steps = 500;
  const LoadPath pull = make_path("axial_pull", o);
  ASSERT_EQ(pull.samples.size(), 501u);
  EXPECT_EQ(pull.samples.front().displacement.norm(), 0.0);
  EXPECT_NEAR(pull.samples.back().displacement(0), 0.4 * 0.06, 1e-15);  // max strain x l0
  EXPECT_NEAR(pull.samples.back().time, 1.0, 1e-12);
  EXPECT_NEAR(make_path("compression", o).samples.back().displacement(0), -0.1 * 0.06, 1e-15);
  const LoadPath spin = make_path("bending_spin", o);
  EXPECT_EQ(spin.samples.back().displacement(0), 0.0);
  EXPECT_NEAR(spin.samples.back().displacement(4), 0.5, 1e-15);
  const LoadPath both = make_path("pull_spin", o);
  EXPECT_NEAR(both.samples[250].displacement(0) / both.samples[250].displacement(4), 0.024 / 0.5, 1e-12);
  for (std::size_t i = 1; i < pull.samples.size(); ++i) ASSERT_GT(pull.samples[i].time, pull.samples[i - 1].time);
  EXPECT_THROW(make_path("twist_and_shout", o), std::invalid_argument);
}

TEST(Paths, CyclesUnloadToZeroBetweenRisingPeaks) {
  PathOptions o;
  const std::vector<Breakpoint> b = path_breakpoints("cycles", o);
  ASSERT_EQ(b.size(), 10u);
  for (std::size_t i = 2; i + 1 < b.size(); i += 2) EXPECT_EQ(b[i].axial, 0.0);
  for (std::size_t i = 3; i < b.size(); i += 2) EXPECT_GT(b[i].axial, b[i - 2].axial);
  const LoadPath path = make_path("cycles", o);
  std::size_t total = 0;
  for (const std::size_t n : leg_steps(b, o.reference_length, o.steps)) total += n;
  EXPECT_EQ(path.samples.size(), total + 1);
  EXPECT_NEAR(path.samples.back().displacement(0), 0.024, 1e-15);
}

TEST(Driver, AxialPullOnWirePmRecordsTheBackboneAndTheBreak) {
  const auto law = make_contact_law("wirepm", wirepm_parameters());
  PathOptions o;
  o.steps = 400;
  const Curve history = replay_path(*law, make_path("axial_pull", o));
  const std::vector<double> force = history.si("axial_force");
  const std::vector<double> broken = history.channel("broken").values;
  double peak = 0.0;
  for (double f : force) peak = std::max(peak, f);
  EXPECT_NEAR(peak, 5.6585e8 * kPi * 0.0027 * 0.0027 / 4.0, 1e-6);  // last backbone force [N]
  EXPECT_EQ(force.back(), 0.0);
  EXPECT_EQ(broken.back(), 1.0);
  // Energy columns balance at every sample (1e-10 relative).
  const auto ext = history.si("external_work"), el = history.si("elastic_energy"), pl = history.si("plastic_work"),
             dm = history.si("damage_work");
  for (std::size_t i = 0; i < ext.size(); ++i) ASSERT_NEAR(ext[i], el[i] + pl[i] + dm[i], 1e-10 * std::max(1.0, ext[i]));
}

TEST(Driver, FreeOscillationOfAnElasticWireHasTheClosedFormAmplitude) {
  const ParameterMap p = wirepm_parameters();
  const auto law = make_contact_law("wirepm", p);
  const double kn = dynamic_cast<const WirePmLaw&>(*law).backbone().unloading_stiffness;
  FreeOscillationOptions o;
  o.initial_axial_velocity = 0.5;  // amplitude v0 sqrt(m/k) = 9.3e-6 m, far below yield (1.15e-4 m)
  o.periods = 0.25;                // a tension-only bond holds the node for half a period only
  o.steps = 2000;
  const Curve history = run_free_oscillation(*law, o);
  const auto displacement = history.si("axial_displacement");
  double peak = 0.0;
  for (double d : displacement) peak = std::max(peak, d);
  const double amplitude = o.initial_axial_velocity * std::sqrt(o.mass / kn);
  EXPECT_NEAR(peak, amplitude, 1e-3 * amplitude);  // symplectic Euler at 8000 steps per period
  // No plastic work: all the external work is stored (round-off).
  EXPECT_NEAR(history.si("external_work").back(), history.si("elastic_energy").back(), 1e-12 * history.si("elastic_energy").back());
  EXPECT_NEAR(history.si("elastic_energy").back(), 0.5 * o.mass * o.initial_axial_velocity * o.initial_axial_velocity,
              2e-3 * 0.5 * o.mass * 0.25);  // kinetic energy turned into spring energy at a quarter period
}

TEST(Driver, RunsAllPathsAndWritesCsvAndHdf5) {
  const ParameterMap p = wirepm_parameters();
  PathOptions o;
  o.steps = 200;
  FreeOscillationOptions f;
  f.steps = 200;
  const auto runs = run_driver("wirepm", p, "all", o, f);
  ASSERT_EQ(runs.size(), 6u);
  const auto dir = scratch("all");
  write_driver_results(runs, "wirepm", p, dir, make_provenance("test"));
  for (const auto& run : runs) {
    const Curve back = read_csv(dir / (run.path_name + ".csv"));
    ASSERT_EQ(back.size(), run.history.size());
    const auto a = back.si("axial_force"), b = run.history.si("axial_force");
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]);  // newton values round-trip exactly
  }
  const Results results = read_results(dir / "driver.h5");
  EXPECT_EQ(results.curves.size(), 6u);
  EXPECT_EQ(results.parameters.size(), p.size());
}

TEST(Driver, ReplaysAPathCsvAndRejectsBadOnes) {
  const auto dir = scratch("csv");
  {
    std::ofstream out(dir / "ramp.csv");
    out << "# source: test\ntime_s,axial_displacement_mm,rotation_y_deg\n0,0,0\n1,0.05,1\n2,0.1,2\n3,0.05,2\n";
  }
  const LoadPath path = read_path_csv(dir / "ramp.csv");
  ASSERT_EQ(path.samples.size(), 4u);
  EXPECT_NEAR(path.samples[2].displacement(0), 1e-4, 1e-18);
  EXPECT_NEAR(path.samples[2].displacement(4), 2.0 * kPi / 180.0, 1e-15);
  const auto runs = run_driver("wirepm", wirepm_parameters(), (dir / "ramp.csv").string(), {}, {});
  ASSERT_EQ(runs.size(), 1u);
  const double kn = 2.5e8 * kPi * 0.0027 * 0.0027 / 4.0 / (0.0019230769 * 0.06);
  EXPECT_NEAR(runs[0].history.si("axial_force")[3], kn * 0.5e-4, 1e-9 * kn * 0.5e-4);  // elastic

  {
    std::ofstream out(dir / "back_in_time.csv");
    out << "# comment line without a colon\ntime_s,axial_displacement_mm\n0,0\n1,0.1\n1,0.2\n";
  }
  try {
    read_path_csv(dir / "back_in_time.csv");
    FAIL() << "accepted a non-increasing time";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 5);
    EXPECT_EQ(e.column(), 1);
  }
  {
    std::ofstream out(dir / "unknown.csv");
    out << "time_s,axial_force_N\n0,0\n1,1\n2,2\n";
  }
  try {
    read_path_csv(dir / "unknown.csv");
    FAIL() << "accepted a force column";
  } catch (const InputError& e) {
    EXPECT_EQ(e.column(), 2);
    EXPECT_NE(std::string(e.what()).find("axial_force_N"), std::string::npos);
  }
}

}  // namespace
}  // namespace dtwire::dem
