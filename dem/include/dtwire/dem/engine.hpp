#pragma once
// The reference DEM engine for wire nets: explicit central-difference (leapfrog) integration of
// node translations and rotations, links carrying any law of the contact library, rigid tools,
// gravity, PFC/YADE local damping and full energy bookkeeping. Formulas: docs/dem_engine.md.
//
// Per step n (positions x_n, half-step velocities v_{n-1/2}):
//   1. links: increments of the six generalised displacements from x_{n-1} -> x_n (axial from
//      the length, shear and rotations from the half-step velocities), law update, forces;
//   2. tools: node-tool contacts (normal spring, incremental shear spring, Coulomb cap), and
//      roller-link contacts (roller.hpp: the same law at a link's point, lever rule to its nodes);
//   3. nodes: F = links + tools + gravity (gravitational mass); local damping
//      F_d = -alpha |F_i| sign(F_i (v_i + dt F_i / 2m)) per component (YADE's NewtonIntegrator);
//      v_{n+1/2} = v_{n-1/2} + dt (F + F_d)/m_inertial, x_{n+1} = x_n + dt v_{n+1/2}
//      (when the step changes, the variable-step form: increments over the last move's step,
//      the velocity update over the mean of the last and the next step).
// Links, tools and nodes are updated in parallel (OpenMP, one region a step), each writing its own
// slot; nodes gather their links in a fixed order and every sum runs on one thread in a fixed
// order, so 1 and N threads give bit-identical results.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "dtwire/dem/net.hpp"
#include "dtwire/dem/roller.hpp"
#include "dtwire/dem/tools.hpp"

namespace dtwire::dem {

struct EngineOptions {
  Vector3 gravity = Vector3(0.0, 0.0, -9.81);  // [m/s^2]
  double local_damping = 0.0;                  // alpha in [0, 1)
  double mass_scale = 1.0;  // inertial mass = mass_scale x mass (gravity keeps the real mass)
  // Rotational inertia = rotational_inertia_scale x mass_scale x I. A node's I (0.4 m r^2, r the
  // wire radius) is tiny against a link's lever arm, so the shear-rotation mode sets the critical
  // step; scaling I alone leaves every static equilibrium unchanged (rotational density scaling,
  // Thornton 2000; PFC's `ball property "density"` per rotational degree).
  double rotational_inertia_scale = 1.0;
  double time_step = 0.0;   // [s]; 0: safety x critical
  double safety = 0.5;      // fraction of the critical step
  bool allow_above_critical = false;  // tests only: step beyond the stability bound
  int threads = 1;
  // Loops shorter than this run on one thread: a parallel region costs more than a few thousand
  // link updates, and much more when the cores are shared. Tests set 0 to force threading.
  std::size_t parallel_threshold = 2000;
};

// Work and energies since the start [J]. balance_error = external - (kinetic + stored +
// dissipated); kinetic uses the synchronised form m v_{n-1/2}.v_{n+1/2}/2, for which the
// trapezoidal work of every force matches the kinetic energy exactly.
struct EnergySplit {
  double kinetic = 0.0;
  double link_elastic = 0.0, link_plastic = 0.0, link_damage = 0.0;
  double contact_elastic = 0.0;  // node-tool and roller-link springs
  double friction = 0.0;         // node-tool and roller-link slip
  double damping = 0.0;          // local and kinetic damping (dissipated, >= 0)
  double gravity_work = 0.0, tool_work = 0.0, boundary_work = 0.0;
  double external() const { return gravity_work + tool_work + boundary_work; }
  double stored_and_dissipated() const {
    return kinetic + link_elastic + link_plastic + link_damage + contact_elastic + friction + damping;
  }
  double balance_error() const { return external() - stored_and_dissipated(); }
};

// A law per link, created by the caller (one per link; the engine owns them).
struct EngineLink {
  NetLink link;
  std::unique_ptr<ContactLaw> law;
};

struct RelaxResult {
  long steps = 0;
  bool converged = false;
  double force_ratio = 0.0;  // max unbalanced force / mean link force magnitude
};

class Engine {
 public:
  // Throws std::invalid_argument for bad nodes (non-positive mass, ...) and for a time step
  // above the critical one (unless allow_above_critical).
  Engine(std::vector<NetNode> nodes, std::vector<EngineLink> links, EngineOptions options);
  ~Engine();
  Engine(Engine&&) noexcept;

