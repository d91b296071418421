#pragma once
// What a `dtwire dem run` would take, known before anything is built: memory (mesh, engine state,
// one law per link, history) and disk (curve, VTU frames). The per-node and per-link figures are
// measured against the peak RSS (docs/dem_engine.md, "Resources").
#include <string>

#include "dtwire/dem/run.hpp"

namespace dtwire::dem {

struct RunFootprint {
  double nodes = 0.0, links = 0.0, rows = 0.0, frames = 0.0;
  double memory = 0.0, disk = 0.0;  // [bytes]
  std::string describe() const;     // "3268 nodes, 4784 links, 301 history rows"
};

RunFootprint run_footprint(const RunInput& input, bool write_frames);

}  // namespace dtwire::dem
