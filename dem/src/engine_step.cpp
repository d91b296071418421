// The engine's step (engine.hpp, steps 1-3), its relaxation and its energy sums
// (docs/dem_engine.md: the energy bookkeeping).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "dtwire/dem/engine.hpp"
#include "engine_state.hpp"

namespace dtwire::dem {
namespace {

// Without branches: the signs of the damping's products are random from node to node, and a
// mispredicted branch per component made the sign a third of the node loop (perf, the punch).
double sign(double x) { return static_cast<double>((x > 0.0) - (x < 0.0)); }

// YADE's second-order local damping on one vector quantity (force or moment): each component
// is reduced or amplified by alpha depending on whether it accelerates the predicted motion.
Vector3 damping_force(const Vector3& force, const Vector3& velocity, double inverse_inertia, double dt,
                      double alpha) {
  Vector3 damped;
  for (int i = 0; i < 3; ++i)
    damped[i] = -alpha * force[i] * sign(force[i] * (velocity[i] + 0.5 * dt * force[i] * inverse_inertia));
  return damped;
}

// The velocity of a free node after its held components are set to the support's velocity
// (slider supports: zero, or the support's prescribed motion, e.g. edges pulled apart).
void hold(const NetNode& node, Vector3& v, Vector3& w) {
  for (int c = 0; c < 3; ++c)
    if (node.held_translation[c]) v[c] = node.guided_velocity[c];
  if (node.held_rotation) w.setZero();
}

// The components of a vector a node's slider support leaves free.
Vector3 free_components(const NetNode& node, const Vector3& v) {
  Vector3 out = v;
  for (int c = 0; c < 3; ++c)
    if (node.held_translation[c]) out[c] = 0.0;
  return out;
}

}  // namespace

using engine_detail::LinkLoad;
using engine_detail::LinkState;
using engine_detail::NodeLinkEntry;
using engine_detail::RollerState;
using engine_detail::ToolState;

void Engine::step() {
  State& s = *s_;
  if (supports_changed_ && options_.time_step <= 0.0 && !caller_step_) refresh_automatic_step();
  // Variable-step central differences: the last move x_{n-1} -> x_n took `moved` (the link and
  // contact increments are over it), the next takes dt, and the velocity update spans their mean
  // (v_{n+1/2} = v_{n-1/2} + (moved + dt)/2 a_n); with a constant step all three are dt.
  const double dt = dt_;
  const double moved = steps_ == 0 ? dt : last_move_;
  const double spanned = 0.5 * (moved + dt);
  const std::size_t n = s.nodes.size();
  const std::size_t links = s.links.size();
  const int threads = options_.threads;
  const bool imposed = s.imposed_pending;
  // The step after an arrest ends the move back to the peak (reset); an arrest asked for then
  // waits a step.
  const bool reset = reset_pending_;
  const bool arrest = arrest_pending_ && !reset;
  if (arrest) arrest_pending_ = false;
  reset_pending_ = arrest;

  // One parallel region a step: the links, tools and rollers, a serial sum of the contacts, then
  // the nodes. Each loop writes only its own slots; every sum over links or nodes runs on one
  // thread in a fixed order, so 1 and N threads give bit-identical results. A region's team start
  // and end, and the serial stretches where the other threads spin, cost more than a loop on a
  // 2-core machine (docs/dem_engine.md, "Speed"). Below parallel_threshold (or on one thread)
  // the same worksharing loops run orphaned on the calling thread, without entering a region.
  // A law that gives up (an exception) must not leave the region, where it would terminate the
  // process: the first one is kept with its link, the rest of the step is skipped, and it is
  // thrown after the region.
  std::string law_failure;
  std::size_t failed_link = links;
  // Links go in blocks, a block's kinematics first, then its laws: a law update is an opaque
  // call, and between two of them the square roots and divisions of one link's frame cannot
  // overlap another's. Every loop is statically scheduled: a thread keeps the same nodes and,
  // with the mesh's numbering, much the same links step after step, in its own core's cache
  // (handing blocks out dynamically balanced the threads better but made the links' reads of the
  // nodes cross between the cores: no faster, bench_dem_punch_macro).
  const std::size_t blocks = (links + link_block - 1) / link_block;
  const auto step_loops = [&] {
    node_tool_contacts(moved);  // no barrier: the links read only positions and velocities
#pragma omp for schedule(static)
    for (std::size_t block = 0; block < blocks; ++block) {
      const std::size_t first = block * link_block, last = std::min(links, first + link_block);
      link_kinematics(moved, first, last);
      link_laws(first, last, failed_link, law_failure);
    }  // a barrier: every link's load is in place
    if (failed_link < links) return;
    link_roller_contacts(moved);  // needs the laws' broken flags
#pragma omp single
    contact_sums(imposed);
    node_updates(moved, spanned, dt, imposed, arrest, reset);
  };
  if (threads > 1 && std::max(n, links) >= options_.parallel_threshold) {
#pragma omp parallel num_threads(threads)
    step_loops();
  } else {
    step_loops();
  }
  if (failed_link < links)
    throw std::runtime_error("link " + std::to_string(failed_link) + " (nodes " +
                             std::to_string(s.links[failed_link].link.a) + "-" +
                             std::to_string(s.links[failed_link].link.b) + ") at step " +
                             std::to_string(steps_) + ": " + law_failure);

  // Serial sums (fixed order: deterministic).
  double kinetic = 0.0, gravity_work = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    kinetic += s.node_kinetic[i];
    if (s.nodes[i].fixity == NodeFixity::Free) {
      energy_.damping += s.node_damping_work[i];
      energy_.boundary_work += s.node_support_work[i];
      gravity_work += s.node_gravity_work[i];
    } else {
      energy_.boundary_work += s.node_damping_work[i];
    }
  }
  energy_.gravity_work += gravity_work;
  // The stored energies are state functions: summed when energy() is read, not every step.
  energy_stale_ = true;
  if (imposed) {
    const EnergySplit& stored = energy();  // the links were unloaded before the jump
    energy_.boundary_work += stored.link_elastic + stored.link_plastic + stored.link_damage;
  }

