// The settle under gravity (settle.hpp).
#include "settle.hpp"

#include <algorithm>
#include <iostream>
#include <string>

#include "dtwire/core/error.hpp"

namespace dtwire::dem {

bool WaitingWall::enter_if_near(Engine& engine) { return place(engine, false); }

void WaitingWall::enter(Engine& engine) { place(engine, true); }

bool WaitingWall::place(Engine& engine, bool now) {
  if (!active_ || entered_) return entered_;
  double lowest = 1e300, radius = 0.0;
  for (std::size_t i = 0; i < engine.node_count(); ++i) {
    const double r = engine.node(i).radius;
    if (engine.position(i).z() - r < lowest) {
      lowest = engine.position(i).z() - r;
      radius = r;
    }
  }
  if (!now && lowest - surface_z_ >= radius) return false;
  if (lowest <= surface_z_)
    throw ComputationError("dem run: a node's surface reached the slack state's wall (" + std::to_string(lowest - surface_z_) +
                           " m) before the wall entered the run: a node moved more than its radius in one step");
  Vector3 position = engine.tool(tool_).position;
  position.z() = surface_z_;
  engine.place_tool(tool_, position, Vector3::Zero());
  entered_ = true;
  entered_at_ = engine.time();
  return true;
}

SettleRecord settle(Engine& engine, const RunInput& in, WaitingWall& wall) {
  SettleRecord record;
  const double start = engine.time();
  if (!(in.settle_rest_ratio > 0.0)) {
    while (engine.time() - start < in.settle_time) {
      engine.step();
      wall.enter_if_near(engine);
    }
  } else {
    // Kinetic damping alone: with the local damping on as well a hanging net reaches rest later
    // (docs/dem_engine.md, "Settling to rest"). A net not at rest by half the settle's time is
    // held by something kinetic damping does not take out (a net lying on the wall: its
    // contacts' chatter, which the arrests at the peaks of the whole net's kinetic energy miss),
    // and the local damping joins it for the rest of the time.
    const double local_damping = engine.local_damping();
    engine.set_local_damping(0.0);
    double previous_kinetic = 0.0;
    long steps = 0;
    while (engine.time() - start < in.settle_time) {
      if (record.local_damping_from < 0.0 && local_damping > 0.0 && engine.time() - start >= 0.5 * in.settle_time) {
        engine.set_local_damping(local_damping);
        record.local_damping_from = engine.time() - start;
      }
      engine.step();
      wall.enter_if_near(engine);
      const double kinetic = engine.kinetic_energy();
      if (kinetic < previous_kinetic) {  // past a peak: stop the swing there
        engine.arrest();
        ++record.arrests;
        previous_kinetic = 0.0;
      } else {
        previous_kinetic = kinetic;
      }
      if (++steps % 10 == 0 && engine.unbalanced_force_ratio() < in.settle_rest_ratio) {
        record.at_rest = true;
        break;
      }
    }
    engine.set_local_damping(local_damping);
  }
  record.time = engine.time() - start;
  record.unbalanced_ratio = engine.unbalanced_force_ratio();
  if (in.settle_rest_ratio > 0.0 && !record.at_rest)
    std::cerr << "[dem run] warning: the net is not at rest after " << record.time << " s of settling (unbalanced-force ratio "
              << record.unbalanced_ratio << ", asked below " << in.settle_rest_ratio << "); the run goes on all the same\n";
  return record;
}

void record_settle(const SettleRecord& settled, RunSummary& summary) {
  summary.settle_seconds = settled.time;
  summary.settled_at_rest = settled.at_rest;
  summary.settle_unbalanced_ratio = settled.unbalanced_ratio;
  summary.settle_arrests = settled.arrests;
  summary.settle_local_damping_from = settled.local_damping_from;
}

}  // namespace dtwire::dem
