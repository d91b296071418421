// The explicit wire-net engine: building the net, its tools and supports, the stability bound
// and the accessors (engine.hpp; the step itself is in engine_step.cpp; docs/dem_engine.md for the
// energy bookkeeping and the stability bound).
#include "dtwire/dem/engine.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dtwire/dem/wirepm.hpp"
#include "engine_state.hpp"

namespace dtwire::dem {
namespace {

Vector3 initial_transverse(const Vector3& n) {
  Vector3 t = n.cross(Vector3::UnitZ());
  if (t.norm() < 1e-6) t = n.cross(Vector3::UnitX());
  return t.normalized();
}

// Elastic stiffness of a law along each generalised component, probed on a copy.
Vector6 probe_stiffness(const ContactLaw& law) {
  Vector6 k = Vector6::Zero();
  if (const auto* wire = dynamic_cast<const WirePmLaw*>(&law)) {
    k[0] = wire->backbone().unloading_stiffness;
    return k;
  }
  const double delta = 1e-9;
  for (int c = 0; c < 6; ++c) {
    std::unique_ptr<ContactLaw> copy = law.clone();
    const Vector6 before = copy->forces();
    Vector6 increment = Vector6::Zero();
    increment[c] = delta;
    copy->update(increment);
    k[c] = std::abs(copy->forces()[c] - before[c]) / delta;
  }
  return k;
}

}  // namespace

using engine_detail::LinkState;
using engine_detail::RollerState;
using engine_detail::ToolState;

Engine::Engine(std::vector<NetNode> nodes, std::vector<EngineLink> links, EngineOptions options)
    : s_(std::make_unique<State>()), options_(options) {
  if (options_.local_damping < 0.0 || options_.local_damping >= 1.0)
    throw std::invalid_argument("local damping must be in [0, 1)");
  if (!(options_.mass_scale > 0.0)) throw std::invalid_argument("mass scale must be positive");
  if (!(options_.rotational_inertia_scale > 0.0))
    throw std::invalid_argument("rotational inertia scale must be positive");
  if (options_.threads < 1) throw std::invalid_argument("threads must be at least 1");
  State& s = *s_;
  s.nodes = std::move(nodes);
  const std::size_t n = s.nodes.size();
  s.x.resize(n);
  s.v.assign(n, Vector3::Zero());
  s.w.assign(n, Vector3::Zero());
  s.inverse_mass.resize(n);
  s.inverse_inertia.resize(n);
  s.radius.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const NetNode& node = s.nodes[i];
    if (!(node.mass > 0.0) || !(node.rotational_inertia > 0.0) || !(node.radius >= 0.0))
      throw std::invalid_argument("node " + std::to_string(i) + ": mass and rotational inertia must be positive");
    s.x[i] = node.position;
    s.radius[i] = node.radius;
    const bool free = node.fixity == NodeFixity::Free;
    s.inverse_mass[i] = free ? 1.0 / (node.mass * options_.mass_scale) : 0.0;
    s.inverse_inertia[i] = free ? 1.0 / (node.rotational_inertia * options_.mass_scale * options_.rotational_inertia_scale) : 0.0;
    if (node.fixity == NodeFixity::Guided) s.v[i] = node.guided_velocity;
  }
  s.x_previous = s.x;
  s.force.assign(n, Vector3::Zero());
  s.moment.assign(n, Vector3::Zero());
  s.damping_previous.assign(n, Vector3::Zero());
  s.damping_moment_previous.assign(n, Vector3::Zero());
  s.reaction_previous.assign(n, Vector3::Zero());
  s.node_damping_work.assign(n, 0.0);
  s.node_support_work.assign(n, 0.0);
  s.node_gravity_work.assign(n, 0.0);
  s.node_kinetic.assign(n, 0.0);
  s.links = std::move(links);
  s.link_state.resize(s.links.size());
  s.link_load.resize(s.links.size());
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const NetLink& link = s.links[l].link;
    if (link.a < 0 || link.b < 0 || static_cast<std::size_t>(link.a) >= n || static_cast<std::size_t>(link.b) >= n ||
        link.a == link.b)
      throw std::invalid_argument("link " + std::to_string(l) + ": node index out of range");
    if (!s.links[l].law) throw std::invalid_argument("link " + std::to_string(l) + ": no contact law");
    const Vector3 d = s.x[link.b] - s.x[link.a];
    if (!(d.norm() > 0.0)) throw std::invalid_argument("link " + std::to_string(l) + ": zero length");
    s.link_state[l].length = d.norm();
    s.link_state[l].transverse = initial_transverse(d / d.norm());
  }
  // Each node's links in link order (the gather's fixed order).
  s.node_link_start.assign(n + 1, 0);
  for (const EngineLink& link : s.links) {
    ++s.node_link_start[static_cast<std::size_t>(link.link.a) + 1];
    ++s.node_link_start[static_cast<std::size_t>(link.link.b) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) s.node_link_start[i + 1] += s.node_link_start[i];
  s.node_link_entries.resize(s.node_link_start[n]);
  std::vector<std::size_t> filled(s.node_link_start.begin(), s.node_link_start.end() - 1);
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const NetLink& link = s.links[l].link;
    s.node_link_entries[filled[static_cast<std::size_t>(link.a)]++] = {static_cast<int>(l), 0};
    s.node_link_entries[filled[static_cast<std::size_t>(link.b)]++] = {static_cast<int>(l), 1};
  }
  if (options_.time_step > 0.0) check_and_set_step(options_.time_step);
  else dt_ = automatic_time_step();
}

