#pragma once
// Strip tension test of DT mesh (the mesh tensile test of EN 10223-3 and EN 15381 Annex D) as a
// `dtwire dem run` tool, `[tool] kind = "strip_tension"` (docs/dem_engine.md, "Strip tension"):
//   1. the net is generated as for the punch (twists along y); the strip is pulled along the
//      twists (y) or across them (x);
//   2. every node within `clamp_depth` of either end (along the pull, measured from the
//      outermost nodes) is held by a rigid clamp bar: translations and rotations; the first bar
//      is fixed, the second moves at `speed` along the pull for `travel` (quasi-static: mass
//      scaling and local damping as in the punch, gravity optional);
//   3. the edges along the pull are free (EN 10223-3: the strip narrows between the clamps);
//   4. the force on each bar is minus the sum of the link forces on its held nodes (the engine's
//      unbalanced force of a held node), averaged over each output interval;
//   5. free length L0 = distance between the clamp faces (node extent along the pull - 2 d),
//      width b = node extent across the pull; strength per metre = peak force / b; secant axial
//      stiffness per metre EA = chord of force per width against engineering strain u / L0
//      between the first passes of 10 % and 50 % of the peak (why: chord_stiffness below).
// The run stops when the strip has torn through (force below 2 % of its peak after a link broke)
// or when the travel is done.
#include <cstddef>
#include <vector>

namespace dtwire::dem {

struct RunInput;
struct RunOptions;
struct RunSummary;

enum class PullDirection { AlongTwists, AcrossTwists };

struct StripTensionInput {
  PullDirection direction = PullDirection::AlongTwists;
  double clamp_depth = 0.05;  // [m]
};

// The chord slope of force per width against strain between the first points where the force
// reaches `low` x and `high` x its peak (linear interpolation between samples, before the peak).
// A strip of DT mesh first straightens its hexagons (near-zero force: the toe depends on how the
// strip was laid and clamped), and its wires yield well before the peak; the 10-50 % chord
// leaves out both, the way a chord modulus between two load levels does for a tensile test.
struct ChordStiffness {
  bool defined = false;
  double value = 0.0;                        // [N/m per unit strain] = [N/m]
  double strain_low = 0.0, strain_high = 0.0;
};
ChordStiffness chord_stiffness(const std::vector<double>& strain, const std::vector<double>& force_per_width,
                               double low, double high);

// The strip figures of a run (RunSummary::strip).
struct StripFigures {
  double width = 0.0, free_length = 0.0;          // b, L0 [m]
  std::size_t fixed_nodes = 0, moving_nodes = 0;  // held by each clamp
  double strength_per_width = 0.0;                // peak force / b [N/m]
  double strain_at_peak = 0.0;                    // elongation at peak / L0
  // EN 10223-3 ends its test at the first wire break: the force of the last row before a link
  // broke [N] (0: none broke).
  double force_at_first_break = 0.0;
  ChordStiffness secant;                          // 10-50 % chord: EA per metre width [N/m]
  double origin_secant = 0.0;                     // 0.5 peak / b / strain at 50 % of the peak [N/m]
  double end_force = 0.0, end_reaction_imbalance = 0.0;  // moving-bar force and its sum with the fixed bar's, last row [N]
  bool torn = false;                              // stopped because the strip tore through
};

// Runs the strip and writes curve.csv, results.h5, summary.json (and frames); called by
// run_simulation for kind = "strip_tension". Throws InputError when the clamps cover the whole
// generated strip (its nodes may end short of the nominal panel length) before writing anything.
RunSummary run_strip_tension(const RunInput& input, const RunOptions& options);

}  // namespace dtwire::dem
