// Fit (3) compares FE curves with the macro-element's two-node driver through the column
// mapping of experiments/sw_fe_fit/macro_fit.toml. Checked here on the elastic wire, with the
// mesh and end conditions of experiments/sw_fe_fit/bending.prm (the half model bent about its
// chord) and a small end rotation theta = 1 deg, alone and with an elongation u = 0.01 mm:
// the mapped rotation is theta, the mapped moment EI theta / L (pure bending, the
// macro-element's k_EI) with the law's sign, the mapped force E A u / L, and the chord
// compensation keeps the force of pure bending far below the E A theta^2 / 24 of a held chord.
// Under the tension N the FE moment is the beam-column's, EI theta / L x (k L/2) / tanh(k L/2)
// with k^2 = N / (EI) (end moments with the ends on the chord; Timoshenko & Gere 1961, ch. 1):
// a coupling the macro-element's constant k_EI does not have (its moment stays EI theta / L).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "dtwire/calibrate/column_map.hpp"
#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/law_replay.hpp"
#include "dtwire/core/csv.hpp"

namespace dtwire::calibrate {
namespace {

const std::filesystem::path kFolder = std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/sw_fe_fit";
constexpr double kE = 130e9, kD = 2.7e-3, kL = 0.06;
const double kArea = M_PI * kD * kD / 4, kInertia = M_PI * std::pow(kD, 4) / 64;
const double kTheta = M_PI / 180.0;

// bending.prm with an elastic material and a two-step path to (u, theta) (two steps: in small
// elastic steps Newton stalls near a relative residual of 1e-9, above the 1e-10 tolerance).
std::string elastic_bending_prm(double u_mm) {
  std::ifstream in(kFolder / "bending.prm");
  std::ostringstream out;
  std::string line;
  const double half_chord = 0.5 * ((60.0 + u_mm) * std::sin(kTheta / 2) / (kTheta / 2) - 60.0);
  while (std::getline(in, line)) {
    if (line.rfind('#', 0) == 0 || line.find("Hardening table") != std::string::npos) continue;
    if (line.find("Hardening law") != std::string::npos)
      line = "  set Hardening law = linear\n  set Yield stress (MPa) = 1e6\n  set Hardening modulus (MPa) = 0";
    else if (line.find("Load path (mm)") != std::string::npos)
      line = "  set Load path (mm) = 0:0, 1:" + format_number(half_chord);
    else if (line.find("Rotation path (deg)") != std::string::npos)
      line = "  set Rotation path (deg) = 0:0, 1:0.5";
    else if (line.find("Initial step") != std::string::npos || line.find("Maximum step") != std::string::npos)
      line = line.substr(0, line.find('=')) + "= 0.5";
    out << line << "\n";
  }
  return out.str();
}

// The last row of the FE run, read through the bending experiment's target_columns.
Curve mapped_fe_curve(double u_mm, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_fe_mapping_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bend.prm") << elastic_bending_prm(u_mm);
  const std::string command = std::string("DEAL_II_NUM_THREADS=1 ") + DTWIRE_EXECUTABLE_PATH + " run " +
                              (dir / "bend.prm").string() + " --out " + (dir / "out").string() + " -q";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  FitReadOptions options;
  options.read_targets = false;
  const FitDefinition def = read_fit_file(kFolder / "macro_fit.toml", options);
  for (std::size_t e = 0; e < def.experiments.size(); ++e)
    if (def.experiments[e].name == "bending") {
      const Curve curve = map_columns(read_csv(dir / "out/curve.csv"), def.experiment_columns[e]);
      std::filesystem::remove_all(dir);
      return curve;
    }
  ADD_FAILURE() << "no experiment 'bending'";
  return {};
}

// The thesis law, elastic, with k_EA = E A / L and k_EI = E I / L (per degree), on the same path.
Curve law_curve(double u_m) {
  dem::ParameterMap p{{"D_m", kD}, {"EA_N", kE * kArea / kL}, {"EI_Nm2_per_deg_convention", kE * kInertia / kL * M_PI / 180},
                      {"N0_N", 1e6}, {"Nult_N", 2e6}, {"Nc_N", 1e6}, {"m_f", 0.0285}, {"beta_f", 0.195},
                      {"k_F", 1.0}, {"k_M", 1.0}, {"m_g", 4.78}, {"alpha_g", 0.5}, {"beta_g", 0.0358},
                      {"W1_J", 1e9}, {"W2_J", 2e9}, {"alpha_d", 2.7}, {"slide_a", 0.0}, {"slide_b", 0.0}};
  LoadPath path;
  path.displacement_m = {0.0, u_m};
  path.rotation_rad = {0.0, kTheta};
  path.increments_per_leg = 10;
  return LawReplaySimulator("thesis", p, path).simulate({});
}

// Tolerance 1 %: the 8-gon section (I within 0.23 %), 60 Q1 cells along the half (bending
// stiffness +0.6 % from shear locking) and the clamped end faces (no lateral contraction).
TEST(FeMapping, ElasticPureBendingMatchesEiOverLAndTheLawsSign) {
  const Curve fe = mapped_fe_curve(0.0, "bending");
  const Curve law = law_curve(0.0);
  const double moment = fe.si("moment").back();
  EXPECT_NEAR(fe.si("rotation").back(), kTheta, 1e-12);
  EXPECT_NEAR(moment / (kE * kInertia / kL * kTheta), 1.0, 0.01) << moment;
  EXPECT_NEAR(moment / law.si("moment").back(), 1.0, 0.01);  // same sign as the law's M_y
  const double held_chord_force = kE * kArea * kTheta * kTheta / 24;
  EXPECT_LT(std::abs(fe.si("force").back()), 0.01 * held_chord_force) << fe.si("force").back();
  std::cout << "elastic pure bending: M / (EI theta / L) - 1 = " << moment / (kE * kInertia / kL * kTheta) - 1
            << ", N = " << fe.si("force").back() << " N (held chord: " << held_chord_force << " N)\n";
}

TEST(FeMapping, ElasticStretchAndBendingMatchEaOverLAndTheBeamColumn) {
  const double u = 1e-5;  // 0.01 mm, elastic
  const Curve fe = mapped_fe_curve(u * 1e3, "stretch");
  const Curve law = law_curve(u);
  EXPECT_NEAR(fe.si("force").back() / (kE * kArea / kL * u), 1.0, 0.01) << fe.si("force").back();
  EXPECT_NEAR(fe.si("force").back() / law.si("force").back(), 1.0, 0.01);
  const double half_kl = 0.5 * kL * std::sqrt(fe.si("force").back() / (kE * kInertia));
  const double beam_column = kE * kInertia / kL * kTheta * half_kl / std::tanh(half_kl);
  EXPECT_NEAR(fe.si("moment").back() / beam_column, 1.0, 0.01);
  EXPECT_NEAR(law.si("moment").back() / (kE * kInertia / kL * kTheta), 1.0, 1e-9);
  std::cout << "elastic stretch and bending: N / (EA u / L) - 1 = " << fe.si("force").back() / (kE * kArea / kL * u) - 1
            << ", M / (EI theta / L) - 1 = " << fe.si("moment").back() / (kE * kInertia / kL * kTheta) - 1
            << ", M / beam-column - 1 = " << fe.si("moment").back() / beam_column - 1 << "\n";
}

}  // namespace
}  // namespace dtwire::calibrate
