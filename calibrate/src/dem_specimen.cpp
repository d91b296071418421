#include "dtwire/calibrate/dem_specimen.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/units.hpp"
#include "dtwire/dem/engine.hpp"
#include "dtwire/dem/law_schema.hpp"
#include "specimen_rollers.hpp"

namespace dtwire::calibrate {
namespace {

using dem::Vector3;
using dem::Vector6;
constexpr double kPi = 3.14159265358979323846;

// Exponent of r = reference_length / link_length by which a parameter scales when the same wire
// is cut to another length: stiffnesses and hardening rates per unit of elongation or rotation
// (elongations and rotations at a given strain and curvature are proportional to the length) x r,
// energies (plastic work at a given strain is proportional to the length) x 1/r. Names not listed
// (forces, the surface's shape exponents, D_m, tolerances) do not depend on the length.
int length_exponent(const std::string& name) {
  static const std::map<std::string, int> exponents = {
      {"EA_N", 1},         {"EI_Nm2_per_deg_convention", 1}, {"k_F", 1},
      {"k_M", 1},          {"axial_stiffness_N_per_m", 1},   {"bending_stiffness_Nm_per_rad", 1},
      {"shear_stiffness_N_per_m", 1}, {"torsion_stiffness_Nm_per_rad", 1}, {"k_F_per_m", 1},
      {"k_M_per_rad", 1},  {"W1_J", -1},                     {"W2_J", -1}};
  const auto found = exponents.find(name);
  return found == exponents.end() ? 0 : found->second;
}

bool has_prefix(const std::string& name, const std::string& prefix) { return name.rfind(prefix, 0) == 0; }

// Elastic stiffness of a law along each generalised component (as the engine probes it).
Vector6 probe_stiffness(const dem::ContactLaw& law) {
  Vector6 k = Vector6::Zero();
  const double delta = 1e-9;
  for (int c = 0; c < 6; ++c) {
    std::unique_ptr<dem::ContactLaw> copy = law.clone();
    const Vector6 before = copy->forces();
    Vector6 increment = Vector6::Zero();
    increment[c] = delta;
    copy->update(increment);
    k[c] = std::abs(copy->forces()[c] - before[c]) / delta;
  }
  return k;
}

std::string describe(double metres) {
  std::ostringstream text;
  text << std::setprecision(6) << metres * 1e3 << " mm";
  return text.str();
}

}  // namespace

void validate(const SpecimenPath& path) {
  if (path.displacement_m.size() < 2) throw std::invalid_argument("specimen path: at least 2 displacement waypoints");
  if (path.displacement_m.front() != 0.0) throw std::invalid_argument("specimen path: the first waypoint must be 0");
  for (double v : path.displacement_m)
    if (!std::isfinite(v)) throw std::invalid_argument("specimen path: waypoints must be finite");
  if (!std::isfinite(path.pull_angle_rad)) throw std::invalid_argument("specimen path: pull angle must be finite");
  if (path.increments_per_leg < 1) throw std::invalid_argument("specimen path: increments per leg >= 1");
}

void validate(const SpecimenGeometry& g) {
  if (!(g.twist_length_m > 0.0) || !(g.arm_length_m > 0.0))
    throw std::invalid_argument("specimen geometry: twist and arm lengths must be > 0");
  if (!(g.arm_angle_rad > 0.0 && g.arm_angle_rad < 0.5 * 3.14159265358979323846))
    throw std::invalid_argument("specimen geometry: arm angle must be in (0, 90) deg");
  if (g.arm_links < 1) throw std::invalid_argument("specimen geometry: arm links >= 1");
}

void validate(const QuasiStaticOptions& o) {
  if (!(o.local_damping >= 0.0 && o.local_damping < 1.0))
    throw std::invalid_argument("quasi-static options: local damping must be in [0, 1)");
  if (o.move_steps < 1) throw std::invalid_argument("quasi-static options: move steps >= 1");
  if (!(o.tolerance > 0.0)) throw std::invalid_argument("quasi-static options: tolerance must be > 0");
  if (o.max_relax_steps < 1) throw std::invalid_argument("quasi-static options: max relax steps >= 1");
  if (!(o.safety > 0.0 && o.safety <= 1.0)) throw std::invalid_argument("quasi-static options: safety must be in (0, 1]");
}

void validate(const RollerRig& r) {
  if (!(r.radius_m > 0.0)) throw std::invalid_argument("roller rig: radius must be > 0");
  for (double z : {r.support_z_m[0], r.support_z_m[1], r.loading_z_m, r.support_tilt_rad})
    if (!std::isfinite(z)) throw std::invalid_argument("roller rig: positions and tilt must be finite");
  if (!(r.support_z_m[0] < r.loading_z_m && r.loading_z_m < r.support_z_m[1]))
    throw std::invalid_argument("roller rig: expected the loading roller between the supports (z1 < z_load < z2)");
  if (!(std::abs(r.support_tilt_rad) < 0.25 * kPi)) throw std::invalid_argument("roller rig: tilt must be within 45 deg");
  if (!(r.friction >= 0.0)) throw std::invalid_argument("roller rig: friction must be >= 0");
  if (!(r.normal_stiffness_N_per_m > 0.0)) throw std::invalid_argument("roller rig: stiffness must be > 0");
  if (!(r.sw_contact_radius_m > 0.0) || !(r.dt_contact_radius_m > 0.0))
    throw std::invalid_argument("roller rig: contact radii must be > 0");
}

dem::ParameterMap scale_to_link_length(const dem::ParameterMap& set, double reference_length, double link_length) {
  if (!(reference_length > 0.0) || !(link_length > 0.0))
    throw std::invalid_argument("reference and link lengths must be > 0");
  const double r = reference_length / link_length;
  dem::ParameterMap out;
  for (const auto& [name, value] : set) out[name] = value * std::pow(r, length_exponent(name));
  out["reference_length_m"] = link_length;
  return out;
}

DemSpecimenSimulator::DemSpecimenSimulator(std::string law, dem::ParameterMap fixed, SpecimenGeometry geometry,
                                           QuasiStaticOptions options, SpecimenPath path, bool scale, RollerRig rig)
    : law_(std::move(law)), fixed_(std::move(fixed)), geometry_(geometry), options_(options), path_(std::move(path)),
      scale_(scale), rig_(rig) {
  if (law_ != "thesis" && law_ != "macro3d")
    throw std::invalid_argument("dem_specimen: law '" + law_ + "' is not supported (expected thesis or macro3d)");
  validate(geometry_);
  validate(options_);
  validate(path_);
  validate(rig_);
  for (const auto& [name, value] : fixed_) {
    const bool sw = has_prefix(name, kSwPrefix), dt = has_prefix(name, kDtPrefix);
    if (!sw && !dt)
      throw std::invalid_argument("dem_specimen: parameter '" + name + "' has no wire-type prefix (sw. or dt.)");
    if (!dem::is_law_parameter(law_, name.substr(3)))
      throw std::invalid_argument("dem_specimen: the " + law_ + " law reads no parameter '" + name.substr(3) + "'");
  }
  if (scale_)
    for (const char* prefix : {kSwPrefix, kDtPrefix}) {
      const auto found = fixed_.find(std::string(prefix) + "reference_length_m");
      if (found == fixed_.end() || !(found->second > 0.0))
        throw std::invalid_argument(std::string("dem_specimen: missing ") + prefix +
                                    "reference_length_m (the length the set was calibrated for, > 0)");
    }
}

Curve DemSpecimenSimulator::simulate(const ParameterValues& parameters) const {
  SpecimenRunInfo info;
  return simulate(parameters, info);
}

Curve DemSpecimenSimulator::simulate(const ParameterValues& parameters, SpecimenRunInfo& info) const {
  // The two sets, unprefixed.
  dem::ParameterMap sets[2];
  const std::string prefixes[2] = {kSwPrefix, kDtPrefix};
  dem::ParameterMap all = fixed_;
  for (const auto& [name, value] : parameters) all[name] = value;
  for (const auto& [name, value] : all) {
    int which = has_prefix(name, prefixes[0]) ? 0 : has_prefix(name, prefixes[1]) ? 1 : -1;
    if (which < 0) throw ComputationError("dem_specimen: parameter '" + name + "' has no sw. or dt. prefix");
    sets[which][name.substr(3)] = value;
  }
  const auto make_law = [&](int which, double length) {
    const dem::ParameterMap& set = sets[which];
    dem::ParameterMap p = set;
    if (scale_) p = scale_to_link_length(set, set.at("reference_length_m"), length);
    try {
      return dem::make_contact_law(law_, p);
    } catch (const std::invalid_argument& error) {
      throw ComputationError(std::string("dem_specimen: the ") + law_ + " law rejected the " +
                             (which == 0 ? "SW" : "DT") + " set: " + error.what());
    }
  };

  // Nodes and links: 0 = J_bot, 1 = J_top, then the arms from the junction outwards.
  const SpecimenGeometry& g = geometry_;
  const double sb = std::sin(g.arm_angle_rad), cb = std::cos(g.arm_angle_rad);
  std::vector<dem::NetNode> nodes(2);
  nodes[0].position = Vector3(0.0, 0.0, 0.0);
  nodes[1].position = Vector3(0.0, 0.0, g.twist_length_m);
  std::vector<dem::EngineLink> links;
  std::vector<double> link_length;
  links.push_back({dem::NetLink{0, 1, dem::LinkTag::DoubleTwist}, make_law(1, g.twist_length_m)});
  link_length.push_back(g.twist_length_m);
  const double segment = g.arm_length_m / g.arm_links;
  std::array<int, 4> grip{}, grip_link{};
  const double side[4] = {1.0, -1.0, 1.0, -1.0}, up[4] = {1.0, 1.0, -1.0, -1.0};
  for (int arm = 0; arm < 4; ++arm) {
    const int junction = up[arm] > 0 ? 1 : 0;
    const Vector3 direction(side[arm] * sb, 0.0, up[arm] * cb);
    int previous = junction;
    for (int i = 1; i <= g.arm_links; ++i) {
      dem::NetNode node;
      node.position = nodes[junction].position + (i * segment) * direction;
      nodes.push_back(node);
      const int index = static_cast<int>(nodes.size()) - 1;
      links.push_back({dem::NetLink{previous, index, dem::LinkTag::SingleWire}, make_law(0, segment)});
      link_length.push_back(segment);
      previous = index;
    }
    grip[arm] = previous;
    grip_link[arm] = static_cast<int>(links.size()) - 1;
    nodes[previous].fixity = dem::NodeFixity::Guided;  // clamped: translation imposed, no spin
  }
  // Bending on rollers: the lower grips guided (x, z, rotations held, free along y), the upper
  // ones free (experiments/dt/dt_bending.prm).
  const bool bending = path_.test == SpecimenTest::ThreePointBending;
  BendingRollers rig;
  if (bending) {
    for (int arm = 0; arm < 4; ++arm) {
      dem::NetNode& node = nodes[grip[arm]];
      node.fixity = dem::NodeFixity::Free;
      if (up[arm] < 0) {
        node.held_translation = {true, false, true};
        node.held_rotation = true;
      }
    }
    std::vector<dem::NetLink> net_links;
    for (const dem::EngineLink& link : links) net_links.push_back(link.link);
    try {
      rig = place_bending_rollers(rig_, nodes, net_links);
    } catch (const std::invalid_argument& error) {
      throw ComputationError(error.what());
    }
  }
  // Density scaling: each node's mass and inertia from the elastic stiffness of its links, so
  // that every node has about the same frequency (pseudo-units; statics do not depend on them).
  std::vector<double> mass(nodes.size(), 0.0), inertia(nodes.size(), 0.0);
  for (std::size_t l = 0; l < links.size(); ++l) {
    const Vector6 k = probe_stiffness(*links[l].law);
    const double half = 0.5 * link_length[l];
    const double shear = std::max(k[1], k[2]);
    const double translational = k[0] + shear;
    const double rotational = std::max({k[3], k[4], k[5]}) + shear * half * half;
    for (int end : {links[l].link.a, links[l].link.b}) {
      mass[end] += translational;
      inertia[end] += rotational;
    }
  }
  // A roller's contact springs count at the nodes of the links it touches.
  for (const std::vector<int>& touched : rig.touched)
    for (int l : touched)
      for (int end : {links[l].link.a, links[l].link.b}) mass[end] += 2.0 * rig_.normal_stiffness_N_per_m;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    nodes[i].mass = mass[i] > 0.0 ? mass[i] : 1.0;
    nodes[i].rotational_inertia = inertia[i] > 0.0 ? inertia[i] : 1.0;
  }