  // Rigid tools: free bodies integrate their own motion, kinematic ones move as prescribed.
  const Vector3 gravity = options_.gravity;
  for (ToolState& t : s.tools) {
    if (t.parked) continue;
    Tool& tool = *t.tool;
    if (tool.mass > 0.0) {
      const Vector3 weight = tool.mass * gravity;
      if (!imposed) energy_.gravity_work += weight.dot(tool.position - t.previous_position);
      const Vector3 v_old = tool.velocity, w_old = tool.angular_velocity;
      tool.velocity += spanned * (t.force_on_tool + weight) / tool.mass;
      tool.angular_velocity += spanned * t.moment_on_tool / tool.rotational_inertia;
      kinetic += 0.5 * tool.mass * v_old.dot(tool.velocity) +
                 0.5 * tool.rotational_inertia * w_old.dot(tool.angular_velocity);
    }
    t.previous_position = tool.position;
    tool.position += dt * tool.velocity;
    const double angle = dt * tool.angular_velocity.norm();
    if (angle > 0.0)
      tool.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, tool.angular_velocity.normalized())) * tool.orientation;
    tool.orientation.normalize();
  }
  for (RollerState& r : s.rollers) {
    r.previous_point = r.roller.point;
    r.roller.point += dt * r.roller.velocity;
  }
  energy_.kinetic = kinetic;
  s.imposed_pending = false;
  time_ += dt;
  last_move_ = dt;
  previous_moved_ = moved;
  previous_spanned_ = spanned;
  ++steps_;
}

// 1a. Links [first, last): each one's frame and the increments of its six generalised
// displacements.
void Engine::link_kinematics(double moved, std::size_t first, std::size_t last) {
  State& s = *s_;
  for (std::size_t l = first; l < last; ++l) {
    LinkState& state = s.link_state[l];
    const NetLink& link = s.links[l].link;
    const Vector3 d = s.x[link.b] - s.x[link.a];
    const double length = d.norm();
    const Vector3 axis = d / length;
    Vector3 t1 = state.transverse - state.transverse.dot(axis) * axis;
    t1.normalize();
    const Vector3 t2 = axis.cross(t1);
    const double half = 0.5 * length;
    const Vector3 relative = (s.v[link.b] - half * s.w[link.b].cross(axis)) - (s.v[link.a] + half * s.w[link.a].cross(axis));
    const Vector3 spin = s.w[link.b] - s.w[link.a];
    state.increment << length - state.length, moved * relative.dot(t1), moved * relative.dot(t2),
        moved * spin.dot(axis), moved * spin.dot(t1), moved * spin.dot(t2);
    if (s.imposed_pending) state.increment.tail<5>().setZero();
    state.length = length;
    state.axis = axis;
    state.transverse = t1;
    state.binormal = t2;
  }
}