Engine::~Engine() = default;
Engine::Engine(Engine&&) noexcept = default;

int Engine::add_tool(std::unique_ptr<Tool> tool, bool parked) {
  ToolState t;
  t.parked = parked;
  const std::size_t n = s_->nodes.size();
  t.previous_position = tool->position;
  t.tool = std::move(tool);
  t.shear.assign(n, Vector3::Zero());
  t.force_on_node.assign(n, Vector3::Zero());
  t.moment_on_node.assign(n, Vector3::Zero());
  t.contact_point.assign(n, Vector3::Zero());
  t.contact_energy.assign(n, 0.0);
  t.friction_increment.assign(n, 0.0);
  t.touching.assign(n, 0);
  if (t.tool->mass > 0.0) {  // its kinetic energy is given from outside: booked on both sides at once
    const double given = 0.5 * t.tool->mass * t.tool->velocity.squaredNorm() +
                         0.5 * t.tool->rotational_inertia * t.tool->angular_velocity.squaredNorm();
    energy_.boundary_work += given;
    energy_.kinetic += given;
  }
  t.previous_force_on_nodes.setZero();
  s_->tools.push_back(std::move(t));
  update_time_step_for_new_contact();
  return static_cast<int>(s_->tools.size()) - 1;
}

void Engine::update_time_step_for_new_contact() {
  if (options_.time_step > 0.0) check_and_set_step(options_.time_step);
  else if (supports_changed_ && !caller_step_) refresh_automatic_step();
  else dt_ = std::min(dt_, automatic_time_step());
}

int Engine::add_roller(const Roller& roller, std::vector<double> link_radius) {
  const std::size_t links = s_->links.size();
  if (link_radius.size() != links)
    throw std::invalid_argument("roller: " + std::to_string(link_radius.size()) + " link radii for " +
                                std::to_string(links) + " links");
  for (double r : link_radius)
    if (!(r >= 0.0)) throw std::invalid_argument("roller: link radii must be >= 0");
  if (!(roller.radius > 0.0)) throw std::invalid_argument("roller: radius must be > 0");
  if (!(roller.axis.norm() > 0.0)) throw std::invalid_argument("roller: axis must be non-zero");
  RollerState r;
  r.roller = roller;
  r.roller.axis.normalize();
  r.link_radius = std::move(link_radius);
  r.shear.assign(links, Vector3::Zero());
  r.on_a.assign(links, Vector3::Zero());
  r.on_b.assign(links, Vector3::Zero());
  r.contact_energy.assign(links, 0.0);
  r.friction_increment.assign(links, 0.0);
  r.touching.assign(links, 0);
  r.previous_point = roller.point;
  s_->rollers.push_back(std::move(r));
  update_time_step_for_new_contact();
  return static_cast<int>(s_->rollers.size()) - 1;
}

