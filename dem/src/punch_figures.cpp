#include "dtwire/dem/punch_figures.hpp"

#include <stdexcept>

namespace dtwire::dem {

PunchFigures punch_figures(const std::vector<double>& x, const std::vector<double>& f, double onset_force, double probe) {
  if (x.size() != f.size()) throw std::invalid_argument("punch_figures: displacement and force columns differ in length");
  PunchFigures out;
  for (std::size_t r = 0; r < f.size(); ++r) {
    if (f[r] > out.peak_force) {
      out.peak_force = f[r];
      out.displacement_at_peak = x[r];
    }
    if (out.onset < 0.0 && f[r] >= onset_force) {
      const bool bracketed = r > 0 && f[r] > f[r - 1];
      out.onset = bracketed ? x[r - 1] + (onset_force - f[r - 1]) / (f[r] - f[r - 1]) * (x[r] - x[r - 1]) : x[r];
    }
    if (r > 0 && x[r - 1] <= probe && x[r] >= probe && x[r] > x[r - 1])
      out.force_at_probe = f[r - 1] + (probe - x[r - 1]) / (x[r] - x[r - 1]) * (f[r] - f[r - 1]);
  }
  return out;
}

}  // namespace dtwire::dem
