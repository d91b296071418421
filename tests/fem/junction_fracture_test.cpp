// The experiments' fracture locus (issue 50; docs/fem_dt.md, "The junction's fracture"): the
// shipped files run as a user runs them, through the dtwire executable on the level-0 meshes.
//
// What must hold, and where each bound comes from:
// - The as-made DT in tension cracks at the SW/DT junction (within one diameter of a twist end:
//   fem/src/failure_place.hpp), as the laboratory's specimens do (thesis ch. 4), and the crack
//   runs: the force falls past the peak. Its peak is the calibration's target, the thesis DT set's
//   5.0 kN: this is a check that the calibration still holds (b was set on it), so it holds to
//   the goal's 10 % (issue 50), not to the bisection's 50 N.
// - The tight twist, which carries no forming strain, is stronger by more than 5 % (13 %
//   measured): the forming history is what brings the junction down to the laboratory's force.
// - The SW tension keeps its peak within 1 % of the same run with a wire too ductile to break (b
//   100; issue 50), and cracks past it at >= 8 % elongation on its 60 mm (EN 10223-3 asks >= 8 %
//   on 250 mm).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "process_scratch.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path& work_directory() { return dtwire::fem::testing::process_scratch_dir("dtwire_junction_fracture_test_"); }
using dtwire::fem::testing::read_text;

// Runs `dtwire run PRM --out DIR -q EXTRA`; returns run.log's text (empty on a failed run).
std::string run(const std::string& prm, const std::string& name, const std::string& extra) {
  const fs::path out = work_directory() / name;
  const std::string command = std::string(DTWIRE_EXE) + " run " DTWIRE_SOURCE_DIR "/experiments/" + prm +
                              " --out " + out.string() + " -q --set 'Output/Fields=false' " + extra + " > " +
                              (work_directory() / (name + ".console")).string() + " 2>&1";
  const int status = std::system(command.c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    ADD_FAILURE() << command << "\n" << read_text(work_directory() / (name + ".console"));
    return "";
  }
  return read_text(out / "run.log");
}

struct Failure {
  bool found = false;
  double displacement_mm = 0.0, force_N = 0.0, z_mm = 0.0;
  std::string place;
};

// run.log's `failure: in the junction, ... at displacement X mm, force F N, z = Z mm, ...`.
Failure failure_of(const std::string& log) {
  static const std::regex line(
      R"(failure: (in the (\w+), )?.*at displacement ([-0-9.e+]+) mm, force ([-0-9.e+]+) N, z = ([-0-9.e+]+) mm)");
  Failure f;
  std::smatch m;
  if (!std::regex_search(log, m, line)) return f;
  f = {true, std::stod(m[3]), std::stod(m[4]), std::stod(m[5]), m[2]};
  return f;
}

double peak_force_of(const std::string& log) {
  static const std::regex line(R"(peak force ([-0-9.e+]+) N)");
  std::smatch m;
  return std::regex_search(log, m, line) ? std::stod(m[1]) : NAN;
}

const std::string dt_mesh = "--set 'Geometry/Mesh file=" DTWIRE_SOURCE_DIR "/experiments/dt/dt_level0.msh'";

// The force of the curve's last row (curve.csv: displacement_mm, force_N first).
double last_force_of(const fs::path& curve) {
  std::ifstream in(curve);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') last = line;
  const auto comma = last.find(',');
  return comma == std::string::npos ? NAN : std::stod(last.substr(comma + 1, last.find(',', comma + 1) - comma - 1));
}

// One test for both DT runs: the as-made run is the longest in the suite (about 2 min), so the
// comparison with the tight twist reuses it rather than forming the twist a second time.
TEST(JunctionFracture, TheAsMadeTwistBreaksAtTheJunctionAtTheLaboratorysForceAndTheTightOneIsStronger) {
  const std::string as_made = run("dt/dt_tension.prm", "as_made", dt_mesh + " --set 'As made/Forming history=true'");
  const Failure f = failure_of(as_made);
  ASSERT_TRUE(f.found);
  EXPECT_EQ(f.place, "junction");
  const double peak = peak_force_of(as_made);
  EXPECT_NEAR(peak, 5000.0, 500.0);
  EXPECT_LT(last_force_of(work_directory() / "as_made" / "curve.csv"), 0.9 * peak);
  // Within one wire diameter of a twist end (z = 0 or 40 mm).
  EXPECT_LT(std::min(std::abs(f.z_mm), std::abs(f.z_mm - 40.0)), 2.7);

  const std::string tight = run("dt/dt_tension.prm", "tight", dt_mesh);
  ASSERT_TRUE(failure_of(tight).found);
  // Measured: 5.64 kN tight against 4.98 kN as made (13 %), both cracking at the same fibre.
  EXPECT_GT(peak_force_of(tight), 1.05 * peak);
}

TEST(JunctionFracture, TheSingleWireKeepsItsPeakAndBreaksPastIt) {
  const std::string path = "--set 'Boundary conditions/Load path (mm)=0:0, 1:20'";
  const std::string with_locus = run("default/sw_tension.prm", "sw", path);
  const std::string without = run("default/sw_tension.prm", "sw_no_failure", path + " --set 'Material/Hosford-Coulomb b=100'");
  const Failure f = failure_of(with_locus);
  ASSERT_TRUE(f.found);
  const double peak = peak_force_of(with_locus), reference = peak_force_of(without);
  EXPECT_NEAR(peak, reference, 0.01 * reference);
  EXPECT_GE(f.displacement_mm / 60.0, 0.08);
  EXPECT_LT(f.force_N, peak);  // past the load maximum, on the falling branch
}

}  // namespace
