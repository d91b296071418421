// The memory and disk estimate of a DEM run (run_footprint.hpp).
#include "dtwire/dem/run_footprint.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace dtwire::dem {
namespace {

// Fitted to the peak RSS of punch_macro.toml panels (thesis law) of 3 x 3, 10 x 10 and 25 x 25 m,
// about 1.2 times it (docs/dem_engine.md, "Resources").
constexpr double kProgramBytes = 80e6;    // executable, libraries (HDF5, MPI), TOML and parameter files
constexpr double kBytesPerNode = 1000.0;  // mesh copies, engine state, tool contact slots
constexpr double kBytesPerLink = 700.0;   // law object, link state, mesh link, recorder snapshots
constexpr double kBytesPerRow = 3 * 20 * 8.0;  // 20 columns, held three times (recorder, curve, summary)
// An ASCII VTU frame: coordinates and displacement per node, connectivity, force, tag, flags per link.
constexpr double kFrameBytesPerNode = 110.0, kFrameBytesPerLink = 50.0, kCsvBytesPerRow = 20 * 24.0;

}  // namespace

std::string RunFootprint::describe() const {
  // Whole numbers up to a billion, then 3 digits (a typo's 1.43e+09 nodes).
  auto count = [](double n) {
    std::ostringstream os;
    if (n < 1e9) os << static_cast<long long>(n);
    else os << std::setprecision(3) << n;
    return os.str();
  };
  std::string text = count(nodes) + " nodes, " + count(links) + " links, " + count(rows) + " history rows";
  if (frames > 0.0) text += ", " + count(frames) + " frames";
  return text;
}

RunFootprint run_footprint(const RunInput& in, bool write_frames) {
  RunFootprint f;
  const HexMeshSize size = hex_mesh_size(in.mesh);
  f.nodes = size.nodes;
  f.links = size.links;
  // The simulated time after settling: the cyclic punch goes up and down once per force level.
  double duration = in.duration;
  if (in.tool == "platter") duration = (1.0 + 2.0 * static_cast<double>(in.force_levels.size())) * in.travel / in.speed;
  if (in.tool == "strip_tension") duration = in.travel / in.speed;
  f.rows = std::floor(duration / in.output_interval) + 2.0;
  f.frames = write_frames && in.frames > 0 ? in.frames + 1.0 : 0.0;
  f.memory = kProgramBytes + kBytesPerNode * f.nodes + kBytesPerLink * f.links + kBytesPerRow * f.rows;
  f.disk = kCsvBytesPerRow * f.rows + f.frames * (kFrameBytesPerNode * f.nodes + kFrameBytesPerLink * f.links);
  return f;
}

}  // namespace dtwire::dem