void Engine::place_tool(std::size_t i, const Vector3& position, const Vector3& velocity) {
  ToolState& t = s_->tools.at(i);
  if (t.tool->mass > 0.0) {
    const double given = 0.5 * t.tool->mass * (velocity.squaredNorm() - t.tool->velocity.squaredNorm());
    energy_.boundary_work += given;
    energy_.kinetic += given;
  }
  t.tool->position = position;
  t.previous_position = position;
  t.tool->velocity = velocity;
  if (t.parked) {
    t.parked = false;
    update_time_step_for_new_contact();
  }
}

void Engine::impose_positions(const std::vector<Vector3>& positions) {
  if (positions.size() != s_->x.size()) throw std::invalid_argument("impose_positions: wrong node count");
  if (steps_ != 0) throw std::logic_error("impose_positions: only before the first step");
  s_->x = positions;
  s_->imposed_pending = true;
}

double Engine::critical_time_step() const { return stability_bound(false, false); }

double Engine::automatic_time_step() const { return options_.safety * stability_bound(false, false); }

void Engine::refresh_automatic_step() {
  supports_changed_ = false;
  dt_ = automatic_time_step();
}

double Engine::stability_bound(bool with_parked_tools, bool held_as_free) const {
  const State& s = *s_;
  const std::size_t n = s.nodes.size();
  // The inverse masses of the degrees of freedom that move: a slider node with all three
  // translations (its rotation) held has no translational (rotational) mode, so its springs bound
  // nothing there (the support takes them). held_as_free: every slider component as if released.
  std::vector<double> im(n), ii(n);
  for (std::size_t i = 0; i < n; ++i) {
    const NetNode& node = s.nodes[i];
    const bool translations_held = node.held_translation[0] && node.held_translation[1] && node.held_translation[2];
    im[i] = held_as_free || !translations_held ? s.inverse_mass[i] : 0.0;
    ii[i] = held_as_free || !node.held_rotation ? s.inverse_inertia[i] : 0.0;
  }
  // Upper bound of the largest eigenvalue of M^-1 K: the largest, over nodes, of the sum of the
  // element bounds of the links and tool contacts at that node (docs/dem_engine.md).
  std::vector<double> bound(n, 0.0);
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const NetLink& link = s.links[l].link;
    const Vector6 k = probe_stiffness(*s.links[l].law);
    const double m = im[link.a] + im[link.b];
    const double i = ii[link.a] + ii[link.b];
    const double half = 0.5 * s.link_state[l].length;
    const double element = k[0] * m + std::max(k[1], k[2]) * (m + half * half * i) + std::max({k[3], k[4], k[5]}) * i;
    bound[link.a] += element;
    bound[link.b] += element;
  }
  for (const ToolState& t : s.tools) {
    if (t.parked && !with_parked_tools) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = s.nodes[i].radius;
      bound[i] += t.tool->contact.normal_stiffness * im[i] + t.tool->contact.shear_stiffness * (im[i] + r * r * ii[i]);
    }
  }
  // A roller-link contact at s is the spring kn w w^T with w = ((1 - s), s) (x) normal; its row
  // sums at either node are below kn / m (Gershgorin), as a node-tool contact's.
  for (const RollerState& r : s.rollers)
    for (std::size_t l = 0; l < s.links.size(); ++l) {
      if (!(r.link_radius[l] > 0.0)) continue;
      const double k = r.roller.contact.normal_stiffness + r.roller.contact.shear_stiffness;
      for (int end : {s.links[l].link.a, s.links[l].link.b}) bound[end] += k * im[end];
    }
  const double largest = n == 0 ? 0.0 : *std::max_element(bound.begin(), bound.end());
  return largest > 0.0 ? 2.0 / std::sqrt(largest) : 1.0;
}

void Engine::set_time_step(double dt) {
  check_and_set_step(dt);
  caller_step_ = true;
}

void Engine::check_and_set_step(double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("time step must be positive");
  // A step must stay stable once the parked tools are placed and the slider supports released
  // too: refused now, not later.
  const double critical = stability_bound(true, true);
  if (dt > critical && !options_.allow_above_critical)
    throw std::invalid_argument("time step " + std::to_string(dt) + " s is above the critical step " +
                                std::to_string(critical) + " s");
  dt_ = dt;
}