// 1b. Links [first, last): the laws and the loads each link puts on its nodes.
void Engine::link_laws(std::size_t first, std::size_t last, std::size_t& failed_link, std::string& law_failure) {
  State& s = *s_;
  for (std::size_t l = first; l < last; ++l) {
    LinkState& state = s.link_state[l];
    ContactLaw& law = *s.links[l].law;
    if (!state.broken) {
      try {
        law.update(state.increment);
      } catch (const std::exception& e) {
#pragma omp critical(dtwire_dem_law_failure)
        if (l < failed_link) {
          failed_link = l;
          law_failure = e.what();
        }
        continue;
      }
    }
    state.broken = law.broken();
    const Vector6 q = state.broken ? Vector6::Zero() : law.forces();
    const Vector3& axis = state.axis;
    const Vector3& t1 = state.transverse;
    const Vector3& t2 = state.binormal;
    const double half = 0.5 * state.length;
    const Vector3 couple = q[3] * axis + q[4] * t1 + q[5] * t2;
    // The shear's lever: axis x (q1 t1 + q2 t2) = q1 t2 - q2 t1 (a right-handed frame).
    const Vector3 lever = half * (q[1] * t2 - q[2] * t1);
    LinkLoad& load = s.link_load[l];
    load.force_on_a = q[0] * axis + q[1] * t1 + q[2] * t2;
    load.moment[0] = couple + lever;
    load.moment[1] = -couple + lever;
  }
}

// 2. Tools: every node against every tool (each node writes its own slot); no barrier (the
// links' loop that follows ends with one).
void Engine::node_tool_contacts(double moved) {
  State& s = *s_;
  const std::size_t n = s.nodes.size();
  for (ToolState& t : s.tools) {
    if (t.parked) continue;  // its contact arrays stay zero
    const Tool& tool = *t.tool;
    const double kn = tool.contact.normal_stiffness, ks = tool.contact.shear_stiffness, mu = tool.contact.friction;
    const double bounding = tool.bounding_radius();
#pragma omp for schedule(static) nowait
    for (std::size_t i = 0; i < n; ++i) {
      const double r = s.radius[i];
      SurfacePoint surface;
      // Most nodes are far from the tool: its bounding sphere rejects them before the surface search.
      const double reach = bounding + r;
      if ((s.x[i] - tool.position).squaredNorm() > reach * reach || !tool.nearest(s.x[i], r, surface) ||
          surface.distance >= r) {
        // A node's contact slots are zero while it is apart: written only when a contact ends
        // (most nodes touch no tool, and the step is bound by memory traffic).
        if (t.touching[i]) {
          t.force_on_node[i].setZero();
          t.moment_on_node[i].setZero();
          t.contact_energy[i] = 0.0;
          t.friction_increment[i] = 0.0;
          t.shear[i].setZero();
          t.touching[i] = 0;
        }
        continue;
      }
      t.touching[i] = 1;
      t.friction_increment[i] = 0.0;
      const double penetration = r - surface.distance;
      const Vector3& normal = surface.normal;
      const Vector3 arm = -(r - 0.5 * penetration) * normal;  // node centre -> contact point
      const Vector3 point = s.x[i] + arm;
      const Vector3 slip_velocity = s.v[i] + s.w[i].cross(arm) - tool.velocity -
                                    tool.angular_velocity.cross(point - tool.position);
      const Vector3 tangential = slip_velocity - slip_velocity.dot(normal) * normal;
      Vector3 shear = t.shear[i] - t.shear[i].dot(normal) * normal;
      const double kept = t.shear[i].norm();
      if (shear.norm() > 0.0) shear *= kept / shear.norm();
      shear -= ks * moved * tangential;
      const double normal_force = kn * penetration;
      const double limit = mu * normal_force;
      const double trial = shear.norm();
      if (trial > limit) {
        t.friction_increment[i] = limit * (trial - limit) / ks;
        shear *= trial > 0.0 ? limit / trial : 0.0;
      }
      t.shear[i] = shear;
      t.force_on_node[i] = normal_force * normal + shear;
      t.moment_on_node[i] = arm.cross(shear);
      t.contact_point[i] = point;
      t.contact_energy[i] = 0.5 * normal_force * normal_force / kn + 0.5 * shear.squaredNorm() / ks;
    }
  }
}

