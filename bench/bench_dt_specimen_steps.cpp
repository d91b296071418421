// Timed program (not a test): the dem_specimen simulator of experiments/dt_fe_fit/dt_specimen_fit.toml
// at three parameter points (the published sets, the file's start, the FE fit's best), with the
// file's quasi-static settings and with variants of them: explicit steps, CPU milliseconds per run
// (this thread's clock), the sum of the fitted channels and the largest difference of each fitted channel from the baseline
// setting's, as a fraction of the channel's range (the fit's residual unit). Issue 52.
// usage: bench_dt_specimen_steps [move_steps:tolerance ...]   (first pair = the baseline)
#include <ctime>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "dtwire/calibrate/dem_specimen.hpp"
#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/parameter.hpp"

using namespace dtwire::calibrate;

namespace {
double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * t.tv_sec + 1e-6 * t.tv_nsec;
}
}  // namespace

int main(int argc, char** argv) {
  FitReadOptions read;
  read.read_targets = false;
  const FitDefinition def =
      read_fit_file(std::string(DTWIRE_SOURCE_DIR) + "/experiments/dt_fe_fit/dt_specimen_fit.toml", read);
  std::vector<std::pair<int, double>> settings;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    const auto colon = s.find(':');
    settings.emplace_back(std::atoi(s.substr(0, colon).c_str()), std::atof(s.substr(colon + 1).c_str()));
  }
  if (settings.empty()) settings = {{200, 1e-6}, {100, 1e-6}, {50, 1e-6}, {200, 1e-5}, {200, 1e-4}, {50, 1e-4}};
  // Points in the file's own parameter coordinates (Nult as the reserve over N0).
  std::vector<std::pair<std::string, std::vector<double>>> points;
  points.emplace_back("published", reference_point(def.parameters));
  std::vector<double> start;
  for (const auto& p : def.parameters) start.push_back(p.initial);
  points.emplace_back("start", start);
  // The 32-start FE fit's best (2026-11-29, docs/validation.md).
  points.emplace_back("fe_best", std::vector<double>{2.96903e6, 3649.93, 2450.39, 230.308, 1.32443e6, 350.926, 2808.48, 20});
  std::cout << "point experiment move_steps tolerance steps cpu_ms max_dev_per_range(channels)\n";
  for (const auto& [label, point] : points) {
    const ParameterValues values = to_values(def.parameters, point);
    for (const Experiment& e : def.experiments) {
      const auto* sim = dynamic_cast<const DemSpecimenSimulator*>(e.simulator.get());
      if (sim == nullptr) return 2;
      std::vector<dtwire::Curve> curves;
      for (const auto& [move, tolerance] : settings) {
        QuasiStaticOptions q = sim->options();
        q.move_steps = move;
        q.tolerance = tolerance;
        DemSpecimenSimulator variant(sim->law(), def.fixed, sim->geometry(), q, sim->path());
        SpecimenRunInfo info;
        const double t0 = cpu_ms();
        curves.push_back(variant.simulate(values, info));
        const double ms = cpu_ms() - t0;
        std::cout << label << " " << e.name << " " << move << " " << tolerance << " " << info.steps << " "
                  << std::setprecision(4) << ms;
        for (const char* channel : {"force", "shear_force", "dt_elongation"}) {
          const std::vector<double> base = curves.front().si(channel), now = curves.back().si(channel);
          double lo = 1e300, hi = -1e300, dev = 0.0;
          for (std::size_t i = 0; i < base.size(); ++i) {
            lo = std::min(lo, base[i]);
            hi = std::max(hi, base[i]);
            dev = std::max(dev, std::abs(now[i] - base[i]));
          }
          std::cout << " " << channel << "=" << std::setprecision(3) << (hi > lo ? dev / (hi - lo) : 0.0);
        }
        // Every fitted channel's sum to the last digit: two builds of the same setting compare bit for bit.
        double sum = 0.0;
        for (const char* channel : {"force", "shear_force", "dt_elongation"})
          for (double x : curves.back().si(channel)) sum += x;
        std::cout << " sum=" << std::setprecision(17) << sum << "\n" << std::flush;
      }
    }
  }
}
