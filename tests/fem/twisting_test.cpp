// Twisting (issue 19): the end rotations a twisting machine imposes, checked against closed forms
// and the energy balance. Runs the dtwire executable's solver in process (run_experiment).
//
// 1. Plastic torsion of a wire (Nadai 1950, "Theory of flow and fracture of solids", ch. 33;
//    any plasticity text): a circular bar of radius a twisted by theta' per length has the shear
//    strain gamma = r theta' and carries T = 2 pi int_0^a tau(gamma(r)) r^2 dr. Von Mises with
//    linear hardening H (sigma = sigma_y + H alpha, alpha = gamma_p / sqrt(3)): tau = G gamma
//    below tau_y = sigma_y / sqrt(3), above it tau = (tau_y + H gamma / 3) / (1 + H / (3 G)).
//    A quarter turn over 40 mm: gamma_s = 16 gamma_y at the surface. The mesh's section is a
//    polygon of the circle's area (its torque differs by O(1 %)); the ends are held at their
//    length, so the second-order axial stress of finite torsion (Swift effect) takes a little of
//    the yield surface, and the strains are small-strain theory's. Tolerance 2 %; measured on the
//    level-0 mesh 0.17 %, on level 1 (8 x the cells, 10 x the time) 0.02 %: converged from level 0.
//    Then the grip lets go (As made/Release after path): unloading is elastic (the fully plastic
//    shaft's residual stress stays below yield, e.g. Chakrabarty, "Theory of plasticity", 3rd ed.,
//    sec. 3.6), so the end springs back by T L / (G J), J = pi a^4 / 2, the bottom grip rigid.
//    The top end's rotation is that of the whole top grip (its own elastic twist adds O(a / L))
//    and the section is a polygon: tolerance 2 % (measured 0.11 % on level 0, 0.6 % on level 1);
//    release energy balance < 1 % (0.12 %).
// 2. The straight DT pair twisted through three half turns (experiments/dt/dt_twisting.prm, the
//    machine's forming run), level 0: external work = elastic energy + plastic dissipation +
//    friction dissipation within 2 % (issue 19's bound; measured 0.087 %), the wires in contact
//    at the end, and wire A's axis wound about the twist axis: at mid-height by half the top's
//    540 deg (270 +- 10 deg; measured 270.4), a quarter of the way up by less than a quarter
//    (the clamps hold the wires straight where they leave them; measured 118 deg, 100-135).
//    Then released (the prm's As made/Release after path): energy balance < 2 % (measured
//    0.69 %), the top turns back (13 deg); its state carried into the DT mesh's twist (As
//    made/Twisted pair state) and settled there keeps the pair's plastic strain (section means,
//    3 %; measured 0.2 %) and residual stress (15 %; measured 4 %): the transfer loses neither.
#include <gtest/gtest.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/fem/run.hpp"
#include "scratch_run.hpp"

