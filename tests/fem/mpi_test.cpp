// Serial vs 2 MPI ranks: `dtwire run` on a small necking bar (plastic, past the load maximum)
// gives the same curve, extensometer included, to 1e-8 relative; so does a wire in bonded grips.
// Runs the dtwire executable through mpirun.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <utility>
#include <sstream>

#include "dtwire/core/csv.hpp"

namespace {

const char* kPrm =
    "subsection Geometry\n set Diameter (mm) = 12.826\n set Length (mm) = 26.667\n set Cross section = quarter\n"
    " set Radial refinements = 1\n set Axial cells = 8\n set Imperfection = 0.018\n"
    " set Imperfection centre (mm) = 0\n set Imperfection half width (mm) = 26.667\nend\n"
    "subsection Material\n set Young modulus (MPa) = 206900\n set Poisson ratio = 0.29\n set Hardening law = voce\n"
    " set Yield stress (MPa) = 450\n set Saturation stress (MPa) = 715\n set Saturation rate = 16.93\n"
    " set Hardening modulus (MPa) = 129.24\nend\n"
    "subsection Boundary conditions\n set Bottom end = symmetry\n set Top end = axial\n"
    " set Load path (mm) = 0:0, 1:4, 1.2:3.6\nend\n"
    "subsection Load stepping\n set Initial step = 0.05\n set Maximum step = 0.1\nend\n"
    "subsection Output\n set Fields = true\n set Extensometer (mm) = 1 1 2, 1 1 20\nend\n";

// Runs the .prm serially and on 2 ranks (outputs in dir/serial, dir/parallel) and reads both curves.
std::pair<dtwire::Curve, dtwire::Curve> run_serial_and_parallel(const std::filesystem::path& dir,
                                                                const std::string& prm) {
  const std::string exe = DTWIRE_EXE;
  const std::string serial = exe + " run " + prm + " -q --out " + (dir / "serial").string();
  const std::string parallel =
      "mpirun --allow-run-as-root --oversubscribe -np 2 " + exe + " run " + prm + " -q --out " + (dir / "parallel").string();
  EXPECT_EQ(std::system(serial.c_str()), 0) << serial;
  EXPECT_EQ(std::system(parallel.c_str()), 0) << parallel;
  return {dtwire::read_csv(dir / "serial" / "curve.csv"), dtwire::read_csv(dir / "parallel" / "curve.csv")};
}

// Each channel agrees to 1e-8 relative to its largest serial value.
void expect_same_channels(const dtwire::Curve& a, const dtwire::Curve& b, std::initializer_list<const char*> quantities) {
  ASSERT_EQ(a.size(), b.size());
  for (const char* q : quantities) {
    const auto x = a.si(q), y = b.si(q);
    double scale = 0, diff = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      scale = std::max(scale, std::abs(x[i]));
      diff = std::max(diff, std::abs(x[i] - y[i]));
    }
    EXPECT_LE(diff, 1e-8 * scale) << q;
    std::cout << q << ": max |serial - 2 ranks| / max |serial| = " << diff / scale << "\n";
  }
}

TEST(Mpi, TwoRanksReproduceTheSerialCurve) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_fem_mpi_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto prm = dir / "bar.prm";
  std::ofstream(prm) << kPrm;
  const auto [a, b] = run_serial_and_parallel(dir, prm.string());
  // The extensometer's points lie in different ranks' cells (each rank locates what it owns).
  expect_same_channels(
      a, b, {"displacement", "force", "plastic_dissipation", "elastic_energy", "neck_radius", "extensometer_elongation"});
  EXPECT_TRUE(std::filesystem::exists(dir / "parallel" / "fields" / "fields.pvd"));
}

