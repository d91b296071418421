// Whole-solver verification (label verification): patch test on a distorted mesh, elastic
// cantilever vs Euler-Bernoulli, necking bar load maximum vs Considere, input errors.
// Runs in-process; MPI is initialised once in main().
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/fem/run.hpp"

namespace dtwire::fem {
namespace {

std::filesystem::path scratch_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("dtwire_fem_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

Curve run_prm(const std::string& name, const std::string& prm_text, RunSummary* summary = nullptr) {
  const auto dir = scratch_dir(name);
  const auto prm = dir / (name + ".prm");
  std::ofstream(prm) << prm_text;
  RunOptions options;
  options.parameter_file = prm;
  options.output_directory = dir / "out";
  options.command_line = "test " + name;
  options.echo = false;
  const RunSummary s = run_experiment(options);
  if (summary) *summary = s;
  return read_csv(s.curve_csv);
}

// Area-preserving polygon scale of the mesh cross-section (see wire_mesh.hpp).
double polygon_scale(double sides) { return std::sqrt(2.0 * M_PI / (sides * std::sin(2.0 * M_PI / sides))); }

// Second moment of area about the y axis (bending in x) of the mesh's regular polygon section
// (vertices at 45 deg + k 360/n deg, area-preserving scale), by the polygon formula.
double polygon_second_moment(double diameter, int sides) {
  const double rho = 0.5 * diameter * polygon_scale(sides);
  double I = 0;
  for (int k = 0; k < sides; ++k) {
    const double a0 = 2 * M_PI * k / sides + M_PI / 4, a1 = 2 * M_PI * (k + 1) / sides + M_PI / 4;
    const double x0 = rho * std::cos(a0), y0 = rho * std::sin(a0), x1 = rho * std::cos(a1), y1 = rho * std::sin(a1);
    I += (x0 * y1 - x1 * y0) * (x0 * x0 + x0 * x1 + x1 * x1) / 12.0;
  }
  return I;
}

// Homogeneous uniaxial bar, Hencky J2 with linear hardening: axial first Piola stress at stretch
// lambda (closed form: ln lambda = alpha + tau / E, tau = sigma_y(alpha)) and the lateral stretch.
void uniaxial_closed_form(double lambda, double E, double nu, double sy, double H, double& P, double& mu) {
  const double eps = std::log(lambda);
  double tau = E * eps, alpha = 0.0;
  if (tau > sy) {
    alpha = (eps - sy / E) / (1.0 + H / E);
    tau = sy + H * alpha;
  }
  P = tau / lambda;
  mu = std::exp(-0.5 * alpha - nu * tau / E);
}

class PatchTest : public ::testing::TestWithParam<const char*> {};

// Distorted interior vertices (25 % of the cell size), uniaxial stress past yield: the exact
// solution is homogeneous, so force and lateral contraction must be exact to round-off.
TEST_P(PatchTest, DistortedMeshReproducesTheHomogeneousSolution) {
  const double E = 200e9, nu = 0.3, sy = 400e6, H = 1e9, R = 1.35e-3, L = 10e-3, u_end = 0.6e-3;
  std::ostringstream prm;
  prm << "subsection Geometry\n set Diameter (mm) = 2.7\n set Length (mm) = 10\n set Cross section = quarter\n"
      << " set Radial refinements = 1\n set Axial cells = 3\n set Mesh distortion = 0.25\nend\n"
      << "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      << " set Hardening law = linear\n set Yield stress (MPa) = 400\n set Hardening modulus (MPa) = 1000\nend\n"
      << "subsection Formulation\n set Element = " << GetParam() << "\nend\n"
      << "subsection Boundary conditions\n set Bottom end = axial\n set Top end = axial\n"
      << " set Load path (mm) = 0:0, 1:0.6\nend\n"
      << "subsection Load stepping\n set Initial step = 0.25\n set Maximum step = 0.25\nend\n"
      << "subsection Output\n set Fields = false\nend\n";
  const Curve c = run_prm(std::string("patch_") + GetParam(), prm.str());
  const auto u = c.si("displacement"), f = c.si("force"), r = c.si("neck_radius");
  ASSERT_EQ(u.size(), 5u);
  EXPECT_DOUBLE_EQ(u.back(), u_end);
  const double A0 = M_PI * R * R;
  const double r0 = R * polygon_scale(16);
  for (std::size_t i = 1; i < u.size(); ++i) {
    double P = 0, mu = 0;
    uniaxial_closed_form(1.0 + u[i] / L, E, nu, sy, H, P, mu);
    EXPECT_NEAR(f[i], P * A0, 1e-9 * P * A0) << "step " << i;  // round-off
    EXPECT_NEAR(r[i], mu * r0, 1e-9 * r0) << "step " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(BothElements, PatchTest, ::testing::Values("fbar", "displacement"));

// Quadratic convergence of Newton in plastic steps, read from run.log: whenever the relative
// residual r_k is in [1e-6, 1e-2], r_{k+1} <= 10 r_k^2 (order 2 with a modest constant; below
// 1e-6 the next residual reaches the round-off floor ~1e-12), in a clamped bar with
// non-uniform plastic flow.
TEST(Newton, ConvergesQuadraticallyInPlasticSteps) {
  const char* prm =
      "subsection Geometry\n set Diameter (mm) = 2.7\n set Length (mm) = 10\n set Cross section = quarter\n"
      " set Radial refinements = 1\n set Axial cells = 6\nend\n"
      "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      " set Hardening law = voce\n set Yield stress (MPa) = 400\n set Saturation stress (MPa) = 600\n"
      " set Saturation rate = 20\n set Hardening modulus (MPa) = 200\nend\n"
      "subsection Boundary conditions\n set Bottom end = clamped\n set Top end = clamped\n"
      " set Load path (mm) = 0:0, 1:1\nend\n"
      "subsection Load stepping\n set Initial step = 0.1\n set Maximum step = 0.1\nend\n"
      "subsection Newton\n set Relative tolerance = 1e-12\n set Line search = false\nend\n"
      "subsection Output\n set Fields = false\nend\n";
  run_prm("newton", prm);
  std::ifstream log(std::filesystem::temp_directory_path() / "dtwire_fem_test_newton" / "out" / "run.log");
  std::string line;
  int checked = 0;
  while (std::getline(log, line)) {
    const auto colon = line.find("newton (relative residual):");
    if (colon == std::string::npos) continue;
    std::istringstream values(line.substr(line.find(':', colon) + 1));
    std::vector<double> r;
    for (double v; values >> v;) r.push_back(v);
    for (std::size_t k = 0; k + 1 < r.size(); ++k)
      if (r[k] <= 1e-2 && r[k] >= 1e-6) {
        EXPECT_LE(r[k + 1], 10 * r[k] * r[k]) << line;
        ++checked;
      }
  }
  EXPECT_GE(checked, 5) << "too few iterations in the asymptotic range";
}

// Elastic cantilever, clamped base, tip displaced laterally (rotation free): reaction
// P = 3 E I w / L^3 (Euler-Bernoulli). L/d = 20, Q2 elements; I of the polygonal section.
TEST(Cantilever, TipStiffnessWithinOnePercentOfEulerBernoulli) {
  const double E = 200e9, d = 2.7e-3, L = 54e-3, w = 0.05e-3;
  const char* prm =
      "subsection Geometry\n set Diameter (mm) = 2.7\n set Length (mm) = 54\n set Cross section = full\n"
      " set Radial refinements = 1\n set Axial cells = 16\nend\n"
      "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      " set Hardening law = linear\n set Yield stress (MPa) = 1e9\nend\n"
      "subsection Formulation\n set Element = displacement\n set Polynomial degree = 2\nend\n"
      "subsection Boundary conditions\n set Bottom end = clamped\n set Top end = axial\n"
      " set Load direction = lateral\n set Load path (mm) = 0:0, 1:0.05\nend\n"
      "subsection Load stepping\n set Initial step = 0.5\n set Maximum step = 0.5\nend\n"
      // Strains ~1e-5: the residual's round-off floor (from ln b near b = I) is ~1e-9 of the
      // internal force norm, so the default 1e-10 is out of reach.
      "subsection Newton\n set Relative tolerance = 1e-7\nend\n"
      "subsection Output\n set Fields = false\nend\n";
  const Curve c = run_prm("cantilever", prm);
  const double P = c.si("force").back();
  const double I = polygon_second_moment(d, 8);
  const double euler_bernoulli = 3.0 * E * I * w / (L * L * L);
  EXPECT_NEAR(P, euler_bernoulli, 0.01 * euler_bernoulli);  // 1 % (shear deformation ~0.15 %)
  std::cout << "cantilever: P = " << P << " N, 3EIw/L^3 = " << euler_bernoulli << " N, error "
            << (P / euler_bernoulli - 1) * 100 << " %\n";
}

// Slender elastic fixed-fixed column (d = 1 mm, L = 50 mm) with a bow of L/10000 in the buckling
// mode, compressed to three times the critical shortening: the force levels off at the buckling
// load, max force within 5 % of 4 pi^2 E I / L^2. Q2 elements.
TEST(Buckling, FixedFixedColumnOnsetWithinFivePercentOfEuler) {
  const double E = 200e9, d = 1e-3, L = 50e-3;
  const char* prm =
      "subsection Geometry\n set Diameter (mm) = 1\n set Length (mm) = 50\n set Cross section = full\n"
      " set Radial refinements = 1\n set Axial cells = 16\n set Bow imperfection (mm) = 0.005\nend\n"
      "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      " set Hardening law = linear\n set Yield stress (MPa) = 1e9\nend\n"
      "subsection Formulation\n set Element = displacement\n set Polynomial degree = 2\nend\n"
      "subsection Boundary conditions\n set Bottom end = clamped\n set Top end = clamped\n"
      " set Load path (mm) = 0:0, 1:-0.15\nend\n"
      "subsection Load stepping\n set Initial step = 0.05\n set Maximum step = 0.05\nend\n"
      "subsection Newton\n set Relative tolerance = 1e-8\nend\n"
      "subsection Output\n set Fields = false\nend\n";
  const Curve c = run_prm("buckling", prm);
  double peak = 0;
  for (double f : c.si("force")) peak = std::max(peak, -f);
  const double euler = 4 * M_PI * M_PI * E * polygon_second_moment(d, 8) / (L * L);
  std::cout << "buckling: peak " << peak << " N, 4 pi^2 E I / L^2 = " << euler << " N, error "
            << (peak / euler - 1) * 100 << " %\n";
  EXPECT_NEAR(peak, euler, 0.05 * euler);
}

// Considere estimate for the weakest section: F(alpha) = sigma_y(alpha) A0 exp(-alpha - sigma_y/E)
// (exact homogeneous Hencky bar, F = tau A0 / lambda), maximised over alpha.
double considere_peak(double A0, double E) {
  auto sy = [](double a) { return 450e6 + 265e6 * (1 - std::exp(-16.93 * a)) + 129.24e6 * a; };
  double best = 0;
  for (double a = 0; a < 0.5; a += 1e-5) best = std::max(best, sy(a) * A0 * std::exp(-a - sy(a) / E));
  return best;
}

// Coarse necking bar (Simo 1992; quarter section, half length): the load maximum within 2 % of
// the Considere estimate for the imperfect (1.8 % thinner) mid-section.
TEST(NeckingBar, CoarseLoadMaximumWithinTwoPercentOfConsidere) {
  std::ifstream in(std::string(DTWIRE_SOURCE_DIR) + "/experiments/verification/necking_bar.prm");
  std::stringstream text;
  text << in.rdbuf();
  std::string prm = text.str();
  auto set = [&](const std::string& key, const std::string& value) {
    const auto pos = prm.find("set " + key + " =");
    ASSERT_NE(pos, std::string::npos) << key;
    const auto end = prm.find('\n', pos);
    prm.replace(pos, end - pos, "set " + key + " = " + value);
  };
  set("Radial refinements", "1");
  set("Axial cells", "10");
  set("Load path (mm)", "0:0, 1:4.5");  // past the maximum (~3.5 mm on the half bar)
  set("Maximum step", "0.05");
  set("Fields", "false");
  RunSummary s;
  const Curve c = run_prm("necking", prm, &s);
  const double r_min = 6.413e-3 * (1 - 0.018);
  const double expected = considere_peak(M_PI * r_min * r_min, 206.9e9);
  std::cout << "necking (coarse): peak " << s.peak_force_N << " N at " << s.displacement_at_peak_mm
            << " mm; Considere (imperfect section) " << expected << " N; error "
            << (s.peak_force_N / expected - 1) * 100 << " %\n";
  EXPECT_NEAR(s.peak_force_N, expected, 0.02 * expected);
  const auto f = c.si("force");
  EXPECT_LT(f.back(), s.peak_force_N);  // the maximum was passed
}

// A SW mesh from the meshes module (gmsh .msh, written by `dtwire mesh sw` when the meshes
// module is built; skipped otherwise), elastic tension: force = E A u / L within the
// discretisation error of the polygonal section (1 %).
TEST(MeshFile, GmshSingleWireElasticStiffness) {
  const auto dir = scratch_dir("msh");
  const std::string mesh_cmd = std::string(DTWIRE_EXE) + " mesh sw --length 60 --grip-length 0 --level 0 -o " +
                               (dir / "sw.msh").string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(mesh_cmd.c_str()), 0) << "dtwire mesh sw failed: " << mesh_cmd;
  const char* prm =
      "subsection Geometry\n set Mesh file = sw.msh\n set Cross section = full\nend\n"
      "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      " set Hardening law = linear\n set Yield stress (MPa) = 1e9\nend\n"
      "subsection Boundary conditions\n set Bottom end = axial\n set Top end = clamped\n"
      " set Load path (mm) = 0:0, 1:0.006\nend\n"
      "subsection Load stepping\n set Initial step = 0.5\n set Maximum step = 0.5\nend\n"
      "subsection Newton\n set Relative tolerance = 1e-8\nend\n"
      "subsection Output\n set Fields = false\nend\n";
  std::ofstream(dir / "msh.prm") << prm;
  RunOptions options;
  options.parameter_file = dir / "msh.prm";
  options.output_directory = dir / "out";
  options.echo = false;
  const RunSummary s = run_experiment(options);
  const Curve c = read_csv(s.curve_csv);
  const double expected = 200e9 * M_PI * 1.35e-3 * 1.35e-3 * 6e-6 / 60e-3;  // E A u / L
  EXPECT_NEAR(c.si("force").back(), expected, 0.01 * expected);
}

// Checkpoint/restart: a run resumed from the checkpoint of step 5 (necking bar past its
// maximum, then unloading; with probes and an extensometer, whose records once went missing
// from checkpoints) reproduces the uninterrupted curve exactly, on every column.
TEST(Restart, ResumedRunReproducesTheUninterruptedCurve) {
  const char* prm =
      "subsection Geometry\n set Diameter (mm) = 12.826\n set Length (mm) = 26.667\n set Radial refinements = 1\n"
      " set Axial cells = 8\n set Imperfection = 0.018\n set Imperfection centre (mm) = 0\n"
      " set Imperfection half width (mm) = 26.667\nend\n"
      "subsection Material\n set Young modulus (MPa) = 206900\n set Poisson ratio = 0.29\n set Hardening law = voce\n"
      " set Yield stress (MPa) = 450\n set Saturation stress (MPa) = 715\n set Saturation rate = 16.93\n"
      " set Hardening modulus (MPa) = 129.24\nend\n"
      "subsection Boundary conditions\n set Bottom end = symmetry\n set Top end = axial\n"
      " set Load path (mm) = 0:0, 1:4, 1.2:3.6\nend\n"
      "subsection Load stepping\n set Initial step = 0.05\n set Maximum step = 0.1\nend\n"
      "subsection Output\n set Fields = false\n set Checkpoint interval = 5\n"
      " set Extensometer (mm) = 0 0 0, 0 0 10\nend\n";
  RunSummary full_run;
  const Curve full = run_prm("restart", prm, &full_run);
  ASSERT_GT(full_run.steps, 8u);
  RunOptions options;
  options.parameter_file = std::filesystem::temp_directory_path() / "dtwire_fem_test_restart" / "restart.prm";
  options.output_directory = std::filesystem::temp_directory_path() / "dtwire_fem_test_restart" / "out";
  options.echo = false;
  options.restart_step = 5;
  const RunSummary resumed_run = run_experiment(options);
  const Curve resumed = read_csv(resumed_run.curve_csv);
  EXPECT_EQ(resumed_run.steps, full_run.steps);
  ASSERT_EQ(resumed.size(), full.size());
  ASSERT_EQ(resumed.channels().size(), full.channels().size());
  ASSERT_TRUE(full.find("extensometer_elongation") != nullptr);
  for (std::size_t c = 0; c < full.channels().size(); ++c) {
    EXPECT_EQ(resumed.channels()[c].column_name(), full.channels()[c].column_name());
    EXPECT_EQ(resumed.channels()[c].values, full.channels()[c].values)  // bit-identical: same ranks, same operations
        << full.channels()[c].column_name();
  }
}

// Force control: elastic bar (one eighth: quarter section, mid-plane symmetry, top face moving
// as one), total force path 0 -> 1 kN -> 0. The converged reaction equals the prescribed force
// (relative residual 1e-9 of the largest path force: 1e-8 relative is reached); the homogeneous uniaxial Hencky bar has
// F = E A0 ln(lambda) / lambda exactly, the small-strain F L/(E A) is its first-order form.
TEST(ForceControl, ElasticBarReachesThePrescribedForce) {
  const double E = 200e9, d = 2.7e-3, L = 60e-3, F = 1000.0;
  const char* prm =
      "subsection Geometry\n set Diameter (mm) = 2.7\n set Length (mm) = 30\n set Cross section = quarter\n"
      " set Radial refinements = 1\n set Axial cells = 6\nend\n"
      "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      " set Hardening law = linear\n set Yield stress (MPa) = 1e9\nend\n"
      "subsection Boundary conditions\n set Bottom end = symmetry\n set Top end = axial\n"
      " set Control = force\n set Force path (N) = 0:0, 1:1000, 2:0\nend\n"
      "subsection Load stepping\n set Initial step = 0.25\n set Maximum step = 0.25\nend\n"
      "subsection Newton\n set Relative tolerance = 1e-9\nend\n"
      "subsection Output\n set Fields = false\nend\n";
  const Curve c = run_prm("force_control", prm);
  const auto force = c.si("force"), displacement = c.si("displacement");
  const std::size_t peak = std::max_element(force.begin(), force.end()) - force.begin();
  const double A = M_PI * d * d / 4;
  double lambda = 1.0 + F / (E * A);  // Newton on E A ln(lambda) / lambda = F
  for (int i = 0; i < 50; ++i)
    lambda -= (E * A * std::log(lambda) / lambda - F) / (E * A * (1 - std::log(lambda)) / (lambda * lambda));
  std::cout << "force control: F = " << force[peak] << " N (prescribed " << F << ", rel. error "
            << force[peak] / F - 1 << "), u = " << displacement[peak] * 1e3 << " mm, finite-strain closed form "
            << L * (lambda - 1) * 1e3 << " mm, F L/(E A) = " << F * L / (E * A) * 1e3 << " mm, back at F = "
            << force.back() << " N, u = " << displacement.back() * 1e3 << " mm\n";
  EXPECT_NEAR(force[peak], F, 1e-8 * F);                                    // 1e-8 relative
  EXPECT_NEAR(displacement[peak], L * (lambda - 1), 1e-7 * L * (lambda - 1));  // exact homogeneous solution
  EXPECT_NEAR(displacement[peak], F * L / (E * A), 2e-3 * F * L / (E * A));    // first order: 1.5 eps = 0.13 %
  EXPECT_NEAR(force.back(), 0.0, 1e-8 * F);                                 // unloaded
  EXPECT_NEAR(displacement.back(), 0.0, 1e-8 * L);                          // elastic: back to zero
}

// Krylov option: GMRES + PETSc GAMG with the rigid-body modes reproduces the MUMPS curve of an
// elastoplastic bar (Voce, clamped ends, plastic loading and elastic unloading) to 1e-6 relative.
// An imperfect plastic bar pulled past its load maximum and partly unloaded.
std::string imperfect_bar_prm() {
  return
      "subsection Geometry\n set Diameter (mm) = 2.7\n set Length (mm) = 20\n set Cross section = quarter\n"
      " set Radial refinements = 1\n set Axial cells = 12\n set Imperfection = 0.01\n"
      " set Imperfection centre (mm) = 0\n set Imperfection half width (mm) = 10\nend\n"
      "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n set Hardening law = voce\n"
      " set Yield stress (MPa) = 450\n set Saturation stress (MPa) = 715\n set Saturation rate = 16.93\n"
      " set Hardening modulus (MPa) = 129.24\nend\n"
      "subsection Boundary conditions\n set Bottom end = symmetry\n set Top end = clamped\n"
      " set Load path (mm) = 0:0, 1:2, 1.2:1.9\nend\n"
      "subsection Load stepping\n set Initial step = 0.05\n set Maximum step = 0.1\nend\n"
      "subsection Output\n set Fields = false\nend\n";
}

double largest_force_difference(const Curve& a, const Curve& b, double& scale) {
  const auto fa = a.si("force"), fb = b.si("force");
  EXPECT_EQ(fa.size(), fb.size());
  double difference = 0.0;
  scale = 0.0;
  for (std::size_t i = 0; i < std::min(fa.size(), fb.size()); ++i) {
    scale = std::max(scale, std::abs(fa[i]));
    difference = std::max(difference, std::abs(fa[i] - fb[i]));
  }
  return difference;
}

TEST(LinearSolver, GmresAmgReproducesTheDirectSolverCurve) {
  const std::string common = imperfect_bar_prm();
  const Curve direct = run_prm("linear_direct", common);
  const Curve krylov = run_prm("linear_krylov", common + "subsection Newton\n set Linear solver = gmres-amg\nend\n");
  double scale = 0.0;
  const double difference = largest_force_difference(direct, krylov, scale);
  std::cout << "gmres-amg vs direct: " << direct.size() << " points, largest force difference " << difference / scale
            << " of the peak force " << scale << " N\n";
  EXPECT_LT(difference, 1e-6 * scale);  // 1e-6 relative to the largest force
}

// From a run's run.log: how often `mark` follows a residual in the Newton histories, and the
// Newton iterations and factorisations of the `done:` line.
struct RunLogCounts {
  int marks = 0;
  std::size_t iterations = 0;
  std::size_t factorisations = std::numeric_limits<std::size_t>::max();  // none in the log: no comparison passes
};

RunLogCounts read_run_log(const std::string& name, char mark) {
  std::ifstream log(std::filesystem::temp_directory_path() / ("dtwire_fem_test_" + name) / "out" / "run.log");
  std::string line;
  RunLogCounts counts;
  while (std::getline(log, line)) {
    if (line.find("newton (relative residual):") != std::string::npos)
      counts.marks += static_cast<int>(std::count(line.begin(), line.end(), mark));
    if (line.rfind("done:", 0) == 0) {
      std::sscanf(line.c_str(), "done: %*u steps, %zu Newton iterations", &counts.iterations);
      const auto at = line.find(" factorisations");
      if (at != std::string::npos) counts.factorisations = std::stoul(line.substr(line.rfind(' ', at - 1) + 1));
    }
  }
  return counts;
}

// Modified Newton (Tangent reuse contraction): the same converged curve as full Newton over the
// same load steps (fixed: modified Newton takes more, cheaper iterations, which the step growth
// would count), both to the relative tolerance 1e-10, so 1e-6 of the peak force is far above
// their difference; kept factorisations (marked * in the Newton history) actually used.
TEST(Newton, ModifiedNewtonReproducesFullNewton) {
  const std::string fixed_steps = imperfect_bar_prm() + "subsection Load stepping\n set Maximum step = 0.05\nend\n";
  const Curve full = run_prm("newton_full", fixed_steps);
  const Curve modified = run_prm("newton_modified", fixed_steps +
                                                        "subsection Newton\n set Tangent reuse contraction = 0.2\n"
                                                        " set Maximum iterations = 40\nend\n");
  double scale = 0.0;
  const double difference = largest_force_difference(full, modified, scale);
  std::cout << "modified vs full Newton: largest force difference " << difference / scale << " of the peak force\n";
  EXPECT_LT(difference, 1e-6 * scale);
  EXPECT_GT(read_run_log("newton_modified", '*').marks, 5) << "no factorisation was kept";
}

// Lagged LU (GMRES preconditioned by an earlier tangent's factors): the same converged curve as
// the direct solver over the same load steps, both to the Newton tolerance 1e-10, so 1e-6 of the
// peak force is far above their difference; GMRES steps (marked ~ in the Newton history) used,
// and fewer factorisations than Newton iterations.
TEST(LinearSolver, LaggedLuReproducesTheDirectSolverCurve) {
  const std::string fixed_steps = imperfect_bar_prm() + "subsection Load stepping\n set Maximum step = 0.05\nend\n";
  const Curve direct = run_prm("linear_direct_fixed", fixed_steps);
  const Curve lagged = run_prm("linear_lagged", fixed_steps + "subsection Newton\n set Linear solver = lagged-lu\nend\n");
  double scale = 0.0;
  const double difference = largest_force_difference(direct, lagged, scale);
  std::cout << "lagged-lu vs direct: largest force difference " << difference / scale << " of the peak force\n";
  EXPECT_LT(difference, 1e-6 * scale);
  const RunLogCounts log = read_run_log("linear_lagged", '~');
  std::cout << "lagged-lu: " << log.marks << " GMRES steps, " << log.factorisations << " factorisations in "
            << log.iterations << " Newton iterations\n";
  EXPECT_GT(log.marks, 5) << "the lagged factors were never used";
  EXPECT_LT(log.factorisations, log.iterations);
}

// Virtual extensometer: on an elastic bar stretched uniformly (bottom axial, top pulled, free
// lateral contraction), a gauge between two points on the axis lengthens by the gauge length
// times the nominal strain, exactly; the curve's displacement_mm column can hold it instead of
// the load path (then in grip_displacement_mm). A gauge whose points coincide is an input error.
TEST(Extensometer, UniformBarGaugeElongationIsStrainTimesGaugeLength) {
  const std::string base =
      "subsection Geometry\n set Diameter (mm) = 2.7\n set Length (mm) = 30\n set Cross section = quarter\nend\n"
      "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
      " set Hardening law = linear\n set Yield stress (MPa) = 1e9\nend\n"
      "subsection Boundary conditions\n set Bottom end = axial\n set Top end = axial\n"
      " set Load path (mm) = 0:0, 1:0.03\nend\n"
      "subsection Load stepping\n set Initial step = 0.5\n set Maximum step = 0.5\nend\n"
      "subsection Newton\n set Relative tolerance = 1e-10\nend\n"
      "subsection Output\n set Fields = false\n set Extensometer (mm) = 0 0 5, 0 0 25; 0.5 0.5 10, 0.5 0.5 12\n";
  const Curve grip = run_prm("extensometer", base + "end\n");
  ASSERT_TRUE(grip.has("extensometer_elongation"));
  const double u = grip.si("displacement").back(), gauge = grip.si("extensometer_elongation").back();
  // Mean of the two gauges (20 mm and 2 mm long) on a bar 30 mm long: (20 + 2) / 2 / 30 of u.
  EXPECT_NEAR(gauge / (u * 11.0 / 30.0), 1.0, 1e-9);
  const Curve measured = run_prm("extensometer_curve", base + " set Curve displacement = extensometer\nend\n");
  EXPECT_NEAR(measured.si("displacement").back(), gauge, 1e-12);
  EXPECT_NEAR(measured.si("grip_displacement").back(), u, 1e-15);
  EXPECT_THROW(run_prm("extensometer_bad", base + " set Extensometer (mm) = 0 0 5, 0 0 5\nend\n"), InputError);
}

TEST(Input, BadEntryNamesTheFileAndLine) {
  const auto dir = scratch_dir("bad");
  const auto prm = dir / "bad.prm";
  std::ofstream(prm) << "subsection Geometry\n  set Diameter (mm) = abc\nend\n";
  RunOptions options;
  options.parameter_file = prm;
  options.output_directory = dir / "out";
  options.echo = false;
  try {
    run_experiment(options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.prm"), std::string::npos) << e.what();
    EXPECT_EQ(e.line(), 2) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "curve.csv"));
}

}  // namespace
}  // namespace dtwire::fem

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
