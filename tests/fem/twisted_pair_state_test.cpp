// The twisted pair state's transfer onto a double twist (fem/src/twisted_pair_state.hpp), without
// a mesh: a pair whose deformed helix is the mesh's own helix turned by 20 deg about the twist
// axis (as a release turns it back) must hand every point of the mesh the state of the pair
// point at the same place in the turned frame, with its tensors turned back (b_mesh = R^T
// b_pair R), through the file's write and read; a pair twisted the other way is refused, and the
// .prm entries are checked by name.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include <fstream>

#include "dtwire/core/error.hpp"
#include "parameters.hpp"
#include "twisted_pair_state.hpp"

namespace {

using dealii::Point;
using dealii::Tensor;
using dtwire::AxisStation;
using dtwire::fem::TwistedPairPoint;
using dtwire::fem::TwistedPairState;

constexpr double R = 1.355e-3, H = 40e-3, kTurn = 20 * M_PI / 180;

double azimuth(unsigned wire, double z, double sense) { return sense * 3 * M_PI * z / H + wire * M_PI; }

// The mesh's axes: straight in from below and out above, the helix in between (0 <= z <= H).
std::vector<std::vector<AxisStation>> mesh_axes() {
  std::vector<std::vector<AxisStation>> axes(2);
  for (unsigned w = 0; w < 2; ++w)
    for (double z = -10e-3; z <= H + 10.0001e-3; z += 0.5e-3) {
      const double outside = z < 0 ? -z : (z > H ? z - H : 0.0);
      const double r = R + 0.5 * outside, a = azimuth(w, std::clamp(z, 0.0, H), 1.0);
      AxisStation s;
      s.wire = w;
      s.point = {{r * std::cos(a), r * std::sin(a), z}};
      s.tangent = {{0, 0, 1}};
      axes[w].push_back(s);
    }
  return axes;
}

Tensor<1, 3> turned(const Tensor<1, 3>& v, double angle) {
  return Tensor<1, 3>({std::cos(angle) * v[0] - std::sin(angle) * v[1], std::sin(angle) * v[0] + std::cos(angle) * v[1], v[2]});
}

// A state that differs from point to point and is not rotation invariant.
dtwire::fem::PlasticState state_of(unsigned id) {
  dtwire::fem::PlasticState s;
  s.plastic_metric_inverse[0][0] = 1.0 + 1e-3 * (id % 7);
  s.plastic_metric_inverse[0][1] = 2e-3 * std::sin(id);
  s.plastic_metric_inverse[1][2] = 1e-3 * std::cos(id);
  s.plastic_metric_inverse[2][2] = 1.0 - 1e-3 * (id % 5);
  s.backstress[0][0] = 1e6 * (id % 11);
  s.backstress[0][1] = -2e6 * (id % 3);
  s.equivalent_plastic_strain = 1e-3 * id;
  return s;
}

const std::vector<Tensor<1, 3>> kOffsets = {Tensor<1, 3>({0, 0, 0}), Tensor<1, 3>({0.9e-3, 0, 0}),
                                            Tensor<1, 3>({0, 0.9e-3, 0}), Tensor<1, 3>({-0.6e-3, -0.6e-3, 0})};

std::filesystem::path write_pair(double sense) {
  std::vector<TwistedPairPoint> points;
  unsigned id = 0;
  for (unsigned w = 0; w < 2; ++w)
    for (int k = 0; k <= 40; ++k) {
      const double z = 1e-3 * k, a = azimuth(w, z, sense) + kTurn;
      for (const auto& offset : kOffsets) {
        TwistedPairPoint p;
        p.wire = w;
        p.station_z_ref = z;
        p.axis = Point<3>(R * std::cos(a), R * std::sin(a), z);
        p.position = p.axis + turned(offset, kTurn);
        p.state = state_of(id++);
        Tensor<2, 3> rotation;  // the pair's tensors are the mesh's turned by kTurn
        rotation[0][0] = rotation[1][1] = std::cos(kTurn);
        rotation[1][0] = std::sin(kTurn);
        rotation[0][1] = -rotation[1][0];
        rotation[2][2] = 1;
        const auto turn = [&](const dtwire::fem::SymTensor2& t) {
          return dealii::symmetrize(Tensor<2, 3>(rotation * Tensor<2, 3>(t) * transpose(rotation)));
        };
        p.state.plastic_metric_inverse = turn(p.state.plastic_metric_inverse);
        p.state.backstress = turn(p.state.backstress);
        points.push_back(p);
      }
    }
  const auto file = std::filesystem::temp_directory_path() / "dtwire_twisted_pair_state_test.csv";
  dtwire::fem::write_twisted_pair_csv(file, 0.0, H, points);
  return file;
}

TEST(TwistedPairState, HandsEachPointTheStateOfItsPlaceInTheTurnedPair) {
  const TwistedPairState pair(write_pair(1.0), mesh_axes());
  EXPECT_NEAR(pair.twist_bottom(), 0.0, 1e-12);
  EXPECT_NEAR(pair.twist_top(), H, 1e-12);
  unsigned id = 0, checked = 0;
  for (unsigned w = 0; w < 2; ++w)
    for (int k = 0; k <= 40; ++k) {
      const double z = 1e-3 * k, a = azimuth(w, z, 1.0);
      const Point<3> foot(R * std::cos(a), R * std::sin(a), z);
      for (const auto& offset : kOffsets) {
        const auto expected = state_of(id++);
        const auto t = pair.at(w, foot + offset, foot);
        ASSERT_TRUE(t.inside);
        EXPECT_LT(t.distance, 1e-9) << "wire " << w << ", z = " << z;
        EXPECT_DOUBLE_EQ(t.state.equivalent_plastic_strain, expected.equivalent_plastic_strain);
        for (unsigned i = 0; i < 3; ++i)
          for (unsigned j = 0; j < 3; ++j) {
            EXPECT_NEAR(t.state.plastic_metric_inverse[i][j], expected.plastic_metric_inverse[i][j], 1e-10);
            EXPECT_NEAR(t.state.backstress[i][j], expected.backstress[i][j], 1e-3);  // Pa
          }
        ++checked;
      }
    }
  EXPECT_EQ(checked, 2u * 41u * kOffsets.size());
  // The arms keep their bending forming.
  EXPECT_FALSE(pair.at(0, Point<3>(3e-3, 0, -5e-3), Point<3>(3e-3, 0, -5e-3)).inside);
}

TEST(TwistedPairState, RefusesAPairTwistedTheOtherWay) {
  try {
    const TwistedPairState pair(write_pair(-1.0), mesh_axes());
    FAIL() << "a pair twisted the other way was accepted";
  } catch (const dtwire::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("twist sense"), std::string::npos) << e.what();
  }
}

