#pragma once
// A force-displacement curve in SI (m, N), the working form of every gap computation, and
// loading it from a curve CSV (displacement/force, or strain/stress with a gauge length and
// a cross-section).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/core/curve.hpp"

namespace dtwire::gap {

struct ForceCurve {
  std::vector<double> u;  // displacement [m]
  std::vector<double> f;  // force [N]
  std::string source;     // file name or a description, for messages
  // A strip tension of a panel of mesh (a DEM run's metadata strip_width_m, free_length_m; 0:
  // not a strip): the standard's figures are per metre of width and per unit strain.
  double strip_width_m = 0.0, free_length_m = 0.0;
  std::size_t size() const { return u.size(); }
};

// Takes a strip tension's width and free length from a curve's metadata (strip_width_m,
// free_length_m), when it has them.
void read_strip_geometry(const Curve& curve, ForceCurve& out);

struct CurveConversion {
  std::optional<double> gauge_length_m;  // turns strain_1 into displacement
  std::optional<double> area_m2;         // turns stress into force
  // Channels (names without unit) to read instead of displacement and force, e.g. a DEM run's
  // tool_displacement and tool_force; empty: the default names.
  std::string displacement_channel, force_channel;
};

// Reads a curve CSV: a length channel named displacement (or elongation/extension) and a
// force channel named force; or strain and stress channels when `conversion` gives the gauge
// length and the area. Throws InputError naming the file and what was expected.
ForceCurve load_force_curve(const std::filesystem::path& path, const CurveConversion& conversion);

// "" if the rows look like one test in the order it ran; otherwise a warning naming the file:
// a test reverses its displacement a few times per cycle, so rows whose large steps (> 5 % of
// the displacement range) reverse direction most of the time (> 40 %, at least 5 times) are
// more likely shuffled or sorted by another column than a test with that many cycles.
std::string row_order_warning(const ForceCurve& curve);

// Checks size (>= 3 points) and finiteness; throws InputError naming `curve.source`.
void validate_force_curve(const ForceCurve& curve);

}  // namespace dtwire::gap
