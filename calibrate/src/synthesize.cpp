#include "dtwire/calibrate/synthesize.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dtwire/calibrate/column_map.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {

Curve synthesize_target(const Experiment& experiment, const ParameterValues& values, double noise,
                        std::mt19937_64& generator, std::size_t points,
                        const std::vector<std::string>& also_written) {
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
  for (const auto& quantity : also_written)
    if (simulated.has(quantity) && !compared(quantity) &&
        std::find(quantities.begin(), quantities.end(), quantity) == quantities.end())
      quantities.push_back(quantity);
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

std::vector<std::filesystem::path> write_synthetic_targets(const FitDefinition& def, const std::filesystem::path& dir,
                                                           double noise, std::uint64_t seed, std::size_t points) {
  const ParameterValues values = to_values(def.parameters, reference_point(def.parameters));
  for (std::size_t e = 0; e < def.experiments.size(); ++e)
    for (std::size_t other = 0; other < e; ++other)
      if (def.experiment_target_names[e] == def.experiment_target_names[other])
        throw InputError(def.file.string(), "experiments '" + def.experiments[other].name + "' and '" +
                                                def.experiments[e].name + "' have the same target name " +
                                                def.experiment_target_names[e].string() + ": --synthesize would write it twice");
  std::mt19937_64 generator(seed);
  std::vector<std::filesystem::path> written;
  for (std::size_t e = 0; e < def.experiments.size(); ++e) {
    // Every mapped quantity is written, so that reading the target back finds its column.
    std::vector<std::string> mapped;
    for (const ColumnMapping& m : def.experiment_columns[e]) mapped.push_back(m.quantity);
    Curve out = synthesize_target(def.experiments[e], values, noise, generator, points, mapped);
    try {
      out = unmap_columns(out, def.experiment_columns[e]);
    } catch (const std::invalid_argument& error) {
      throw InputError(def.file.string(), "experiment '" + def.experiments[e].name + "': target_columns " + error.what());
    }
    out.set_metadata("source", "synthetic: dtwire fit --synthesize, simulator " + def.simulator + " law " +
                                   def.law + " at the reference parameter values of " +
                                   def.file.filename().string());
    out.set_metadata("noise", format_number(noise) + " x channel range (Gaussian, seed " + std::to_string(seed) + ")");
    const auto file = dir / def.experiment_target_names.at(e);
    std::filesystem::create_directories(file.parent_path());
    write_csv(out, file);
    written.push_back(file);
  }
  return written;
}

}  // namespace dtwire::calibrate