// The message of the InputError `run` throws (empty if none).
template <class Run>
std::string refusal(Run run) {
  try {
    run();
  } catch (const dtwire::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TwistedPairState, EntriesAndFilesAreCheckedByName) {
  const std::filesystem::path tension = std::string(DTWIRE_SOURCE_DIR) + "/experiments/dt/dt_tension.prm";
  const auto read = [&](std::vector<std::string> settings) {
    return refusal([&] { dtwire::fem::read_parameters(tension, settings); });
  };
  const auto pair = write_pair(1.0).string();
  EXPECT_EQ(read({"As made/Forming history=true", "As made/Twisted pair state=" + pair}), "");
  std::string message = read({"As made/Twisted pair state=" + pair});
  EXPECT_NE(message.find("Twisted pair state"), std::string::npos) << message;
  EXPECT_NE(message.find("Forming history = true"), std::string::npos) << message;
  message = read({"As made/Forming history=true", "As made/Twisted pair state=/nonexistent/pair.csv"});
  EXPECT_NE(message.find("/nonexistent/pair.csv"), std::string::npos) << message;
  message = read({"As made/Forming history=true", "As made/Release after path=true"});
  EXPECT_NE(message.find("Release after path"), std::string::npos) << message;
  message = read({"As made/Release after path=true", "Boundary conditions/Top end=axial"});
  EXPECT_NE(message.find("Top end = clamped"), std::string::npos) << message;

  const auto garbage = std::filesystem::temp_directory_path() / "dtwire_twisted_pair_garbage.csv";
  std::ofstream(garbage) << "displacement_mm,force_N\n0,0\n1,1\n2,2\n";  // a curve, not a pair state
  message = refusal([&] { TwistedPairState(garbage, mesh_axes()); });
  EXPECT_NE(message.find(garbage.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not a twisted pair state"), std::string::npos) << message;
}

}  // namespace
