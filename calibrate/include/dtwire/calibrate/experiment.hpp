#pragma once
// One experiment of a fit: a target curve, the simulator that should reproduce it, and how the
// two are compared. Residuals are taken at the target's points on a common abscissa (a channel
// such as displacement, or the normalised arc length), branch by branch so that loading and
// unloading are compared with their own counterpart.
#include <memory>
#include <string>
#include <vector>

#include "dtwire/calibrate/simulator.hpp"
#include "dtwire/core/curve.hpp"

namespace dtwire::calibrate {

enum class AbscissaKind { Channel, NormalizedArcLength };

struct ChannelWeight {
  std::string quantity;  // e.g. "force"
  double weight = 1.0;
  double scale = 0.0;  // SI; residuals are divided by it. 0: the target channel's range
};

// The target's peak of a channel compared as one residual row of its own: for a target that
// ends where the specimen breaks (a crack that no static state follows, a laboratory failure),
// its strength is the figure the curve's points alone leave open, because the simulation may
// go on rising past the target's last point. The simulated peak is taken over the whole
// simulated path, which should run past the target's end, so a set that is stronger after the
// target broke pays for it.
// Its weight 1 weighs the row as much as the channel's whole curve; scale 0: the channel's range.
using PeakWeight = ChannelWeight;

struct Experiment {
  std::string name;
  std::shared_ptr<const Simulator> simulator;
  Curve target;
  std::string abscissa = "displacement";  // quantity present in target and simulated curves
  AbscissaKind kind = AbscissaKind::Channel;
  std::vector<ChannelWeight> channels;
  std::vector<PeakWeight> peaks;
  double weight = 1.0;
  // A reversal of the abscissa counts as a new branch once it exceeds this fraction of the
  // abscissa range (noise in laboratory curves must not create branches).
  double branch_tolerance = 1e-3;
};

// Throws std::invalid_argument naming the experiment if the target lacks a channel, has a
// non-positive weight or cannot be split into branches.
void validate(const Experiment& experiment);

// Number of residuals the experiment contributes (one per target point and channel, one per peak).
std::size_t residual_count(const Experiment& experiment);

// Whether `quantity` is one of the channels compared point by point.
bool compares_channel(const Experiment& experiment, const std::string& quantity);

// Sizes of the consecutive residual groups with a variance of their own (lsq::Problem): one per
// channel, its peak rows with it; one for the peaks of channels not compared point by point.
std::vector<std::size_t> residual_groups(const Experiment& experiment);

// Residuals sqrt(w_exp w_ch / n_ch) (simulated - target) / scale_ch, in the order channel by
// channel, point by point, each channel followed by its peak rows, sqrt(w_exp w_peak)
// (simulated peak - target peak) / scale, a peak being the value of largest magnitude (signed);
// then the peaks of channels not compared point by point. Throws ComputationError if the
// simulated curve cannot be compared (missing channel, different number of branches, too few
// points).
std::vector<double> residuals(const Experiment& experiment, const Curve& simulated);

// The simulated channels at the target's points (same abscissa), for plots and fit quality:
// a curve with the target's abscissa channel and the compared channels, in the target's units.
Curve simulated_at_target(const Experiment& experiment, const Curve& simulated);

struct ChannelQuality {
  std::string experiment;
  std::string quantity;
  std::string unit;       // unit of rmse (the target column's unit)
  std::size_t points = 0;
  double rmse = 0.0;
  double nrmse = 0.0;     // rmse / range of the target channel
  double r_squared = 0.0;
};

std::vector<ChannelQuality> fit_quality(const Experiment& experiment, const Curve& simulated);

struct PeakQuality {
  std::string experiment;
  std::string quantity;
  std::string unit;  // of the two peaks (the target column's unit)
  double target = 0.0;
  double simulated = 0.0;  // over the whole simulated path
  double target_abscissa = 0.0;     // where each peak is, in the abscissa's target unit
  double simulated_abscissa = 0.0;
};

std::vector<PeakQuality> peak_quality(const Experiment& experiment, const Curve& simulated);

}  // namespace dtwire::calibrate
