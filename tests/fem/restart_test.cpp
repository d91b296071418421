// Checkpoint/restart with contact (label verification): a run resumed from a checkpoint written
// part-way repeats the uninterrupted run on every curve column, for each part that keeps state
// between steps: rigid tools (friction history), wire-wire contact (friction history, master
// faces, matrix pattern) and bonded grips (bond slip), plus the external-work sums. Runs the
// dtwire executable, serially and through mpirun on 2 ranks.
//
// Tolerances: on 1 rank the resumed curve is bit-identical (the same operations in the same
// order). On 2 ranks MUMPS's parallel factorisation of the contact-coupled matrix is itself
// reproducible to ~1e-13 only (two uninterrupted 2-rank DT runs differ there; on another machine
// the 2-rank grip run differed by 1e-12 N in a shear force that is itself round-off), so 2-rank
// columns are compared to 1e-6 of the largest value of their unit over a short path without
// cut-backs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <sys/wait.h>

#include "dtwire/core/csv.hpp"

namespace {

namespace fs = std::filesystem;

fs::path fresh_directory(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("dtwire_restart_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string dtwire_command(unsigned ranks) {
  const std::string exe = DTWIRE_EXE;
  return ranks == 1 ? exe : "mpirun --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) + " " + exe;
}

int run(const std::string& command, const fs::path& log) {
  return std::system((command + " > " + log.string() + " 2>&1").c_str());
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `prm` uninterrupted with a checkpoint every `interval` steps, then resumes a copy of its
// output from the checkpoint of step `restart` and compares the two curves column by column
// (`tolerance` relative to the largest magnitude among the columns of the same unit, so a column
// that is round-off noise in this test, e.g. the shear force of a pull, is judged against the
// run's forces; 0: bit-identical).
void expect_restart_repeats_the_run(const fs::path& dir, const fs::path& prm, unsigned ranks, unsigned interval,
                                    unsigned restart, double tolerance) {
  const std::string options = " -q --set 'Output/Checkpoint interval=" + std::to_string(interval) + "'";
  const std::string base = dtwire_command(ranks) + " run " + prm.string() + options;
  const fs::path full = dir / ("full_" + std::to_string(ranks)), resumed = dir / ("resumed_" + std::to_string(ranks));
  ASSERT_EQ(run(base + " --out " + full.string(), dir / "full.log"), 0) << read_text(dir / "full.log");
  fs::remove_all(resumed);
  fs::copy(full, resumed, fs::copy_options::recursive);
  fs::remove(resumed / "curve.csv");
  ASSERT_EQ(run(base + " --out " + resumed.string() + " --restart " + std::to_string(restart), dir / "resumed.log"), 0)
      << read_text(dir / "resumed.log");
  ASSERT_NE(read_text(resumed / "run.log").find("restarted from the checkpoint of step " + std::to_string(restart)),
            std::string::npos);
  const dtwire::Curve a = dtwire::read_csv(full / "curve.csv"), b = dtwire::read_csv(resumed / "curve.csv");
  ASSERT_GT(a.size(), restart + 2) << "the run must go on past the checkpoint";
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.channels().size(), b.channels().size());
  const auto unit_of = [](const std::string& column) { return column.substr(column.rfind('_') + 1); };
  std::map<std::string, double> unit_scale;  // largest magnitude over the columns sharing a unit
  for (const auto& channel : a.channels())
    for (double value : channel.values) {
      double& scale = unit_scale[unit_of(channel.column_name())];
      scale = std::max(scale, std::abs(value));
    }
  // The end moments of a pull are round-off themselves (1e-14 N m), so their own largest value
  // is no scale: a moment is judged against the largest force times 1 mm (a lever shorter than
  // any dimension of these specimens, so the check stays strict).
  unit_scale["Nm"] = std::max(unit_scale["Nm"], 1e-3 * unit_scale["N"]);
  for (std::size_t c = 0; c < a.channels().size(); ++c) {
    const auto& x = a.channels()[c];
    const auto& y = b.channels()[c];
    ASSERT_EQ(x.column_name(), y.column_name());
    if (tolerance == 0.0) {
      EXPECT_EQ(x.values, y.values) << x.column_name();
      continue;
    }
    double difference = 0.0;
    for (std::size_t i = 0; i < x.values.size(); ++i) difference = std::max(difference, std::abs(x.values[i] - y.values[i]));
    EXPECT_LE(difference, tolerance * unit_scale[unit_of(x.column_name())]) << x.column_name();
  }
}

// The bundled DT tension (level-0 mesh, wire-wire contact with friction) on a short path:
// 0 -> 2 mm in steps of 0.2 mm, through the straightening of the arms with sliding.
fs::path short_dt_tension(const fs::path& dir) {
  const fs::path source = fs::path(DTWIRE_SOURCE_DIR) / "experiments" / "dt";
  fs::copy_file(source / "dt_level0.msh", dir / "dt_level0.msh", fs::copy_options::overwrite_existing);
  std::string text = read_text(source / "dt_tension.prm");
  const auto replace_line = [&](const std::string& key, const std::string& line) {
    const auto at = text.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    text.replace(at, text.find('\n', at) - at, line);
  };
  replace_line("set Load path (mm)", "set Load path (mm) = 0:0, 1:2");
  replace_line("set Initial step", "set Initial step = 0.1");
  replace_line("set Maximum step", "set Maximum step = 0.1");
  replace_line("set Fields", "set Fields = false");
  std::ofstream(dir / "dt_short.prm") << text;
  return dir / "dt_short.prm";
}

TEST(Restart, RigidToolsWithFrictionResumeBitIdentical) {
  const auto dir = fresh_directory("tools");
  const fs::path prm = fs::path(DTWIRE_SOURCE_DIR) / "experiments" / "verification" / "contact_sliding_block.prm";
  expect_restart_repeats_the_run(dir, prm, 1, 20, 60, 0.0);  // mid-drag: the block slides
}

TEST(Restart, WireContactResumesBitIdenticalOnOneRankAndToRoundOffOnTwo) {
  const auto dir = fresh_directory("wire_contact");
  const fs::path prm = short_dt_tension(dir);
  expect_restart_repeats_the_run(dir, prm, 1, 5, 5, 0.0);
  expect_restart_repeats_the_run(dir, prm, 2, 5, 5, 1e-6);
}

// A SW in bonded grips whose top bond slides forwards and back (as in the MPI test).
TEST(Restart, BondedGripsResumeBitIdenticalOnOneRankAndToRoundOffOnTwo) {
  const auto dir = fresh_directory("grip");
  const std::string mesh = std::string(DTWIRE_EXE) + " mesh sw --length 60 --grip-length 10 --level 0 -o " +
                           (dir / "sw.msh").string();
  ASSERT_EQ(run(mesh, dir / "mesh.log"), 0) << read_text(dir / "mesh.log");
  std::ofstream(dir / "grip.prm")
      << "subsection Geometry\n set Mesh file = sw.msh\n set Cross section = full\nend\n"
         "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
         " set Hardening law = linear\n set Yield stress (MPa) = 1e6\nend\n"
         "subsection Boundary conditions\n set Bottom boundary ids = 4\n set Top boundary ids = 5\n"
         " set Grip interface = bonded\n set Grip bond strength (MPa) = 5\n set Load path (mm) = 0:0, 1:0.05, 2:-0.02\nend\n"
         "subsection Load stepping\n set Initial step = 0.1\n set Maximum step = 0.1\nend\n"
         "subsection Output\n set Fields = false\nend\n";
  expect_restart_repeats_the_run(dir, dir / "grip.prm", 1, 5, 5, 0.0);  // before the reversal at step 10
  expect_restart_repeats_the_run(dir, dir / "grip.prm", 2, 5, 15, 1e-6);  // after it
}

// A checkpoint written by a run with contact tools does not fit the same specimen without
// them: exit code 2 and a message naming the checkpoint file, no crash.
TEST(Restart, CheckpointOfAnotherContactSetUpIsRefusedNamingTheFile) {
  const auto dir = fresh_directory("mismatch");
  const fs::path prm = fs::path(DTWIRE_SOURCE_DIR) / "experiments" / "verification" / "contact_sliding_block.prm";
  std::string text = read_text(prm);
  std::ofstream(dir / "no_tools.prm") << text.substr(0, text.find("subsection Contact"));
  const std::string base = std::string(DTWIRE_EXE) + " run ";
  ASSERT_EQ(run(base + prm.string() + " -q --out " + (dir / "out").string() + " --set 'Output/Checkpoint interval=10'",
                dir / "with.log"),
            0)
      << read_text(dir / "with.log");
  const int status = run(base + (dir / "no_tools.prm").string() + " -q --out " + (dir / "out").string() +
                             " --restart 10",
                         dir / "without.log");
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  const std::string message = read_text(dir / "without.log");
  EXPECT_NE(message.find("step_00010"), std::string::npos) << message;
  EXPECT_NE(message.find("contact tools"), std::string::npos) << message;
}

}  // namespace