  dem::EngineOptions engine_options;
  engine_options.gravity = Vector3::Zero();
  engine_options.local_damping = options_.local_damping;
  engine_options.safety = options_.safety;
  engine_options.threads = 1;
  dem::Engine engine(nodes, std::move(links), engine_options);
  for (const dem::Roller& roller : rig.rollers) engine.add_roller(roller, rig.link_radius);
  const int loading = 2;  // rig.rollers: supports 0, 1, loading roller 2
  const Vector3 press = -Vector3::UnitY();
  const double dt = engine.time_step();
  info.time_step = dt;

  const Vector3 d(std::sin(path_.pull_angle_rad), 0.0, std::cos(path_.pull_angle_rad));
  const Vector3 v = Vector3::UnitY().cross(d);
  const std::array<int, 2> moved = {grip[0], grip[1]};
  const Vector3 start = bending ? rig.rollers[loading].point : Vector3(0.5 * (nodes[moved[0]].position + nodes[moved[1]].position));
  std::vector<int> free_nodes;
  std::vector<double> free_length;  // shortest link at a free node: moment -> force scale
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].fixity == dem::NodeFixity::Free) {
      free_nodes.push_back(static_cast<int>(i));
      double shortest = 1e300;
      for (std::size_t l = 0; l < engine.link_count(); ++l) {
        const dem::NetLink& link = engine.link(l).link;
        if (link.a == static_cast<int>(i) || link.b == static_cast<int>(i))
          shortest = std::min(shortest, link_length[l]);
      }
      free_length.push_back(shortest);
    }

  std::vector<double> time, displacement, force, shear_force, moment, dt_elongation, dt_axial, dt_shear, dt_moment;
  std::array<std::vector<double>, 2> support_force;
  std::array<std::vector<double>, 4> arm_force;
  // The displacement is the path's (the grips are moved to it exactly, up to round-off).
  const auto record = [&](double t, double grip_displacement) {
    Vector3 f = Vector3::Zero();
    double m = 0.0;
    const Vector3 centre = 0.5 * (engine.position(moved[0]) + engine.position(moved[1]));
    for (int gi : moved) {
      const Vector3 on_specimen = -engine.unbalanced_force(gi);
      f += on_specimen;
      m += ((engine.position(gi) - centre).cross(on_specimen) - engine.unbalanced_moment(gi)).dot(Vector3::UnitY());
    }
    const Vector6 q = engine.link(0).law->forces();
    time.push_back(t);
    displacement.push_back(grip_displacement);
    force.push_back(bending ? engine.roller_force(loading).dot(-press) : f.dot(d));
    for (int k = 0; k < 2; ++k) support_force[k].push_back(bending ? -engine.roller_force(k).y() : 0.0);
    shear_force.push_back(f.dot(v));
    moment.push_back(m);
    dt_elongation.push_back(engine.link_length(0) - g.twist_length_m);
    dt_axial.push_back(q[0]);
    dt_shear.push_back(q[2]);
    dt_moment.push_back(q[4]);
    for (int arm = 0; arm < 4; ++arm) arm_force[arm].push_back(engine.link(grip_link[arm]).law->forces()[0]);
  };
  const auto residual_ratio = [&]() {
    double largest = 0.0;
    for (std::size_t k = 0; k < free_nodes.size(); ++k) {
      const int i = free_nodes[k];
      const dem::NetNode& node = engine.node(i);
      Vector3 f = engine.unbalanced_force(i);  // a held component's is the support's reaction
      for (int c = 0; c < 3; ++c)
        if (node.held_translation[c]) f[c] = 0.0;
      const double m = node.held_rotation ? 0.0 : engine.unbalanced_moment(i).norm();
      largest = std::max(largest, f.norm() + m / free_length[k]);
    }
    double reference = 1.0;  // N
    for (std::size_t l = 0; l < engine.link_count(); ++l)
      reference = std::max(reference, engine.link(l).law->forces().head<3>().norm());
    return largest / reference;
  };

  record(0.0, 0.0);
  const std::string what_moves = bending ? "roller displacement" : "grip displacement";
  const auto& u = path_.displacement_m;
  const int increments = path_.increments_per_leg;
  for (std::size_t leg = 1; leg < u.size(); ++leg)
    for (int i = 1; i <= increments; ++i) {
      const double before = u[leg - 1] + (u[leg] - u[leg - 1]) * (i - 1) / increments;
      const double after = u[leg - 1] + (u[leg] - u[leg - 1]) * static_cast<double>(i) / increments;
      // Smooth velocity profile (1 - cos) over the move steps: its weights sum to 1, and a start
      // and stop without a jump in velocity excite the net far less than a constant velocity.
      const int n_move = options_.move_steps;
      for (int s = 0; s < n_move; ++s) {
        const double weight = n_move == 1 ? 1.0 : (1.0 - std::cos(2.0 * kPi * (s + 0.5) / n_move)) / n_move;
        const double speed = (after - before) * weight / dt;
        if (bending) engine.roller(loading).velocity = speed * press;
        else
          for (int gi : moved) engine.set_guided_velocity(static_cast<std::size_t>(gi), speed * d);
        engine.step();
      }
      if (bending) engine.roller(loading).velocity.setZero();
      else
        for (int gi : moved) engine.set_guided_velocity(static_cast<std::size_t>(gi), Vector3::Zero());
      long relax = 0;
      double ratio = 0.0;
      for (;;) {
        engine.step();
        ++relax;
        ratio = residual_ratio();
        if (ratio <= options_.tolerance) break;
        if (relax >= options_.max_relax_steps)
          throw ComputationError("dem_specimen: not converged at " + what_moves + " " + describe(after) + " (leg " +
                                 std::to_string(leg) + ", increment " + std::to_string(i) + "): unbalanced force " +
                                 format_number(ratio) + " of the largest link force after " +
                                 std::to_string(relax) + " steps (tolerance " + format_number(options_.tolerance) + ")");
      }
      info.largest_relax_steps = std::max(info.largest_relax_steps, relax);
      if (engine.broken_links() > 0)
        throw ComputationError("dem_specimen: the specimen broke (" + std::to_string(engine.broken_links()) +
                               " link(s)) at " + what_moves + " " + describe(after) + ", before the path's end");
      const double moved_by = bending ? (engine.roller(loading).point - start).dot(press)
                                      : (0.5 * (engine.position(moved[0]) + engine.position(moved[1])) - start).dot(d);
      if (!(std::abs(moved_by - after) <= 1e-9 * (std::abs(after) + 1e-3)))
        throw ComputationError(std::string("dem_specimen: the ") + (bending ? "loading roller is" : "grips are") +
                               " at " + describe(moved_by) + " instead of " + describe(after));
      record(static_cast<double>(leg - 1) + static_cast<double>(i) / increments, after);
    }
  info.steps = engine.steps_taken();

  Curve curve;
  const auto add = [&](const char* name, Dimension dimension, const std::vector<double>& values) {
    for (double x : values)
      if (!std::isfinite(x)) throw ComputationError(std::string("dem_specimen: non-finite ") + name);
    curve.add_channel_si(name, dimension, values, si_unit(dimension));
  };
  add("time", Dimension::Time, time);
  add("displacement", Dimension::Length, displacement);
  add("force", Dimension::Force, force);
  add("support1_force", Dimension::Force, support_force[0]);
  add("support2_force", Dimension::Force, support_force[1]);
  add("shear_force", Dimension::Force, shear_force);
  add("moment", Dimension::Moment, moment);
  add("dt_elongation", Dimension::Length, dt_elongation);
  add("dt_axial_force", Dimension::Force, dt_axial);
  add("dt_shear_force", Dimension::Force, dt_shear);
  add("dt_moment", Dimension::Moment, dt_moment);
  const char* arm_names[4] = {"arm1_force", "arm2_force", "arm3_force", "arm4_force"};
  for (int arm = 0; arm < 4; ++arm) add(arm_names[arm], Dimension::Force, arm_force[arm]);
  return curve;
}

