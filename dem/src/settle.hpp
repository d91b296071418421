#pragma once
// The settle under gravity before the tool moves (docs/dem_engine.md, "Settling to rest"), and
// the slack state's wall, which waits out of the run until the net comes near it.
#include <cstddef>

#include "dtwire/dem/engine.hpp"
#include "dtwire/dem/run.hpp"

namespace dtwire::dem {

// A horizontal wall the net may come down onto (the slack state's, run.hpp `wall_below`). It is
// added parked while the net settles: a wall the net has not reached only shortens the settling
// step (its contact spring is the stiffest term of an edge node's bound, docs/dem_engine.md
// "Speed"). It enters the run when a node's surface comes within one node radius of it, checked
// after every step: a node moves far less than its radius in a step (its speed times a step of
// about 1e-3 s), so no node is inside the wall when it enters, which enter_if_near checks all
// the same. It enters at the latest when the tool starts: with it in the bound the push's step
// keeps the platter contact's omega dt at 0.58 ("What sets the step of the slack punch").
class WaitingWall {
 public:
  WaitingWall() = default;
  WaitingWall(std::size_t tool_index, double surface_z) : tool_(tool_index), surface_z_(surface_z), active_(true) {}
  // Places the wall if a node has come near it; returns true once it is in the run. Throws
  // ComputationError if a node is already inside it.
  bool enter_if_near(Engine& engine);
  // Places the wall now if it has not entered yet (the net clear of it: throws otherwise).
  void enter(Engine& engine);
  bool entered() const { return entered_; }
  double entered_at() const { return entered_at_; }  // engine time [s], -1 if it never entered

 private:
  bool place(Engine& engine, bool now);  // now: whatever the distance
  std::size_t tool_ = 0;
  double surface_z_ = 0.0, entered_at_ = -1.0;
  bool active_ = false, entered_ = false;
};

struct SettleRecord {
  double time = 0.0;                // how long it settled [s]
  bool at_rest = false;             // the rest criterion was met (rest_ratio > 0 only)
  double unbalanced_ratio = 0.0;    // Engine::unbalanced_force_ratio at the end
  long arrests = 0;                 // kinetic-damping arrests
  double local_damping_from = -1.0; // when the local damping joined the kinetic [s]; < 0: never
};

// Settles under gravity: for in.settle_time if in.settle_rest_ratio is 0; otherwise with kinetic
// damping (the free nodes stopped at each peak of the kinetic energy, Barnes 1999) until YADE's
// unbalanced-force ratio is below in.settle_rest_ratio (checked every 10 steps), at most
// in.settle_time, the local damping joining the kinetic from half that time on, with a warning
// on stderr if the net is not at rest by then. The wall, if any, enters as it says.
SettleRecord settle(Engine& engine, const RunInput& in, WaitingWall& wall);

// The settle's figures in a run's summary (settle_seconds, settled_at_rest, ...).
void record_settle(const SettleRecord& settled, RunSummary& summary);

}  // namespace dtwire::dem
