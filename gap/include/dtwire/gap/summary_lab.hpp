#pragma once
// Diagnosis against laboratory summary figures (mean and scatter of curve features, e.g. the
// peak and residual force of a test series) instead of laboratory curves: the simulated
// curve's features are compared with the laboratory means in units of the laboratory scatter,
// and that scatter is the noise floor. Effects are fitted to the features; model-only effects
// through the ModelRunner with a small, bounded 1-D search (every FE run costs seconds).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dtwire/gap/effects.hpp"

namespace dtwire::gap {

struct SummaryFeature {
  // peak_force_N, residual_force_N, peak_displacement_mm, onset_displacement_mm or force_at_<D>mm_N
  std::string name;
  double mean = 0.0, sd = 0.0;  // in the unit of the name
};

// "peak_force_N=1510:196,residual_force_N=550:77". Throws InputError naming `field` and the
// feature: unknown name, missing '=' or ':', a value that is not a number, sd <= 0, repeats.
std::vector<SummaryFeature> parse_lab_summary(const std::string& text,
                                              const std::string& field = "--lab-summary");
std::string summary_feature_names();

// The feature of an oriented curve (dominant force positive), in the unit of its name:
// peak_force_N the largest force, residual_force_N the force at the end of the test,
// peak_displacement_mm the displacement at the peak, onset_displacement_mm where the force first
// reaches kOnsetFraction of the peak, force_at_<D>mm_N the force where the displacement first
// reaches D mm (linear between samples; the first force before the curve's start, the last
// after its end: diagnose_summary refuses a simulation that does not reach D);
// displacement_at_<F>N_mm where the force first reaches F newtons (linear between samples; the
// last displacement where it never does: diagnose_summary refuses a simulation that does not);
// strength_N_per_m the peak force per metre of a strip's width, secant_stiffness_N_per_m its chord
// between kSecantLow and kSecantHigh of the peak, per metre and per unit strain over the free
// length (both need a strip tension's geometry, else InputError).
double curve_feature(const ForceCurve& curve, const std::string& name);
// Warnings that laboratory figures may not be in their names' units (flagged, not refused): a
// mean of the other sign than the simulation's figure, or more than kScaleWarningDecades decades
// from it (docs/gap.md: beyond any effect's plausible reach), naming the figure and what its
// ratio suggests ("peak_force_N=25: 0.000553 times the simulation's 45200; a figure in kN given
// in N?"). Checked before the diagnosis (whose searches may take minutes); throws what
// diagnose_summary would for a curve or figure it cannot take.
std::vector<std::string> summary_scale_warnings(const std::vector<SummaryFeature>& lab, const ForceCurve& sim);
// Whether a curve's largest force lies in the last kCurveEndShare of its displacement: a run that
// ended before its specimen failed (a punch whose platter stopped first), so the figures that
// hang on the peak (feature_needs_peak) are lower bounds of the specimen's, not its failure's.
// The campaign's rule for a punch that does not apply (docs/campaign.md, "The recommended set").
bool peak_at_curve_end(const ForceCurve& curve);
inline constexpr double kCurveEndShare = 0.01;
struct SummaryCandidate;
// Whether the run of a single model-only candidate's fitted value is in its peak_at_end.
bool fitted_peak_at_end(const SummaryCandidate& c);
// peak_force_N, peak_displacement_mm, onset_displacement_mm (a share of the peak),
// strength_N_per_m and secant_stiffness_N_per_m (its chord between shares of the peak).
bool feature_needs_peak(const std::string& name);
// D of a force_at_<D>mm_N name (D a positive plain decimal, e.g. force_at_420mm_N), else none.
std::optional<double> force_at_displacement_mm(const std::string& name);
// F of a displacement_at_<F>N_mm name (F a positive plain decimal, e.g. displacement_at_1000N_mm:
// where the force first reaches 1 kN, the onset of `dem run`'s punch summary), else none.
std::optional<double> displacement_at_force_N(const std::string& name);
// The force_at_<D>mm_N name of a displacement in mm (up to 10 significant digits).
std::string force_at_feature_name(double displacement_mm);

struct SummaryOptions {
  std::vector<std::string> effects;  // empty: all
  ModelRunner model;
  std::map<std::string, std::string> model_unsupported;  // effect -> reason
  std::map<std::string, std::string> inapplicable;  // effects not acting in the loading mode -> reason
  std::size_t model_runs = 3;  // FE runs per model-only effect (the base run is given), and
                               // search points per pair with a model-only effect
  bool try_pairs = true;
  unsigned seed = 1;
  // Model-only effects searched side by side (issue 38): each search's runs stay in their order,
  // so the diagnosis is the serial one; the runner must then be safe to call from several threads.
  unsigned jobs = 1;
};

struct SummaryCandidate {
  std::string effect;
  std::vector<AppliedEffect> fitted;
  std::vector<double> features;  // of the augmented simulation, in feature order
  ForceCurve curve;              // the augmented simulation
  double gap_after = 0.0, shrink = 0.0, plausibility = 1.0, score = 0.0;
  // Akaike's criterion with the laboratory sd known, corrected for few figures (AICc, Hurvich and
  // Tsai 1989): sum of z^2 + 2 k + 2 k (k + 1) / (n - k - 1), k parameters, n figures; where
  // n <= k + 1 the correction is undefined (taken as 1e9, as the curve mode's AICc does): so many
  // parameters reproduce any n figures, and the candidate cannot be judged against fewer.
  double aic = 0.0;
  int parameters = 0;
  int runs = 0;  // FE runs spent (pairs: search points, each at most one FE run)
  double model_seconds = 0.0;  // wall time of its model search (searches side by side overlap)
  // Model-only effects: every value run (the neutral one is the simulation; a pair's values of its
  // model-only parameters) and the features.
  std::vector<std::pair<std::vector<double>, std::vector<double>>> samples;
  // The values whose run's peak lay at its curve's end (peak_at_curve_end) while a figure hangs
  // on the peak: their peak figures are lower bounds.
  std::vector<std::vector<double>> peak_at_end;
  bool qualifies = false;
  bool implausible = false;  // a magnitude fitted outside its plausible range: never the cause
  std::vector<BeyondRange> beyond_range;  // which magnitudes, with their ranges
  // Magnitudes fitted just past their ranges' edges that the features, refitted with them held
  // at the edge, still allow (then not implausible; the fitted values are kept).
  std::vector<BeyondRange> at_range_edge;
  // A pair with a curve-mode partner: its model run's curve, before the partner is applied.
  ForceCurve model_curve;
  bool qualifies_but_implausible = false;  // met every rule of a cause but the plausible range
};

struct SummaryDiagnosis {
  std::string metric = "summary_z_rms";
  std::vector<SummaryFeature> lab;
  std::vector<double> sim_features;
  double noise_floor = 1.0;  // one laboratory standard deviation
  double gap_before = 0.0;
  bool compression = false;
  std::vector<SummaryCandidate> ranking;  // by score
  std::string cause = "none", reason;
  // As Diagnosis::verdict (issue 51): cause, beyond_plausible_range (refused_effect names the
  // candidate), no_effect_closes, within_noise.
  std::string verdict = "no_effect_closes", refused_effect;
  // "cause" within the scatter: the other single effects that qualify and are too (Diagnosis::also_closes).
  std::vector<std::string> also_closes;
  std::vector<std::string> not_tested;
  std::map<std::string, std::string> not_tested_reason;
  // Wall time from the first model search to the last pair's (with --jobs below the candidates'
  // summed model_seconds).
  double model_elapsed_seconds = 0.0;
  ForceCurve sim, best_model;  // oriented
};

// Root mean square of (simulated - laboratory mean) / laboratory sd over the features.
double summary_gap(const std::vector<SummaryFeature>& lab, const std::vector<double>& features);

SummaryDiagnosis diagnose_summary(const ForceCurve& sim, const std::vector<SummaryFeature>& lab,
                                  const SummaryOptions& options);

nlohmann::json summary_json(const SummaryDiagnosis& d);
std::string summary_markdown(const SummaryDiagnosis& d);

inline constexpr double kOnsetFraction = 0.04;
// secant_stiffness_N_per_m: the chord between these fractions of the peak force (as `dem run`'s
// strip summary; the standard states no range for its "about 500 kN/m").
inline constexpr double kSecantLow = 0.1, kSecantHigh = 0.5;
// A qualifying effect must remove at least this fraction of the gap.
inline constexpr double kSummaryMinimumShrink = 0.3;
// Pairs (with a model-only effect) are tried among this many best single effects.
inline constexpr std::size_t kSummaryPairCandidates = 4;

}  // namespace dtwire::gap