// Rollers: every link against every roller (each link writes its own slot); ends with a barrier.
void Engine::link_roller_contacts(double moved) {
  State& s = *s_;
  const std::size_t links = s.links.size();
  for (RollerState& r : s.rollers) {
#pragma omp for schedule(static)
    for (std::size_t l = 0; l < links; ++l) {
      const NetLink& link = s.links[l].link;
      r.on_a[l].setZero();
      r.on_b[l].setZero();
      r.contact_energy[l] = 0.0;
      r.friction_increment[l] = 0.0;
      r.touching[l] = 0;
      if (!(r.link_radius[l] > 0.0) || s.link_state[l].broken) {
        r.shear[l].setZero();
        continue;
      }
      const SegmentContact c = roller_segment_contact(r.roller, s.x[link.a], s.x[link.b], r.link_radius[l],
                                                      s.v[link.a], s.v[link.b], moved, r.shear[l]);
      if (!c.touching) continue;
      r.touching[l] = 1;
      r.on_a[l] = c.on_a;
      r.on_b[l] = c.on_b;
      r.contact_energy[l] = c.elastic_energy;
      r.friction_increment[l] = c.friction_work;
    }
  }
}

// The tools' and rollers' resultants, contact counts and works over x_{n-1} -> x_n (none for an
// imposed jump: its work is in the links); one thread, fixed order.
void Engine::contact_sums(bool imposed) {
  State& s = *s_;
  const std::size_t n = s.nodes.size();
  const std::size_t links = s.links.size();
  for (RollerState& r : s.rollers) {
    Vector3 on_links = Vector3::Zero();
    std::size_t contacts = 0;
    for (std::size_t l = 0; l < links; ++l) {
      if (!r.touching[l]) continue;
      ++contacts;
      on_links += r.on_a[l] + r.on_b[l];
      energy_.friction += r.friction_increment[l];
    }
    r.contacts = contacts;
    if (!imposed) energy_.tool_work += 0.5 * (r.previous_force_on_links + on_links).dot(r.roller.point - r.previous_point);
    r.previous_force_on_links = on_links;
    r.force_on_roller = -on_links;
  }
  for (ToolState& t : s.tools) {
    Vector3 on_nodes = Vector3::Zero(), on_tool_moment = Vector3::Zero();
    std::size_t contacts = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!t.touching[i]) continue;
      ++contacts;
      on_nodes += t.force_on_node[i];
      on_tool_moment += (t.contact_point[i] - t.tool->position).cross(-t.force_on_node[i]);
      energy_.friction += t.friction_increment[i];
    }
    t.contacts = contacts;
    if (t.tool->mass <= 0.0 && !imposed)
      energy_.tool_work += 0.5 * (t.previous_force_on_nodes + on_nodes).dot(t.tool->position - t.previous_position);
    t.previous_force_on_nodes = on_nodes;
    t.force_on_tool = -on_nodes;
    t.moment_on_tool = on_tool_moment;
  }
}

