#pragma once
// What a double-twist tension test shows besides its curve, as numbers a model can be held to
// (issue 17, "the DT tension FE curve against what the laboratory shows"): the tightening toe
// and where the specimen fails (in the twist, at the SW/DT junction, in an arm).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap {

// Toe of the loading branch (m), as in the toe compensation of tensile standards (ISO 527-1
// sec. 10.1, ASTM D638 annex A1): the steepest chord below half the peak force, extended down
// to zero force; its intercept with the displacement axis (0 when it falls below 0).
double toe_length(const ForceCurve& curve);

enum class FailureZone { twist, junction, arm, unknown };
std::string zone_name(FailureZone zone);

// Where along the twist axis a failure at height z (m) lies, from the wires' axis stations as
// (height m, curvature magnitude 1/m): the station nearest in height decides; straight (curvature
// below 1 % of the largest) is an arm, the twist's helix curvature (the most frequent non-zero
// one, within 10 %) the twist, anything more curved a junction bend.
FailureZone failure_zone(double z, const std::vector<std::pair<double, double>>& stations);

// The failure an FE curve's metadata reports (`# failure: [in the <place>, ]<mode> at displacement
// X mm, ..., z = Z mm, ...`), in SI; nullopt when the text has no such figures.
struct ReportedFailure {
  std::string mode;
  double displacement = 0.0, z = 0.0;  // m
};
std::optional<ReportedFailure> parse_reported_failure(const std::string& text);

// One run of the DT model (the model as it is, or with one effect) as `gap features` reads it.
struct FeatureRun {
  std::string effect;  // "none" for the model as it is
  bool failed = false;  // the run did not finish
  double peak_force = 0.0;  // N
  FailureZone zone = FailureZone::unknown;
};

// What the laboratory shows: where the specimens fail (nullopt: not stated) and their peak force
// with its standard deviation (N; sd 0: not stated).
struct LabFeatures {
  std::optional<FailureZone> zone;
  double peak_force = 0.0, peak_sd = 0.0;
};

// Which effect explains the laboratory's failure and strength. A candidate puts the failure in the
// laboratory's zone (when one is stated) and brings the peak nearer (when one is stated); of the
// candidates, the one with the smallest peak gap after wins (the first one run on a tie, and the
// first candidate when no peak is stated). `effect` is "none" when no run is a candidate.
struct FeatureVerdict {
  std::string effect = "none";
  std::vector<std::string> candidates;
  double gap_before_sd = 0.0, gap_after_sd = 0.0;  // |peak - laboratory| / sd; 0 with no peak
  double shrink = 0.0;                             // 1 - after / before
  bool within_scatter = false;                     // the gap after is at most 1 sd
};
FeatureVerdict explain_features(const std::vector<FeatureRun>& runs, const LabFeatures& lab);

}  // namespace dtwire::gap