  // Adds a tool; returns its index. The critical step is recomputed. A tool added `parked`
  // touches nothing and is left out of the stability bound until place_tool() puts it in the
  // run (e.g. the punch platter while the net settles: its contact spring would otherwise set
  // the settling step, docs/dem_engine.md "Speed").
  int add_tool(std::unique_ptr<Tool> tool, bool parked = false);
  // Adds a kinematic roller that touches the links (roller.hpp); link_radius[l] is link l's wire
  // radius against it (0: no contact). Returns its index; the critical step is recomputed.
  // Throws std::invalid_argument for a radius list of the wrong size, a negative radius or a
  // roller with a non-positive radius or a zero axis.
  int add_roller(const Roller& roller, std::vector<double> link_radius);
  // Moves tool i (no contacts may act at that moment) and sets its velocity; the kinetic energy
  // given to a free tool is booked as boundary work. A parked tool enters the run here: the
  // step drops to the stable step with its contact.
  void place_tool(std::size_t i, const Vector3& position, const Vector3& velocity);
  // Moves every node (not only free ones) to a new position before the first step, as an
  // imposed initial deformation (e.g. pre-tension); the links see it in the first step and its
  // work is booked as boundary work.
  void impose_positions(const std::vector<Vector3>& positions);

  // Stability bound of the undamped system (element eigenvalue bound, docs/dem_engine.md) [s],
  // with the tools in the run (parked ones left out) and the degrees of freedom that move (a
  // slider node with all its translations or its rotation held adds nothing there).
  double critical_time_step() const;
  double time_step() const { return dt_; }
  // A step of the caller's, kept from then on; throws if above the bound with every tool placed
  // and every slider component released (unless allowed).
  void set_time_step(double dt);

  // Changes the prescribed velocity of guided node i from the next step on (e.g. grips moved
  // by a load increment, then held while the net relaxes); for a free node on a slider support
  // only its held components follow it (e.g. edges pulled apart along their normal, free along
  // the edge; the support's work is booked as boundary work). Throws std::invalid_argument if the
  // node is neither guided nor on a slider.
  void set_guided_velocity(std::size_t i, const Vector3& velocity);

  // Changes the slider support of free node i: components newly held stop (their kinetic energy
  // is taken out by the support, booked as boundary work), released ones move freely. The
  // automatic step (no time_step given) follows the new bound from the next step on.
  void set_support(std::size_t i, const std::array<bool, 3>& held_translation, bool held_rotation);

  void step();
  // Kinetic damping (Barnes 1999, Int. J. Space Struct. 14(2) 89-104): called after the step n
  // whose kinetic energy fell, the next step takes out the kinetic energy it would leave (booked
  // as damping) and the one after moves every free node back to the peak, Barnes's
  // x* = x_n - dt v_{n-1/2} / 2 (= x_{n+1} - 3/2 dt v_{n+1/2} + dt^2/2 F_n/m), nodes and spins
  // alike, and starts it from rest there (a slider's held components keep the support's motion);
  // the work of the forces over that move is booked as damping, so the balance stays exact.
  // Called at a peak of the kinetic energy, where the forces are nearly in balance, it stops a
  // slow swing at its middle instead of damping it over periods. Without the move back (the
  // nodes stopped at x_{n+1}, 1.5 steps past the peak) the arrests pump any swing of 3 to 10
  // steps a period (omega dt 0.62-1.0 and above 1.7): they lock to its period and give it up to
  // 11 % more amplitude each (test KineticDampingDoesNotPumpASwingOfFewStepsAPeriod).
  void arrest();
  // The local damping coefficient from the next step on, in [0, 1) (e.g. off while kinetic
  // damping settles a net: the two together reach rest later than kinetic damping alone).
  void set_local_damping(double alpha);
  double local_damping() const { return options_.local_damping; }
  // YADE's unbalancedForce (utils.unbalancedForce): the mean unbalanced force on the free nodes
  // in the last step (gravity included, held components the support's) over the mean force of
  // the interactions (the links and the tools' and rollers' contacts); infinite while none
  // carries force. Tends to 0 at static equilibrium.
  double unbalanced_force_ratio() const;
  // Dynamic relaxation: steps with kinematic tools held until the largest unbalanced force on a
  // free node is below `tolerance` x the mean link force magnitude (at most max_steps).
  RelaxResult relax(double tolerance, long max_steps);