// 3. Nodes: gather in a fixed order, damp, integrate, move (free nodes by their velocity, guided
// ones at their prescribed one). Each node's works go to its own slots, summed after the region.
void Engine::node_updates(double moved, double spanned, double dt, bool imposed, bool arrest, bool reset) {
  State& s = *s_;
  const std::size_t n = s.nodes.size();
  const Vector3 gravity = options_.gravity;
  const double alpha = options_.local_damping;
#pragma omp for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const NetNode& node = s.nodes[i];
    Vector3 f = node.mass * gravity, m = Vector3::Zero();
    const std::size_t first = s.node_link_start[i], last = s.node_link_start[i + 1];
    for (std::size_t k = first; k < last; ++k) {
      const NodeLinkEntry entry = s.node_link_entries[k];
      const LinkLoad& load = s.link_load[static_cast<std::size_t>(entry.link)];
      // (-1) x force is -force bit for bit: end b takes the opposite of end a's force.
      f += (1.0 - 2.0 * entry.end) * load.force_on_a;
      m += load.moment[static_cast<std::size_t>(entry.end)];
    }
    for (const ToolState& t : s.tools) {
      if (!t.touching[i]) continue;  // its slots are zero
      f += t.force_on_node[i];
      m += t.moment_on_node[i];
    }
    for (const RollerState& r : s.rollers)
      for (std::size_t k = first; k < last; ++k) {
        const NodeLinkEntry entry = s.node_link_entries[k];
        const auto l = static_cast<std::size_t>(entry.link);
        f += entry.end == 0 ? r.on_a[l] : r.on_b[l];
      }
    // An arrest (kinetic damping) needs step n's forces to recover v_{n-1/2}; the move back after
    // it, the forces at its start to book their work.
    Vector3 f_before = Vector3::Zero(), m_before = Vector3::Zero(), fd_before = Vector3::Zero(), md_before = Vector3::Zero();
    if (arrest || reset) {
      f_before = s.force[i];
      m_before = s.moment[i];
      fd_before = s.damping_previous[i];
      md_before = s.damping_moment_previous[i];
    }
    s.force[i] = f;
    s.moment[i] = m;
    const Vector3 dx = imposed ? Vector3::Zero() : Vector3(s.x[i] - s.x_previous[i]);
    if (node.fixity != NodeFixity::Free) {
      // The support supplies -f (held) or whatever keeps the prescribed velocity: its work.
      s.node_damping_work[i] = 0.5 * (s.reaction_previous[i] - f).dot(dx);
      s.reaction_previous[i] = -f;
      s.node_kinetic[i] = node.fixity == NodeFixity::Guided ? 0.5 * node.mass * options_.mass_scale * s.v[i].squaredNorm() : 0.0;
      s.x_previous[i] = s.x[i];
      if (node.fixity == NodeFixity::Guided) {
        s.v[i] = node.guided_velocity;
        s.x[i] += dt * s.v[i];
      }
      continue;
    }
    s.node_gravity_work[i] = node.mass * gravity.dot(dx);
    // A slider support takes the held components: its reaction -f does the support's work (its
    // velocity may be prescribed), and nothing there is damped or counted as kinetic energy.
    const Vector3 reaction = free_components(node, f) - f;
    s.node_support_work[i] = 0.5 * (s.reaction_previous[i] + reaction).dot(dx);
    s.reaction_previous[i] = reaction;
    const Vector3 dtheta = imposed ? Vector3::Zero() : Vector3(moved * s.w[i]);
    if (reset) {
      // The move back to the peak is over (x_{n+1} -> x*, made by the arrest step's velocities):
      // the node starts from rest, and the work of every force over that move, which no kinetic
      // energy took up, is dissipated (trapezoidal, as every work here).
      s.v[i] -= free_components(node, s.v[i]);
      s.w[i].setZero();
    }
    const Vector3 fd = free_components(node, damping_force(f, s.v[i], s.inverse_mass[i], spanned, alpha));
    const Vector3 md = damping_force(m, s.w[i], s.inverse_inertia[i], spanned, alpha);
    s.node_damping_work[i] = reset ? 0.5 * free_components(node, f_before + f).dot(dx) + 0.5 * (m_before + m).dot(dtheta)
                                   : -(0.5 * (s.damping_previous[i] + fd).dot(dx) +
                                       0.5 * (s.damping_moment_previous[i] + md).dot(dtheta));
    s.damping_previous[i] = fd;
    s.damping_moment_previous[i] = md;
    const Vector3 v_old = s.v[i], w_old = s.w[i];
    s.v[i] += spanned * (f + fd) * s.inverse_mass[i];
    s.w[i] += spanned * (m + md) * s.inverse_inertia[i];
    hold(node, s.v[i], s.w[i]);
    s.node_kinetic[i] = 0.5 * free_components(node, v_old).dot(s.v[i]) / s.inverse_mass[i] +
                        0.5 * w_old.dot(s.w[i]) / s.inverse_inertia[i];
    if (arrest) {
      // Kinetic damping: the kinetic energy this step would leave (the synchronised form, so the
      // balance stays exact) is dissipated, and the node moves back to the peak of the kinetic
      // energy, Barnes's (1999, Int. J. Space Struct. 14(2) 89-104, eq. for the reset geometry)
      // x* = x_n - dt v_{n-1/2} / 2, with x_n = x_{n+1} - moved v_{n+1/2} and v_{n-1/2} from step
      // n's forces; the spins alike. The next step starts it from rest there (reset).
      s.node_damping_work[i] += s.node_kinetic[i];
      s.node_kinetic[i] = 0.0;
      const Vector3 v_before = v_old - previous_spanned_ * (f_before + fd_before) * s.inverse_mass[i];
      const Vector3 w_before = w_old - previous_spanned_ * (m_before + md_before) * s.inverse_inertia[i];
      s.v[i] = free_components(node, -(moved * v_old + 0.5 * previous_moved_ * v_before) / dt);
      s.w[i] = -(moved * w_old + 0.5 * previous_moved_ * w_before) / dt;
      hold(node, s.v[i], s.w[i]);
    }
    s.x_previous[i] = s.x[i];
    s.x[i] += dt * s.v[i];
  }
}