// The non-local crack initiation on the necking bar (Hosford-Coulomb a = 2, c = 0: D = alpha / b,
// largest at the neck): the averaging gathers every rank's points, so 2 ranks give the serial
// indicator to 1e-8; an average never exceeds the largest value it averages, so the non-local
// indicator stays at or below the local one step by step and reaches 1 no earlier; before the
// crack the indicator does not act on the stresses, so the forces of both runs agree.
TEST(Mpi, NonlocalCrackInitiationOnTwoRanksAndAgainstTheLocalIndicator) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_fem_mpi_test_nonlocal";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string prm = kPrm;
  const std::string failure = " set Failure locus = hosford-coulomb\n set Hosford-Coulomb b = 0.3\n set Stop at failure = true\n";
  prm.replace(prm.find("end\nsubsection Boundary"), 3, failure + "end");
  prm.replace(prm.find("0:0, 1:4, 1.2:3.6"), 17, "0:0, 1:5");
  prm.replace(prm.find("set Fields = true"), 17, "set Fields = false");
  std::ofstream(dir / "local.prm") << prm;
  prm.replace(prm.find(" set Stop at failure"), 0, " set Nonlocal radius (mm) = 4\n");
  std::ofstream(dir / "nonlocal.prm") << prm;
  const auto [serial, parallel] = run_serial_and_parallel(dir, (dir / "nonlocal.prm").string());
  expect_same_channels(serial, parallel, {"force", "damage"});
  const std::string exe = DTWIRE_EXE;
  const std::string local_run = exe + " run " + (dir / "local.prm").string() + " -q --out " + (dir / "local").string();
  ASSERT_EQ(std::system(local_run.c_str()), 0) << local_run;
  const dtwire::Curve local = dtwire::read_csv(dir / "local" / "curve.csv");
  const auto d_local = local.si("damage"), d_nonlocal = serial.si("damage");
  const auto f_local = local.si("force"), f_nonlocal = serial.si("force");
  ASSERT_GE(d_nonlocal.size(), d_local.size());  // the local crack first (its run stops there)
  ASSERT_GE(d_local.back(), 1.0);
  ASSERT_GE(d_nonlocal.back(), 1.0);
  EXPECT_LT(d_nonlocal[d_local.size() - 1], d_local.back());  // the neck is averaged with the shoulders
  for (std::size_t i = 0; i < d_local.size(); ++i) {
    EXPECT_LE(d_nonlocal[i], d_local[i] * (1.0 + 1e-6)) << "step " << i;
    EXPECT_NEAR(f_nonlocal[i], f_local[i], 1e-10 * std::abs(f_local.back())) << "step " << i;
  }
}

// Bonded grips on 2 ranks: a SW mesh (`dtwire mesh sw`, grips 4 and 5) whose top grip's bond
// slides forwards and back; the grip faces lie in both ranks' cells.
TEST(Mpi, BondedGripsOnTwoRanksReproduceTheSerialCurve) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_fem_mpi_test_grip";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string exe = DTWIRE_EXE;
  const std::string mesh = exe + " mesh sw --length 60 --grip-length 10 --level 0 -o " + (dir / "sw.msh").string() +
                           " > /dev/null 2>&1";
  ASSERT_EQ(std::system(mesh.c_str()), 0) << "dtwire mesh sw failed: " << mesh;
  std::ofstream(dir / "grip.prm")
      << "subsection Geometry\n set Mesh file = sw.msh\n set Cross section = full\nend\n"
         "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
         " set Hardening law = linear\n set Yield stress (MPa) = 1e6\nend\n"
         "subsection Boundary conditions\n set Bottom boundary ids = 4\n set Top boundary ids = 5\n"
         " set Grip interface = bonded\n set Grip bond strength (MPa) = 5\n set Load path (mm) = 0:0, 1:0.05, 2:-0.02\nend\n"
         "subsection Load stepping\n set Initial step = 0.1\n set Maximum step = 0.1\nend\n"
         "subsection Output\n set Fields = false\nend\n";
  const auto [a, b] = run_serial_and_parallel(dir, (dir / "grip.prm").string());
  expect_same_channels(a, b, {"force", "external_work", "grip_slip_dissipation", "grip_bond_energy", "grip_max_slip",
                              "grip_slipping_fraction", "energy_balance_error"});
  EXPECT_EQ(a.metadata("grip_capacity_N"), b.metadata("grip_capacity_N"));
}

}  // namespace
