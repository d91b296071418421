// The channels a simulator declares (used to check fit files when they are read) are the
// channels it returns, with the same dimensions.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "dtwire/calibrate/law_replay.hpp"
#include "dtwire/calibrate/voce_bar.hpp"

namespace dtwire::calibrate {
namespace {

void expect_declared_channels(const Simulator& simulator, const ParameterValues& values) {
  const Curve curve = simulator.simulate(values);
  const auto declared = simulator.channels();
  ASSERT_EQ(declared.size(), curve.channels().size());
  for (std::size_t i = 0; i < declared.size(); ++i) {
    EXPECT_EQ(declared[i].first, curve.channels()[i].quantity);
    EXPECT_EQ(declared[i].second, curve.channels()[i].unit.dimension) << declared[i].first;
  }
}

TEST(SimulatorChannels, LawReplayDeclaresWhatItReturns) {
  std::ifstream in(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/data/macroelement_thesis_params.json");
  const auto root = nlohmann::json::parse(in);
  dem::ParameterMap fixed;
  for (const auto& [name, value] : root["single_wire"].items())
    if (value.is_number()) fixed[name] = value.get<double>();
  LoadPath path;
  path.displacement_m = {0.0, 1e-3};
  path.rotation_rad = {0.0, 0.1};
  path.increments_per_leg = 10;
  expect_declared_channels(LawReplaySimulator("thesis", fixed, path), {});
}

TEST(SimulatorChannels, VoceBarDeclaresWhatItReturns) {
  expect_declared_channels(VoceBarSimulator({0.0, 0.01}, 10),
                           {{"E_Pa", 200e9}, {"sigma_y0_Pa", 300e6}, {"Q_Pa", 100e6}, {"b_1", 20.0}});
}

}  // namespace
}  // namespace dtwire::calibrate