RelaxResult Engine::relax(double tolerance, long max_steps) {
  RelaxResult result;
  std::vector<Vector3> held;
  for (ToolState& t : s_->tools) {
    held.push_back(t.tool->velocity);
    if (t.tool->mass <= 0.0) t.tool->velocity.setZero();
  }
  for (long k = 0; k < max_steps; ++k) {
    step();
    ++result.steps;
    if (k % 10 != 9) continue;
    double largest = 0.0, mean = 0.0;
    for (std::size_t i = 0; i < s_->nodes.size(); ++i)
      if (s_->nodes[i].fixity == NodeFixity::Free) {
        Vector3 f = s_->force[i], unused = Vector3::Zero();
        hold(s_->nodes[i], f, unused);  // a held component's force is the support's
        largest = std::max(largest, f.norm());
      }
    for (const LinkLoad& load : s_->link_load) mean += load.force_on_a.norm();
    mean = s_->link_state.empty() ? 1.0 : mean / static_cast<double>(s_->link_state.size());
    result.force_ratio = mean > 0.0 ? largest / mean : largest;
    if (result.force_ratio < tolerance) {
      result.converged = true;
      break;
    }
  }
  for (std::size_t j = 0; j < s_->tools.size(); ++j) s_->tools[j].tool->velocity = held[j];
  return result;
}

double Engine::unbalanced_force_ratio() const {
  const State& s = *s_;
  double unbalanced = 0.0, link_force = 0.0;
  std::size_t free_nodes = 0;
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    if (s.nodes[i].fixity != NodeFixity::Free) continue;
    Vector3 f = s.force[i], unused = Vector3::Zero();
    hold(s.nodes[i], f, unused);  // a held component's force is the support's
    unbalanced += f.norm();
    ++free_nodes;
  }
  // The interactions are YADE's: every link and every contact of a node or a link with a tool
  // or roller (a net lying on a wall carries its weight through the wall's contacts, not its links).
  double interaction_force = 0.0;
  std::size_t interactions = s.link_load.size();
  for (const LinkLoad& load : s.link_load) interaction_force += load.force_on_a.norm();
  for (const ToolState& t : s.tools) {
    if (t.parked) continue;
    for (std::size_t i = 0; i < t.touching.size(); ++i)
      if (t.touching[i]) {
        interaction_force += t.force_on_node[i].norm();
        ++interactions;
      }
  }
  for (const RollerState& r : s.rollers)
    for (std::size_t l = 0; l < r.touching.size(); ++l)
      if (r.touching[l]) {
        interaction_force += (r.on_a[l] + r.on_b[l]).norm();
        ++interactions;
      }
  if (free_nodes == 0) return 0.0;
  if (interactions == 0 || !(interaction_force > 0.0)) return std::numeric_limits<double>::infinity();
  return (unbalanced / static_cast<double>(free_nodes)) / (interaction_force / static_cast<double>(interactions));
}

const EnergySplit& Engine::energy() const {
  if (!energy_stale_) return energy_;
  const State& s = *s_;
  double elastic = 0.0, plastic = 0.0, damage = 0.0;
  for (const EngineLink& link : s.links) {  // fixed order: deterministic
    const EnergyAccount e = link.law->energy();
    elastic += e.elastic;
    plastic += e.plastic;
    damage += e.damage;
  }
  energy_.link_elastic = elastic;
  energy_.link_plastic = plastic;
  energy_.link_damage = damage;
  double contact = 0.0;
  for (const ToolState& t : s.tools)
    for (double e : t.contact_energy) contact += e;
  for (const RollerState& r : s.rollers)
    for (double e : r.contact_energy) contact += e;
  energy_.contact_elastic = contact;
  energy_stale_ = false;
  return energy_;
}

}  // namespace dtwire::dem