void Engine::set_guided_velocity(std::size_t i, const Vector3& velocity) {
  NetNode& node = s_->nodes.at(i);
  const bool slider = node.fixity == NodeFixity::Free &&
                      (node.held_translation[0] || node.held_translation[1] || node.held_translation[2]);
  if (node.fixity != NodeFixity::Guided && !slider)
    throw std::invalid_argument("node " + std::to_string(i) + " is neither guided nor on a slider support: its velocity is not prescribed");
  node.guided_velocity = velocity;
}

void Engine::set_support(std::size_t i, const std::array<bool, 3>& held_translation, bool held_rotation) {
  State& s = *s_;
  NetNode& node = s.nodes.at(i);
  if (node.fixity != NodeFixity::Free)
    throw std::invalid_argument("node " + std::to_string(i) + " is not free: its support cannot change");
  for (int c = 0; c < 3; ++c) {
    if (held_translation[c] && !node.held_translation[c]) {
      energy_.boundary_work -= 0.5 * s.v[i][c] * s.v[i][c] / s.inverse_mass[i];
      s.v[i][c] = 0.0;
    }
    node.guided_velocity[c] = 0.0;
  }
  if (held_rotation && !node.held_rotation) {
    energy_.boundary_work -= 0.5 * s.w[i].squaredNorm() / s.inverse_inertia[i];
    s.w[i].setZero();
  }
  node.held_translation = held_translation;
  node.held_rotation = held_rotation;
  supports_changed_ = true;  // the automatic step follows at the next step (the bound is a sweep)
}

void Engine::arrest() { arrest_pending_ = true; }

void Engine::set_local_damping(double alpha) {
  if (!(alpha >= 0.0 && alpha < 1.0)) throw std::invalid_argument("local damping " + std::to_string(alpha) + ": expected a value in [0, 1)");
  options_.local_damping = alpha;
}

std::size_t Engine::node_count() const { return s_->nodes.size(); }
std::size_t Engine::link_count() const { return s_->links.size(); }
const NetNode& Engine::node(std::size_t i) const { return s_->nodes.at(i); }
Vector3 Engine::position(std::size_t i) const { return s_->x.at(i); }
Vector3 Engine::velocity(std::size_t i) const { return s_->v.at(i); }
Vector3 Engine::unbalanced_force(std::size_t i) const { return s_->force.at(i); }
Vector3 Engine::unbalanced_moment(std::size_t i) const { return s_->moment.at(i); }
const EngineLink& Engine::link(std::size_t i) const { return s_->links.at(i); }
Vector3 Engine::link_force_on_a(std::size_t i) const { return s_->link_load.at(i).force_on_a; }
Vector3 Engine::link_direction(std::size_t i) const {
  const NetLink& link = s_->links.at(i).link;
  return (s_->x[link.b] - s_->x[link.a]).normalized();
}
double Engine::link_length(std::size_t i) const {
  const NetLink& link = s_->links.at(i).link;
  return (s_->x[link.b] - s_->x[link.a]).norm();
}
double Engine::link_law_length(std::size_t i) const { return s_->link_state.at(i).length; }
std::size_t Engine::broken_links() const {
  return static_cast<std::size_t>(std::count_if(s_->link_state.begin(), s_->link_state.end(),
                                                [](const LinkState& state) { return state.broken; }));
}
Tool& Engine::tool(std::size_t i) { return *s_->tools.at(i).tool; }
const Tool& Engine::tool(std::size_t i) const { return *s_->tools.at(i).tool; }
std::size_t Engine::tool_count() const { return s_->tools.size(); }
Vector3 Engine::tool_force(std::size_t i) const { return s_->tools.at(i).force_on_tool; }
std::size_t Engine::tool_contacts(std::size_t i) const { return s_->tools.at(i).contacts; }
Roller& Engine::roller(std::size_t i) { return s_->rollers.at(i).roller; }
const Roller& Engine::roller(std::size_t i) const { return s_->rollers.at(i).roller; }
std::size_t Engine::roller_count() const { return s_->rollers.size(); }
Vector3 Engine::roller_force(std::size_t i) const { return s_->rollers.at(i).force_on_roller; }
std::size_t Engine::roller_contacts(std::size_t i) const { return s_->rollers.at(i).contacts; }

}  // namespace dtwire::dem
