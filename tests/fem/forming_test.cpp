// The double twist as made (issue 19): the forming path of one fibre against the uniaxial closed
// form, the axis file's fibre strains, bad axis files, and through the solver the springback of
// a bent wire against beam theory (elastic and plastic forming) and the energy balance of the DT's springback.
// Runs in-process; MPI is initialised once in main().
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "dtwire/core/error.hpp"
#include "dtwire/fem/run.hpp"
#include "scratch_run.hpp"
#include "forming_history.hpp"

namespace {

using namespace dtwire::fem;
using dealii::Point;
using dealii::Tensor;

constexpr double kE = 200e9, kNu = 0.3, kYield = 400e6, kHardening = 2e9;

J2LogPlasticity linear_material(double hardening) {
  HardeningParameters h;
  h.law = HardeningLaw::linear;
  h.yield_stress = kYield;
  h.linear_modulus = hardening;
  return J2LogPlasticity(ElasticParameters{kE, kNu}, IsotropicHardening(h));
}

Tensor<1, 3> unit(double x, double y, double z) {
  Tensor<1, 3> t;
  t[0] = x, t[1] = y, t[2] = z;
  return t / t.norm();
}

// Held in its formed shape (F = I), the fibre carries the uniaxial stress of its path along the
// tangent: elastic E eps below yield; above it sigma = sigma_0 + H alpha with the log strain
// split eps = sigma / E + alpha, i.e. sigma = (sigma_0 + H |eps|) / (1 + H / E); no lateral stress.
TEST(FormingHistory, FibreCarriesTheUniaxialStressOfItsPath) {
  const auto material = linear_material(kHardening);
  const Tensor<1, 3> t = unit(1, 2, 3);
  for (const double strain : {0.5 * kYield / kE, -0.5 * kYield / kE, 0.05, -0.05, 0.2}) {
    const PlasticState state = formed_state(material, t, strain, 20);
    const auto held = material.update(dealii::unit_symmetric_tensor<3>(), state, false);
    const double elastic_limit = kYield / kE;
    const double expected = std::abs(strain) <= elastic_limit
                                ? kE * strain
                                : std::copysign((kYield + kHardening * std::abs(strain)) / (1.0 + kHardening / kE), strain);
    const double axial = t * (held.kirchhoff * t);
    EXPECT_NEAR(axial, expected, 1e-6 * std::abs(expected)) << "strain " << strain;
    const Tensor<1, 3> lateral = unit(2, -1, 0);  // normal to t
    EXPECT_NEAR(lateral * (held.kirchhoff * lateral), 0.0, 1e-6 * std::abs(expected)) << "strain " << strain;
    const double alpha = std::abs(strain) <= elastic_limit ? 0.0 : std::abs(strain) - std::abs(expected) / kE;
    EXPECT_NEAR(state.equivalent_plastic_strain, alpha, 1e-8) << "strain " << strain;
    EXPECT_NEAR(held.plastic_increment, 0.0, 1e-12);  // held, it does not yield again
  }
}

std::filesystem::path scratch_dir(const std::string& name) {
  return dtwire::fem::testing::scratch_dir("dtwire_forming_test_", name);
}

// An axis along z with curvature vector (kappa, 0, 0) 1/mm at every station, wire 0 only.
void write_axis(const std::filesystem::path& file, double kappa_per_mm, double length_mm) {
  std::ofstream out(file);
  out << "wire,arc_length_mm,x_mm,y_mm,z_mm,tangent_x,tangent_y,tangent_z,curvature_x_per_mm,curvature_y_per_mm,"
         "curvature_z_per_mm\n";
  for (int k = 0; k <= 30; ++k) {
    const double z = length_mm * k / 30.0;
    out << "0," << z << ",0,0," << z << ",0,0,1," << kappa_per_mm << ",0,0\n";
  }
}

// A point at offset y from the axis gets the fibre strain ln(1 - kappa . y) (SI inside).
TEST(FormingHistory, AxisFileGivesTheFibreStrain) {
  const auto dir = scratch_dir("axis");
  write_axis(dir / "a.axis.csv", 0.1, 60.0);
  const WireAxes axes(dtwire::read_axis_csv(dir / "a.axis.csv"));
  ASSERT_EQ(axes.wires(), 1u);
  const auto at = axes.locate(0, Point<3>(1.0e-3, 0.3e-3, 17.3e-3));
  EXPECT_NEAR(at.bending_strain, std::log(1.0 - 0.1 * 1.0), 1e-12);
  EXPECT_NEAR(at.arc_length, 17.3e-3, 1e-12);
  EXPECT_NEAR(at.tangent[2], 1.0, 1e-12);
}

TEST(FormingHistory, BadAxisFileIsNamedWithItsLine) {
  const auto dir = scratch_dir("bad");
  std::ofstream(dir / "bad.axis.csv") << "wire,arc_length_mm,x_mm,y_mm,z_mm,tangent_x,tangent_y,tangent_z,"
                                         "curvature_x_per_mm,curvature_y_per_mm,curvature_z_per_mm\n"
                                         "0,0,0,0,0,0,0,1,0,0,0\n0,1,0,0,1,0,0,one,0,0,0\n";
  try {
    dtwire::read_axis_csv(dir / "bad.axis.csv");
    FAIL() << "accepted a bad row";
  } catch (const dtwire::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.axis.csv:3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(dtwire::read_axis_csv(dir / "missing.axis.csv"), dtwire::InputError);
}

using dtwire::fem::testing::make_mesh;

// Springback of a bent wire: bent to a uniform curvature kappa and released as a cantilever, a
// wire loses the curvature M / (E I), M the moment of the forming stress sigma(y) = clamp(E ln(1 -
// kappa y), -sigma_y, sigma_y) over the circle (beam theory of springback; e.g. Timoshenko,
// "Strength of Materials" II, ch. on plastic bending). Elastic forming (kappa below the yield
// curvature) loses all of it. The test mesh is straight and is taken as the formed shape, so
// the released wire bends by -M / (E I) from it. Tip deflection (1 - cos(dk L)) / dk over the
// free length L = 50 mm. Level 1 within 7 % (measured -6.2 % elastic, -6.0 % plastic; mesh
// convergence in docs/fem_dt.md: level 0 / 1 / 2 = -22 / -6.2 / -1.1 % elastic).
class BentWire : public ::testing::TestWithParam<double> {};

TEST_P(BentWire, SpringbackIsTheBeamTheoryCurvature) {
  const double over_yield = GetParam();
  const auto dir = scratch_dir("cantilever_" + std::to_string(static_cast<int>(10 * over_yield)));
  const auto mesh = make_mesh("sw", dir, "--length 60 --grip-length 10 --level 1");
  ASSERT_FALSE(mesh.empty());
  const double R = 1.35e-3, kappa = over_yield * (kYield / kE) / R;
  write_axis(dir / "curved.axis.csv", kappa * 1e-3, 60.0);
  std::ofstream(dir / "springback.prm")
      << "subsection Geometry\n set Mesh file = sw.msh\n set Cross section = full\nend\n"
         "subsection Material\n set Young modulus (MPa) = 200000\n set Poisson ratio = 0.3\n"
         " set Hardening law = linear\n set Yield stress (MPa) = 400\n set Hardening modulus (MPa) = 0\nend\n"
         "subsection As made\n set Forming history = true\n set Axis file = curved.axis.csv\nend\n"
         "subsection Boundary conditions\n set Bottom boundary ids = 4\n set Top boundary ids = 5\n"
         " set Load path (mm) = 0:0, 1:0.0001\nend\n"
         "subsection Load stepping\n set Initial step = 0.5\n set Maximum step = 0.5\nend\n"
         "subsection Output\n set Fields = false\nend\n";
  RunOptions options;
  options.parameter_file = dir / "springback.prm";
  options.output_directory = dir / "out";
  options.echo = false;
  const RunSummary s = run_experiment(options);
  ASSERT_TRUE(s.springback.done);
  double moment = 0.0;
  const int strips = 200000;
  for (int k = 0; k < strips; ++k) {
    const double y = -R + (k + 0.5) * 2.0 * R / strips;
    const double sigma = std::clamp(kE * std::log(1.0 - kappa * y), -kYield, kYield);
    moment -= sigma * y * 2.0 * std::sqrt(R * R - y * y) * 2.0 * R / strips;
  }
  const double inertia = M_PI * std::pow(R, 4) / 4.0, L = 50e-3;
  const double lost = moment / (kE * inertia);
  if (over_yield < 1.0) {
    EXPECT_NEAR(lost, kappa, 1e-4 * kappa);  // elastic: all of it
  }
  const double deflection_mm = 1e3 * (1.0 - std::cos(lost * L)) / lost;
  EXPECT_NEAR(s.springback.largest_displacement_mm, deflection_mm, 0.07 * deflection_mm);
  EXPECT_LT(s.springback.energy_balance, 0.005);
}

INSTANTIATE_TEST_SUITE_P(ElasticAndPlastic, BentWire, ::testing::Values(0.5, 3.0));

// The default DT (level 0) as made: the springback closes its energy balance within 2 % (issue
// 19's bound; measured 0.04 %).
TEST(FormingSpringback, DoubleTwistEnergyBalance) {
  const auto dir = scratch_dir("dt");
  const auto mesh = make_mesh("dt", dir, std::string("--prm ") + DTWIRE_SOURCE_DIR + "/experiments/default/dt_mesh.prm --level 0");
  ASSERT_FALSE(mesh.empty());
  RunOptions options;
  options.parameter_file = std::string(DTWIRE_SOURCE_DIR) + "/experiments/dt/dt_tension.prm";
  options.settings = {"Geometry/Mesh file=" + mesh.string(), "As made/Forming history=true", "Output/Fields=false",
                      "Boundary conditions/Load path (mm)=0:0, 1:0.01", "Load stepping/Initial step=0.5",
                      "Load stepping/Maximum step=0.5", "Material/Stop at failure=false"};
  options.output_directory = dir / "out";
  options.echo = false;
  const RunSummary s = run_experiment(options);
  ASSERT_TRUE(s.springback.done);
  EXPECT_LT(s.springback.energy_balance, 0.02);
  EXPECT_GT(s.springback.largest_displacement_mm, 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "as_made.csv"));
}

}  // namespace

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