namespace {

using dtwire::fem::run_experiment;
using dtwire::fem::RunOptions;
using dtwire::fem::RunSummary;

std::filesystem::path scratch_dir(const std::string& name) {
  return dtwire::fem::testing::scratch_dir("dtwire_twisting_test_", name);
}

using dtwire::fem::testing::make_mesh;

TEST(Torsion, FullyPlasticTorqueOfAWire) {
  const auto dir = scratch_dir("torsion");
  const auto mesh = make_mesh("sw", dir, "--length 60 --grip-length 10 --level 0");
  ASSERT_FALSE(mesh.empty());
  constexpr double E = 200e9, nu = 0.3, sigma_y = 400e6, H = 2e9, a = 1.35e-3, free_length = 40e-3;
  const double tau_y = sigma_y / std::sqrt(3.0), G = E / (2 * (1 + nu));
  const double angle = M_PI / 2, gamma_s = a * angle / free_length, gamma_y = tau_y / G;
  ASSERT_GT(gamma_s / gamma_y, 15.0);
  std::ofstream(dir / "torsion.prm")
      << "subsection Geometry\n set Mesh file = sw.msh\n set Cross section = full\nend\n"
         "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
         " set Hardening law = linear\n set Yield stress (MPa) = 400\n set Hardening modulus (MPa) = 2000\nend\n"
         "subsection Boundary conditions\n set Bottom boundary ids = 4\n set Top boundary ids = 5\n"
         " set Load path (mm) = 0:0, 1:0\n set Rotation path (deg) = 0:0, 1:90\n set Rotation axis = 0 0 1\n"
         " set Rotation centre (mm) = 0 0 0\nend\n"
         "subsection Load stepping\n set Initial step = 0.1\n set Maximum step = 0.1\nend\n"
         "subsection Newton\n set Relative tolerance = 1e-8\nend\n"
         "subsection As made\n set Release after path = true\nend\n"
         "subsection Output\n set Fields = false\nend\n";
  RunOptions options;
  options.parameter_file = dir / "torsion.prm";
  options.output_directory = dir / "out";
  options.echo = false;
  const RunSummary s = run_experiment(options);
  const dtwire::Curve curve = dtwire::read_csv(s.curve_csv);
  const double torque = std::abs(curve.si("end_moment_z").back());
  const auto T_over_GJ = [&](double T) { return T * free_length / (G * M_PI * std::pow(a, 4) / 2); };
  double expected = 0.0;  // 2 pi int tau r^2 dr, midpoint rule
  const int rings = 100000;
  for (int k = 0; k < rings; ++k) {
    const double r = (k + 0.5) * a / rings, gamma = gamma_s * r / a;
    const double tau = gamma <= gamma_y ? G * gamma : (tau_y + H * gamma / 3) / (1 + H / (3 * G));
    expected += 2 * M_PI * tau * r * r * a / rings;
  }
  std::cout << "torque " << torque << " N m against " << expected << " N m (" << 100 * (torque / expected - 1)
            << " %)\n";
  EXPECT_NEAR(torque, expected, 0.02 * expected);

  const double springback = T_over_GJ(torque);
  ASSERT_TRUE(s.springback.done);
  std::cout << "released: turned " << s.springback.top_rotation_rad << " rad against " << -springback
            << " rad (" << 100 * (-s.springback.top_rotation_rad / springback - 1) << " %), energy balance "
            << 100 * s.springback.energy_balance << " %\n";
  EXPECT_NEAR(-s.springback.top_rotation_rad, springback, 0.02 * springback);
  EXPECT_LT(s.springback.energy_balance, 0.01);
}

TEST(Twisting, DoubleTwistPairEnergyBalanceAndHelix) {
  const auto dir = scratch_dir("pair");
  const auto mesh = make_mesh("dt", dir,
                              std::string("--prm ") + DTWIRE_SOURCE_DIR +
                                  "/experiments/default/dt_mesh.prm --half-turns 0 --arm-angle 0 --arm-length 10 --level 0");
  ASSERT_FALSE(mesh.empty());
  RunOptions options;
  options.parameter_file = std::string(DTWIRE_SOURCE_DIR) + "/experiments/dt/dt_twisting.prm";
  // Wire A's axis at mid-height and a quarter of the way up (reference positions, mm).
  options.settings = {"Geometry/Mesh file=" + mesh.string(), "Output/Fields=false",
                      "Output/Probe points (mm)=1.355 0 20; 1.355 0 10"};
  options.output_directory = dir / "out";
  options.echo = false;
  const RunSummary s = run_experiment(options);
  const dtwire::Curve curve = dtwire::read_csv(s.curve_csv);
  const double work = curve.si("external_work").back();
  const double error = curve.si("energy_balance_error").back();
  std::cout << "external work " << work << " J, balance error " << error << " J (" << 100 * error / work << " %)\n";
  EXPECT_LT(std::abs(error), 0.02 * work);
  EXPECT_GT(curve.si("wire_contact_normal_force").back(), 0.0);
  const auto turned = [&](int probe, double near) {
    const double x = 1.355e-3 + curve.si("probe" + std::to_string(probe) + "_displacement_x").back();
    const double y = curve.si("probe" + std::to_string(probe) + "_displacement_y").back();
    double angle = std::atan2(y, x) * 180 / M_PI;
    while (angle < near - 180) angle += 360;
    std::cout << "probe " << probe << ": turned " << angle << " deg about the twist axis, radius "
              << std::hypot(x, y) * 1e3 << " mm\n";
    EXPECT_NEAR(std::hypot(x, y), 1.355e-3, 0.15e-3) << "probe " << probe << " left the helix radius";
    return angle;
  };
  EXPECT_NEAR(turned(1, 270.0), 270.0, 10.0);
  const double quarter = turned(2, 135.0);
  EXPECT_GT(quarter, 100.0);
  EXPECT_LT(quarter, 135.0);

  // The release: the top grips let go and the twist turns back, the energy balanced.
  ASSERT_TRUE(s.springback.done);
  std::cout << "released: turned back " << s.springback.top_rotation_rad * 180 / M_PI << " deg, energy balance "
            << 100 * s.springback.energy_balance << " %, clearance mean " << s.springback.clearance_mean_mm << " mm\n";
  EXPECT_LT(s.springback.energy_balance, 0.02);
  EXPECT_LT(s.springback.top_rotation_rad, -1 * M_PI / 180);
  EXPECT_GT(s.springback.top_rotation_rad, -45 * M_PI / 180);
  const auto state = dir / "out" / "twisted_pair_state.csv";
  ASSERT_TRUE(std::filesystem::exists(state));

  // Carried into the double twist: after the DT's own settling, the twist holds the plastic
  // strain and residual stress the pair was left with (section means over the twist, clear of
  // its ends), the arms their bending forming.
  RunOptions dt;
  dt.parameter_file = std::string(DTWIRE_SOURCE_DIR) + "/experiments/dt/dt_tension.prm";
  dt.settings = {"As made/Forming history=true", "As made/Twisted pair state=" + state.string(),
                 "Output/Fields=false", "Boundary conditions/Load path (mm)=0:0, 1:1"};
  dt.output_directory = dir / "dt";
  dt.echo = false;
  const RunSummary d = run_experiment(dt);
  ASSERT_TRUE(d.springback.done);
  EXPECT_LT(d.springback.energy_balance, 0.02);
  const auto twist_mean = [](const std::filesystem::path& file, const char* column) {
    const dtwire::Curve c = dtwire::read_csv(file);
    const auto z = c.si("z"), v = c.si(column);
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < z.size(); ++i)
      if (z[i] > 2e-3 && z[i] < 38e-3) sum += v[i], ++n;
    return n > 0 ? sum / n : 0.0;
  };
  const auto pair_profile = dir / "out" / "as_made.csv", dt_profile = dir / "dt" / "as_made.csv";
  const double ep_pair = twist_mean(pair_profile, "plastic_strain_mean"), ep_dt = twist_mean(dt_profile, "plastic_strain_mean");
  const double vm_pair = twist_mean(pair_profile, "von_mises_mean"), vm_dt = twist_mean(dt_profile, "von_mises_mean");
  std::cout << "twist: plastic strain " << ep_dt << " (pair " << ep_pair << "), residual von Mises " << vm_dt * 1e-6
            << " MPa (pair " << vm_pair * 1e-6 << " MPa)\n";
  EXPECT_GT(ep_pair, 0.05);  // three half turns take the wires far past yield
  EXPECT_NEAR(ep_dt, ep_pair, 0.03 * ep_pair);
  EXPECT_NEAR(vm_dt, vm_pair, 0.15 * vm_pair);
  const dtwire::Results results = dtwire::read_results(d.results_h5);
  double mapped = 0.0, distance = 1.0;
  for (const auto& p : results.parameters) {
    if (p.name == "twisted_pair_points") mapped = p.value;
    if (p.name == "twisted_pair_largest_distance") distance = p.value;
  }
  EXPECT_GT(mapped, 1000.0);
  EXPECT_LT(distance, 1.35e-3) << "a twist point took the state of a pair point more than a wire radius away";
}

}  // namespace

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
