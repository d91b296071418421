#pragma once
// The selfcheck's second family of laboratory effects: each catalogue effect produced by
// physical forms other than the augmentation `dtwire gap` fits (docs/gap.md, "Independent
// family"), so that a right diagnosis cannot come from fitting the generating formula.
#include <random>
#include <string>
#include <vector>

#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap::independent {

struct Setting {
  int shape = 0;               // which physical form of the effect (0 .. shape_count - 1)
  std::vector<double> draws;   // uniform (0, 1) numbers fixing the magnitudes (shared by repeats)
  double scatter = 1.0;        // specimen-to-specimen factor on the magnitude
  double end_m = 0.0;          // test end on the base model
  double visible_peak_N = 0.0; // peak force of the base model up to the test end
  double stiffness_N_per_m = 0.0;  // initial stiffness of the base model
};

// Physical forms per effect: two each, three for strain_rate (its growing gain, issue 37).
int shape_count(const std::string& effect);

// Magnitude in [lo, hi] from draw `k` of the setting, times its scatter.
double magnitude(const Setting& s, std::size_t k, double lo, double hi);

// A magnitude from draw `k`: from `inner` out to `outer` (the plausible range's edge away from the
// neutral value), a fifth of the draws on the edge itself (issue 51); the specimen scatter then
// multiplies the distance from `neutral`, held within the edge (a real set-up's effect lies in
// the range, a specimen's too).
double toward_edge(const Setting& s, std::size_t k, double neutral, double inner, double outer);

// The edges of the plausible range of an effect's magnitude parameter (or of its parameter
// `index`), from the catalogue with a unit peak force (ranges in fractions of the peak).
double plausible_lower(const std::string& effect, std::size_t index);
double plausible_upper(const std::string& effect, std::size_t index);

// Force of the base model at u (linear, clamped; base.u increasing).
double force_at(const ForceCurve& base, double u);

// The base model up to end_m (the last point interpolated at end_m): what the test shows.
ForceCurve visible(const ForceCurve& base, double end_m);

// Running maximum of v.
std::vector<double> running_max(const std::vector<double>& v);

// One generator per effect (gap/src/independent/<effect>.cpp); shape names for the report.
ForceCurve machine_compliance(const ForceCurve& base, const Setting& s);
ForceCurve grip_slip(const ForceCurve& base, const Setting& s);
ForceCurve initial_slack(const ForceCurve& base, const Setting& s);
ForceCurve gauge_length(const ForceCurve& base, const Setting& s);
ForceCurve ductile_damage(const ForceCurve& base, const Setting& s);
ForceCurve strain_rate(const ForceCurve& base, const Setting& s);

// Dispatch by catalogue name; throws std::invalid_argument for an unknown one.
ForceCurve apply(const std::string& effect, const ForceCurve& base, const Setting& s);
std::string shape_name(const std::string& effect, int shape);

struct Measurement {
  std::size_t points = 800;
  double end_m = 0.0;           // where the record ends (fracture or end of test)
  double noise_sigma_N = 0.0;   // marginal sigma of the load noise
  double noise_rho = 0.0;       // lag-1 correlation of the load noise (AR(1))
  double drift_N = 0.0;         // load-cell drift reached at the end of the record
  double jitter = 0.0;          // irregular sampling: spacing varies by +- this fraction
  bool fracture = false;        // the record ends in the specimen's fracture: its drop recorded
};

// The laboratory record of `truth`: irregular sampling up to end_m (the record stops where the
// specimen broke), correlated load noise and a linear drift of the load-cell zero; with
// `fracture`, two more samples half a step and a step further, where the broken specimen
// carries nothing (the load cell's zero drift and its noise).
ForceCurve measure(const ForceCurve& truth, const Measurement& m, std::mt19937& rng);

}  // namespace dtwire::gap::independent