  double time() const { return time_; }
  // The kinetic energy of the last step [J] (energy().kinetic without summing the stored parts).
  double kinetic_energy() const { return energy_.kinetic; }
  long steps_taken() const { return steps_; }
  // The energy split; the stored parts (link and contact energies) are summed on reading.
  const EnergySplit& energy() const;
  std::size_t node_count() const;
  std::size_t link_count() const;
  const NetNode& node(std::size_t i) const;
  Vector3 position(std::size_t i) const;
  Vector3 velocity(std::size_t i) const;  // v_{n-1/2}
  Vector3 unbalanced_force(std::size_t i) const;  // last step, without damping
  Vector3 unbalanced_moment(std::size_t i) const;  // last step, without damping
  const EngineLink& link(std::size_t i) const;
  Vector3 link_direction(std::size_t i) const;  // unit, a -> b
  double link_length(std::size_t i) const;
  // The length link i's law has been advanced to: the positions before the last step's move,
  // so (this - initial length) is the law's axial displacement u exactly.
  double link_law_length(std::size_t i) const;
  // The force link i applied on its node a in the last step (axial and shear; zero once broken);
  // on node b it is the opposite [N].
  Vector3 link_force_on_a(std::size_t i) const;
  std::size_t broken_links() const;
  Tool& tool(std::size_t i);
  const Tool& tool(std::size_t i) const;
  std::size_t tool_count() const;
  // Resultant force of the nodes on tool i (last step) [N] and its moment about the tool centre.
  Vector3 tool_force(std::size_t i) const;
  std::size_t tool_contacts(std::size_t i) const;
  // Roller i (its point moves by its velocity each step), the resultant force of the links on it
  // (last step) [N] and the links it touches.
  Roller& roller(std::size_t i);
  const Roller& roller(std::size_t i) const;
  std::size_t roller_count() const;
  Vector3 roller_force(std::size_t i) const;
  std::size_t roller_contacts(std::size_t i) const;

 private:
  // After a tool or roller is added: the fixed step if one was given, else the stable step.
  void update_time_step_for_new_contact();
  double automatic_time_step() const;  // safety x the bound of the run as it stands
  void check_and_set_step(double dt);   // a given step, checked as set_time_step says
  void refresh_automatic_step();        // after set_support: the automatic step of the new bound
  double stability_bound(bool with_parked_tools, bool held_as_free) const;
  // The step's loops (engine_step.cpp), run inside one parallel region by every thread.
  static constexpr std::size_t link_block = 256;  // links whose kinematics go before their laws
  void link_kinematics(double moved, std::size_t first, std::size_t last);
  void link_laws(std::size_t first, std::size_t last, std::size_t& failed_link, std::string& law_failure);
  void node_tool_contacts(double moved);
  void link_roller_contacts(double moved);
  void contact_sums(bool imposed);  // one thread
  void node_updates(double moved, double spanned, double dt, bool imposed, bool arrest, bool reset);

  struct State;
  std::unique_ptr<State> s_;
  EngineOptions options_;
  double dt_ = 0.0, time_ = 0.0;
  double last_move_ = 0.0;  // the step of the last position update
  long steps_ = 0;
  bool caller_step_ = false;       // set_time_step was called: the step is no longer automatic
  bool supports_changed_ = false;  // set_support since the last step: the automatic step follows
  bool arrest_pending_ = false;    // arrest(): the next step stops the free nodes
  bool reset_pending_ = false;     // the step after an arrest: the move back to the peak, from rest
  double previous_moved_ = 0.0, previous_spanned_ = 0.0;  // the last step's `moved` and `spanned`
  mutable EnergySplit energy_;
  mutable bool energy_stale_ = true;
};

}  // namespace dtwire::dem
