// Bonded grips (`Grip interface = bonded`, label verification): the bond law's return map and
// consistent tangent; a single wire from `dtwire mesh sw` pulled out of a weak bond (force plateau
// tau_b x the grip's lateral area, closed form; reversed slip; slip dissipation and energy
// balance); the bonded grip's stiffness approaching the clamped grip's as the penalty grows; bad
// input. Runs in-process; MPI is initialised once in main().
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "contact/bond_law.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/fem/run.hpp"

namespace dtwire::fem {
namespace {

using contact::BondHistory;
using contact::BondLaw;
using contact::Matrix3;
using contact::Vector3;

Vector3 vec(double x, double y, double z) {
  Vector3 v;
  v[0] = x, v[1] = y, v[2] = z;
  return v;
}

// d traction / d gap by central differences against the consistent tangent: stick, slip (with a
// committed slip vector, so that the return direction is not the gap's), and the elastic bond.
TEST(BondLaw, TangentMatchesCentralDifferences) {
  const Vector3 n = vec(0.6, 0.8, 0.0);  // unit
  BondHistory history;
  history.slip_vector = vec(-0.8e-6, 0.6e-6, 0.5e-6);  // tangential to n
  history.slip = 1.2e-6;
  const double k = 1e14, tau = 5e6;
  struct Case {
    const char* name;
    BondLaw law;
    Vector3 gap;
    bool slipping;
  };
  const Case cases[] = {{"stick", {k, tau, true}, history.slip_vector + vec(1e-8, -2e-8, 2.5e-8), false},
                        {"slip", {k, tau, true}, vec(3e-7, -1e-7, 4e-6), true},
                        {"elastic bond", {k, tau, false}, vec(3e-7, -1e-7, 4e-6), false}};
  for (const Case& c : cases) {
    const auto r = contact::evaluate_bond(c.law, history, n, c.gap);
    EXPECT_EQ(r.slipping, c.slipping) << c.name;
    const double h = 1e-12;
    double worst = 0.0, scale = 0.0;
    for (unsigned j = 0; j < 3; ++j) {
      Vector3 dg;
      dg[j] = h;
      const Vector3 fd = (contact::evaluate_bond(c.law, history, n, c.gap + dg).traction -
                          contact::evaluate_bond(c.law, history, n, c.gap - dg).traction) /
                         (2.0 * h);
      for (unsigned i = 0; i < 3; ++i) {
        worst = std::max(worst, std::abs(fd[i] - r.stiffness[i][j]));
        scale = std::max(scale, std::abs(r.stiffness[i][j]));
      }
    }
    EXPECT_LT(worst, 1e-6 * scale) << c.name;  // 1e-6 of the largest entry
  }
}

// Slip: |t_T| = tau_b exactly, Delta gamma = (|trial| - tau_b) / k, the new slip vector leaves
// exactly tau_b / k of elastic tangential gap, dissipation tau_b Delta gamma; the normal part
// stays elastic (-k g_N n) whatever the tangential state.
TEST(BondLaw, ReturnMapLandsOnTheStrength) {
  const Vector3 n = vec(0, 0, 1);
  const BondLaw law{2e14, 3e6, true};
  const Vector3 gap = vec(1e-7, -2e-7, -4e-8);
  const auto r = contact::evaluate_bond(law, BondHistory{}, n, gap);
  ASSERT_TRUE(r.slipping);
  const Vector3 t_t = r.traction - (r.traction * n) * n;
  EXPECT_NEAR(t_t.norm(), law.strength, 1e-9 * law.strength);
  const double trial = law.stiffness * std::hypot(1e-7, 2e-7);
  EXPECT_NEAR(r.slip_increment, (trial - law.strength) / law.stiffness, 1e-12 * r.slip_increment);
  EXPECT_NEAR(r.history.slip, r.slip_increment, 1e-20);
  EXPECT_NEAR((gap - (gap * n) * n - r.history.slip_vector).norm(), law.strength / law.stiffness, 1e-21);
  EXPECT_NEAR(r.dissipation, law.strength * r.slip_increment, 1e-12 * r.dissipation);
  EXPECT_NEAR(r.traction * n, -law.stiffness * gap[2], 1e-9 * law.stiffness * 4e-8);
  // Unloading from there (the gap moved back by half its elastic part, i.e. along t_T): stick,
  // half the strength, measured from the slipped anchor.
  const Vector3 back = gap + 0.5 * (law.strength / law.stiffness) * (t_t / t_t.norm());
  const auto s = contact::evaluate_bond(law, r.history, n, back);
  EXPECT_FALSE(s.slipping);
  EXPECT_NEAR((s.traction - (s.traction * n) * n).norm(), 0.5 * law.strength, 1e-9 * law.strength);
}

// ---- through the solver, on a SW mesh from the meshes module ----

std::filesystem::path scratch_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("dtwire_grip_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// 60 mm wire, 10 mm grips, level 0 (`dtwire mesh sw`); empty when the meshes module is missing.
std::filesystem::path sw_mesh() {
  static const std::filesystem::path mesh = [] {
    const auto dir = scratch_dir("mesh");
    const std::string command = std::string(DTWIRE_EXE) + " mesh sw --length 60 --grip-length 10 --level 0 -o " +
                                (dir / "sw.msh").string() + " > /dev/null 2>&1";
    return std::system(command.c_str()) == 0 ? dir / "sw.msh" : std::filesystem::path();
  }();
  return mesh;
}

// Lateral area of the faces with boundary id `id`, summed by deal.II's face measures (independent
// of the bond's quadrature).
double boundary_area(const std::filesystem::path& mesh, unsigned id) {
  dealii::Triangulation<3> tria;
  dealii::GridIn<3> in;
  in.attach_triangulation(tria);
  std::ifstream file(mesh);
  in.read_msh(file);
  double area = 0.0;
  for (const auto& cell : tria.active_cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == id) area += cell->face(f)->measure();
  return area;
}

// Elastic 2.7 mm wire on the SW mesh: grips 4 (bottom) and 5 (top).
std::string sw_prm(const std::string& boundary, const std::string& path, double step) {
  std::ostringstream prm;
  prm << "subsection Geometry\n set Mesh file = " << sw_mesh().string() << "\n set Cross section = full\nend\n"
      << "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      << " set Hardening law = linear\n set Yield stress (MPa) = 1e6\nend\n"
      << "subsection Boundary conditions\n set Bottom end = clamped\n set Top end = clamped\n"
      << " set Bottom boundary ids = 4\n set Top boundary ids = 5\n set Load path (mm) = " << path << "\n"
      << boundary << "end\n"
      << "subsection Load stepping\n set Initial step = " << step << "\n set Maximum step = " << step << "\nend\n"
      << "subsection Newton\n set Relative tolerance = 1e-9\nend\n"
      << "subsection Output\n set Fields = false\nend\n";
  return prm.str();
}

Curve run_prm(const std::string& name, const std::string& text, RunSummary* summary = nullptr) {
  const auto dir = scratch_dir(name);
  std::ofstream(dir / (name + ".prm")) << text;
  RunOptions options;
  options.parameter_file = dir / (name + ".prm");
  options.output_directory = dir / "out";
  options.command_line = "test " + name;
  options.echo = false;
  const RunSummary s = run_experiment(options);
  if (summary) *summary = s;
  return read_csv(s.curve_csv);
}

// (a) + (c): tau_b = 5 MPa, the top grip pulled 0.1 mm and pushed back to -0.1 mm in steps of
// 0.005 mm (elastic wire: the slip is the whole story). Closed form: once the whole top grip slides the force is
// tau_b A exactly (the facets contain the wire axis, so the slip is axial at every point), A the
// mesh's gripped area; reversed, -tau_b A. Dissipation over the sliding = tau_b A x slip; energy
// balance W_ext = elastic + bond + slip dissipation.
TEST(BondedGrip, WeakBondPlateausAtStrengthTimesGripAreaAndBalancesEnergy) {
  ASSERT_FALSE(sw_mesh().empty()) << "dtwire mesh sw failed (the mesher is part of every build)";
  const double tau = 5e6, d = 2.7e-3, grip_length = 10e-3;
  const double area = boundary_area(sw_mesh(), 5);
  const double capacity = tau * area;
  RunSummary summary;
  const Curve c = run_prm("plateau",
                          sw_prm(" set Grip interface = bonded\n set Grip bond strength (MPa) = 5\n",
                                 "0:0, 1:0.1, 3:-0.1", 0.05),
                          &summary);
  std::cout << "grip area: mesh " << area * 1e6 << " mm^2, pi d L_grip " << M_PI * d * grip_length * 1e6
            << " mm^2 (ratio " << area / (M_PI * d * grip_length) << "); capacity tau_b A = " << capacity << " N; "
            << summary.steps << " steps, " << summary.newton_iterations << " Newton iterations, " << summary.wall_seconds
            << " s\n";
  EXPECT_NEAR(std::stod(c.metadata("grip_top_area_mm2")) * 1e-6, area, 1e-9 * area);  // the bond's own quadrature
  const auto t = c.si("displacement"), f = c.si("force"), fraction = c.si("grip_slipping_fraction");
  const auto slip = c.si("grip_max_slip"), dissipation = c.si("grip_slip_dissipation");
  const auto work = c.si("external_work"), error = c.si("energy_balance_error");
  const std::size_t peak = std::max_element(t.begin(), t.end()) - t.begin();
  ASSERT_DOUBLE_EQ(t[peak], 1e-4);
  EXPECT_EQ(fraction[peak], 1.0);  // the whole top grip slides
  EXPECT_NEAR(f[peak], capacity, 1e-6 * capacity);  // 1e-6: Newton tolerance; the closed form is exact
  EXPECT_EQ(fraction.back(), 1.0);
  EXPECT_NEAR(f.back(), -capacity, 1e-6 * capacity);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_LE(std::abs(f[i]), capacity * (1 + 1e-6)) << "step " << i;
  // Dissipation while the whole grip slides, forwards (first full slip .. peak) and back
  // (first full reversed slip .. end): tau_b A x the slip of the points, which all slide by the
  // same amount up to the elastic strain differences along the grip (< 1e-4 here).
  std::size_t first = 1;
  while (fraction[first] < 1.0) ++first;
  std::size_t back = peak + 1;
  while (fraction[back] < 1.0) ++back;
  for (auto [a, b] : {std::pair{first, peak}, std::pair{back, f.size() - 1}}) {
    ASSERT_LT(a, b);
    const double expected = capacity * (slip[b] - slip[a]);
    EXPECT_NEAR(dissipation[b] - dissipation[a], expected, 1e-3 * expected) << a << " .. " << b;  // 0.1 %
    std::cout << "slip " << (slip[b] - slip[a]) * 1e3 << " mm: dissipation " << dissipation[b] - dissipation[a]
              << " J, tau_b A slip " << expected << " J\n";
  }
  // Energy balance (c): every step once a fifth of the final work is done, 1 %. The error comes from
  // the steps in which points go from stick to slip: the bond reaches tau_b early in the step,
  // the trapezoidal rule of the external work assumes a linear rise (about tau_b A du / 2 per
  // transition of the whole grip; it does not grow while sliding).
  double worst = 0.0;
  for (std::size_t i = 0; i < work.size(); ++i)
    if (work[i] > 0.2 * work.back()) worst = std::max(worst, std::abs(error[i]) / work[i]);
  std::cout << "external work " << work.back() << " J, slip dissipation " << dissipation.back()
            << " J, bond energy " << c.si("grip_bond_energy").back() << " J, elastic " << c.si("elastic_energy").back()
            << " J; largest balance error " << worst * 100 << " % of the work\n";
  EXPECT_LT(worst, 0.01);
}

// (b) Below the strength the bonded grip is an elastic penalty tie: its compliance (the bond's
// and the shear lag it allows in the gripped wire) vanishes as the stiffness factor grows, and
// the bonded wire's stiffness approaches the clamped one's (grips 4, 5 held) from below.
TEST(BondedGrip, StiffnessApproachesTheClampedGripAsThePenaltyGrows) {
  ASSERT_FALSE(sw_mesh().empty()) << "dtwire mesh sw failed (the mesher is part of every build)";
  const double u = 0.005e-3;
  const auto stiffness = [&](const std::string& name, const std::string& boundary) {
    return run_prm(name, sw_prm(boundary, "0:0, 1:0.005", 0.5)).si("force").back() / u;
  };
  const double clamped = stiffness("clamped", "");
  std::vector<double> ratio;
  for (const char* factor : {"1", "10", "100"})
    ratio.push_back(stiffness(std::string("bonded_") + factor,
                              " set Grip interface = bonded\n set Grip bond strength (MPa) = 1e5\n"
                              " set Grip bond stiffness factor = " +
                                  std::string(factor) + "\n") /
                    clamped);
  std::cout << "clamped stiffness " << clamped * 1e-6 << " kN/mm (E A / L_free " << 200e9 * M_PI * 1.35e-3 * 1.35e-3 / 40e-3 * 1e-6
            << " kN/mm); bonded / clamped at factors 1, 10, 100: " << ratio[0] << ", " << ratio[1] << ", " << ratio[2]
            << "\n";
  // Softer than the clamp, and the difference shrinks at least threefold per tenfold penalty
  // (about 1 / factor once the shear-lag length sqrt(E A / (k perimeter)) is below a cell).
  EXPECT_LT(ratio[2], 1.0);
  EXPECT_LT(1.0 - ratio[1], (1.0 - ratio[0]) / 3.0);
  EXPECT_LT(1.0 - ratio[2], (1.0 - ratio[1]) / 3.0);
  EXPECT_GT(ratio[2], 0.999);  // within 0.1 % at factor 100
}

// (d) Bad input: InputError naming the file and the entry.
TEST(BondedGrip, BadInputNamesTheEntry) {
  const std::string base =
      "subsection Geometry\n set Length (mm) = 10\n set Axial cells = 2\nend\n"
      "subsection Boundary conditions\n set Grip interface = bonded\n";
  const auto expect_error = [&](const std::string& name, const std::string& lines, const std::string& entry) {
    try {
      run_prm(name, base + lines + "end\nsubsection Output\n set Fields = false\nend\n");
      ADD_FAILURE() << name << ": expected InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name + ".prm"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(entry), std::string::npos) << e.what();
    }
  };
  expect_error("no_strength", "", "'Grip bond strength (MPa)'");
  expect_error("negative_strength", " set Grip bond strength (MPa) = -2\n", "'Grip bond strength (MPa)'");
  expect_error("zero_factor", " set Grip bond strength (MPa) = 2\n set Grip bond stiffness factor = 0\n",
               "'Grip bond stiffness factor'");
  expect_error("axial_top", " set Grip bond strength (MPa) = 2\n set Top end = axial\n", "'Grip interface = bonded'");
}

}  // namespace
}  // namespace dtwire::fem

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
