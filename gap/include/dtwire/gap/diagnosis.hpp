#pragma once
// The gap diagnosis: where the gap between a simulated curve and laboratory curves lies, which
// catalogue effect explains it, and how far it shrinks once that effect is added.
#include <map>
#include <string>
#include <vector>

#include "dtwire/gap/effect_fit.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/regions.hpp"

namespace dtwire::gap {

struct DiagnosisOptions {
  std::vector<std::string> effects;  // empty: every effect of the catalogue
  bool try_pairs = true;
  unsigned seed = 1;
  std::size_t random_starts = 3;
  // --model mode: with a runner, model-only effects are candidates too (else "not tested").
  ModelRunner model;
  // Model-only effects the runner cannot switch on for this model, with the reason.
  std::map<std::string, std::string> model_unsupported;
  // Effects that do not act in this loading mode, with the reason (listed as not tested).
  std::map<std::string, std::string> inapplicable;
  // Pairs with a model-only effect: at most this many points of the bounded search (each at most
  // one FE run; cached runs are free).
  std::size_t model_runs = 3;  // also: values run per single model-only effect (issue 51)
};

// Evidence for a pair against the best single effect (see gap/src/parsimony.cpp).
struct PairEvidence {
  bool done = false;
  std::string single;            // the best single effect it is compared with
  double lag1 = 0.0, n_eff = 0.0;  // of the single's residual
  double bic_single = 0.0, bic_pair = 0.0;
  bool heldout_done = false;      // not for pairs with a model-only effect (FE cost)
  double heldout_error_single = 0.0, heldout_error_pair = 0.0;  // weighted SSE on held-out blocks
  bool information_ok = false, heldout_ok = false;
};

struct RankedEffect {
  std::string effect;  // catalogue name, or "a+b" for a pair
  std::vector<AppliedEffect> fitted;
  int parameters = 0;
  double gap_after = 0.0;
  double shrink = 0.0;  // 1 - gap_after / gap_before
  double score = 0.0;   // Akaike weight x plausibility x (1 + region match) / 2
  double aicc = 0.0, delta_aicc = 0.0, bic = 0.0;  // delta: against the simulation alone
  double plausibility = 1.0;
  double region_match = 0.0;  // 1 when the effect changes the curve where the gap is
  double frechet_after = 0.0;
  double pcm_after = 0.0;
  std::vector<double> gap_after_by_segment;  // per entry of Diagnosis::where
  bool qualifies = false;  // beats the noise floor and the information criterion
  bool implausible = false;  // a magnitude fitted outside its plausible range: never the cause
  // Which magnitudes lie beyond their plausible range (empty unless implausible), and whether
  // the candidate met every other rule of a cause (then the verdict names it, issue 51).
  std::vector<BeyondRange> beyond_range;
  bool qualifies_but_implausible = false;
  // Magnitudes fitted past their range's edge by no more than the data tell (held at the edge,
  // the rest refitted, the fit is as good): the candidate stays plausible and says so.
  std::vector<BeyondRange> at_range_edge;
  int search_points = 0;   // pairs with a model-only effect: points of the bounded search
  // Candidates with a model-only effect: values run by its search (each at most one model run;
  // cached runs are free) and the search's wall time.
  int model_runs = 0;
  double model_seconds = 0.0;
  PairEvidence against_single;  // pairs only
  bool also_possible = false;   // a pair that fits better but fails the parsimony rule
  // Combined ranking over several loading modes: the effects as applied in each mode.
  std::vector<std::pair<std::string, std::vector<AppliedEffect>>> fitted_by_mode;
};

struct PredictiveCheck {
  bool done = false;
  std::string note;  // why not done
  std::string effect, fitted_on, predicted;
  double gap_before = 0.0, gap_after = 0.0, shrink = 0.0;
};

struct Diagnosis {
  std::string metric = "normalised_area";
  double noise_sigma_N = 0.0;
  double scatter_gap = -1.0;  // mean gap between the laboratory curves (< 0: one curve)
  // Repeated curves (< 0: one curve): their mean gap once each pair is aligned by a force and a
  // displacement scale, the bounds on the mean specimen's scales, and the gap before with the
  // scatter left in (gap_before has it profiled out).
  double aligned_scatter_gap = -1.0;
  double specimen_force_bound = -1.0, specimen_length_bound = -1.0;
  double gap_before_unadjusted = -1.0;
  double noise_floor = 0.0;
  double gap_before = 0.0;
  double frechet_before = 0.0;
  double pcm_before = 0.0;  // partial curve mapping
  double effective_sample_size = 0.0;
  double lag1_autocorrelation = 0.0;
  bool compression = false;  // a curve was given in compression; reported as magnitudes
  std::vector<GapSegment> where;
  std::vector<RankedEffect> ranking;
  std::string cause = "none";
  std::string reason;
  // The verdict (issue 51), one of: "cause" (an effect closes the gap with a plausible
  // magnitude), "beyond_plausible_range" (an effect closes it, but only with a magnitude beyond
  // its plausible range: `refused` names it), "no_effect_closes" (none does), "within_noise"
  // (nothing to explain), "nothing_tested".
  std::string verdict = "no_effect_closes";
  std::string refused_effect;  // "beyond_plausible_range": the ranking entry it names
  // "cause" that closes the gap to the noise floor: the other single effects that qualify and do
  // too. The evidence ranks them below the cause, but the laboratory's own scatter does not tell
  // them apart (e.g. a gauge scale against a grip slip on a curve that hardens to its end).
  std::vector<std::string> also_closes;
  std::vector<std::string> not_tested;
  std::map<std::string, std::string> not_tested_reason;
  PredictiveCheck predictive;
  ForceCurve sim;                // oriented
  std::vector<ForceCurve> labs;  // oriented, each up to its fracture when it broke
  std::vector<double> fracture_m;  // per laboratory curve: where it broke (0: it ended otherwise)
  ForceCurve best_model;         // the simulation with the cause (or the top effect) added
};

// Orients a curve so that its dominant force is positive (compression -> tension signs).
ForceCurve oriented(const ForceCurve& curve, bool* flipped = nullptr);

// Throws InputError (naming the files) for curves that cannot be compared: too few points,
// no force, or displacement ranges that do not overlap.
Diagnosis diagnose(const std::vector<ForceCurve>& labs, const ForceCurve& sim,
                   const DiagnosisOptions& options);

// Thresholds, documented in docs/gap.md.
inline constexpr double kNoiseFloorFactor = 1.2;    // floor = 1.2 x expected noise-only area
inline constexpr double kMinimumReduction = 0.3;    // x expected noise-only area
inline constexpr double kMinimumOverlap = 0.2;      // of the laboratory displacement range
inline constexpr double kInformationMargin = 10.0;  // AICc units an accepted effect must gain
inline constexpr double kPairGapRatio = 0.8;        // a pair must cut the single's gap by 20 %
// A plausible candidate that leaves the gap above the floor is the cause only when it removes at
// least this share of what the best implausible candidate removes (the verdict, issue 51).
inline constexpr double kOutdoneRatio = 0.5;
inline constexpr double kPairBicMargin = 6.0;       // BIC units a pair must gain over the single
inline constexpr double kPairHeldOutRatio = 0.8;    // held-out error of the pair / the single's
inline constexpr int kHeldOutBlocks = 10;           // alternate blocks: even fitted, odd held out
// Laboratory curves with fewer points are digitised polylines: refined between their vertices,
// and their noise taken as at least 0.5 % of the peak force (digitisation resolution).
inline constexpr std::size_t kSparseCurvePoints = 50;
inline constexpr double kDigitisedResolution = 0.005;

}  // namespace dtwire::gap