std::string DemSpecimenSimulator::identity() const {
  std::string text = "dem_specimen law=" + law_ + " scale_to_link_length=" + (scale_ ? "1" : "0");
  text += "\ngeometry: twist=" + format_number(geometry_.twist_length_m) + " arm=" + format_number(geometry_.arm_length_m) +
          " angle=" + format_number(geometry_.arm_angle_rad) + " arm_links=" + std::to_string(geometry_.arm_links);
  text += "\nquasi_static: damping=" + format_number(options_.local_damping) +
          " move_steps=" + std::to_string(options_.move_steps) + " tolerance=" + format_number(options_.tolerance) +
          " max_relax_steps=" + std::to_string(options_.max_relax_steps) + " safety=" + format_number(options_.safety);
  text += "\nfixed:";
  for (const auto& [name, value] : fixed_) text += " " + name + "=" + format_number(value);
  if (path_.test == SpecimenTest::ThreePointBending)
    text += "\nrollers: radius=" + format_number(rig_.radius_m) + " supports=" + format_number(rig_.support_z_m[0]) + "," +
            format_number(rig_.support_z_m[1]) + " loading=" + format_number(rig_.loading_z_m) +
            " tilt=" + format_number(rig_.support_tilt_rad) + " friction=" + format_number(rig_.friction) +
            " stiffness=" + format_number(rig_.normal_stiffness_N_per_m) + " radii=" +
            format_number(rig_.sw_contact_radius_m) + "," + format_number(rig_.dt_contact_radius_m);
  text += "\npath: " + std::string(path_.test == SpecimenTest::ThreePointBending ? "test=bending " : "") +
          "angle=" + format_number(path_.pull_angle_rad) + " increments=" + std::to_string(path_.increments_per_leg);
  for (double x : path_.displacement_m) text += " " + format_number(x);
  return text;
}

std::vector<std::pair<std::string, Dimension>> DemSpecimenSimulator::channels() const {
  return {{"time", Dimension::Time},          {"displacement", Dimension::Length},
          {"force", Dimension::Force},        {"support1_force", Dimension::Force},
          {"support2_force", Dimension::Force}, {"shear_force", Dimension::Force},
          {"moment", Dimension::Moment},      {"dt_elongation", Dimension::Length},
          {"dt_axial_force", Dimension::Force}, {"dt_shear_force", Dimension::Force},
          {"dt_moment", Dimension::Moment},   {"arm1_force", Dimension::Force},
          {"arm2_force", Dimension::Force},   {"arm3_force", Dimension::Force},
          {"arm4_force", Dimension::Force}};
}

std::vector<std::string> DemSpecimenSimulator::parameter_names() const {
  std::vector<std::string> names;
  for (const char* prefix : {kSwPrefix, kDtPrefix})
    for (const std::string& name : dem::law_parameter_names(law_)) names.push_back(prefix + name);
  return names;
}

}  // namespace dtwire::calibrate
