#include "dtwire/calibrate/synthesize.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtwire::calibrate {

Curve synthesize_target(const Experiment& experiment, const ParameterValues& values, double noise,
                        std::mt19937_64& generator, std::size_t points) {
  if (points < 3) throw std::invalid_argument("synthesize_target: points must be >= 3");
  const auto gaussian = [&] {
    const double u1 = (static_cast<double>(generator() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(generator() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  };
  const Curve simulated = experiment.simulator->simulate(values);
  const std::size_t stride = std::max<std::size_t>(1, (simulated.size() + points - 2) / (points - 1));
  const auto compared = [&](const std::string& quantity) {
    return std::any_of(experiment.channels.begin(), experiment.channels.end(),
                       [&](const ChannelWeight& c) { return c.quantity == quantity; });
  };
  std::vector<std::string> quantities{experiment.abscissa};
  for (const char* path_channel : {"displacement", "rotation", "strain"})
    if (simulated.has(path_channel) && path_channel != experiment.abscissa && !compared(path_channel))
      quantities.push_back(path_channel);
  for (const auto& c : experiment.channels) quantities.push_back(c.quantity);
  Curve out;
  for (const auto& quantity : quantities) {
    const Channel& channel = simulated.channel(quantity);
    std::vector<double> v;
    for (std::size_t i = 0; i < simulated.size(); i += stride) v.push_back(channel.values[i]);
    if ((simulated.size() - 1) % stride) v.push_back(channel.values.back());
    if (compared(quantity) && noise > 0) {
      const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
      const double sigma = noise * (*hi - *lo);
      for (double& x : v) x += sigma * gaussian();
    }
    if (channel.unit.dimension == Dimension::Length) {
      const Unit mm = *find_unit("mm");
      for (double& x : v) x /= mm.to_si / channel.unit.to_si;
      out.add_channel(quantity, mm, v);
    } else {
      out.add_channel(quantity, channel.unit, v);
    }
  }
  return out;
}

}  // namespace dtwire::calibrate
