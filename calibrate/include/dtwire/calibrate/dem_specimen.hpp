#pragma once
// `dem_specimen`: a laboratory double-twist (DT) specimen assembled in the DEM engine (dem/) and
// loaded quasi-statically through its grips, so that `dtwire fit` can fit the single-wire (SW)
// and the DT parameter sets of a contact law JOINTLY to whole-specimen curves (FE virtual
// experiments or laboratory tests) as well as to link-level ones. docs/calibrate.md.
//
// Geometry (docs/meshes.md, the FE DT mesh): the twist from J_bot = (0, 0, 0) to
// J_top = (0, 0, twist_length) is ONE DT link; from each junction the two wires leave as SW arms
// of axis length arm_length in the mesh plane x-z, upper arms along (+-sin beta, 0, cos beta)
// from J_top, lower ones along (+-sin beta, 0, -cos beta) from J_bot (beta = arm angle), each
// arm arm_links SW links. The arm ends are grips (guided nodes: translations imposed, rotations
// held, i.e. clamped). Lower grips held; the upper grips move together along the pull
// direction d = (sin a, 0, cos a) by the path's grip displacement (a = 0: tension).
//
// Three-point bending on rollers (SpecimenTest::ThreePointBending; the FE's
// experiments/dt/dt_bending.prm): rigid cylinders of radius R, two supports under the arms at
// z = support_z (axes along x, turned by support_tilt about z) and the loading roller above the
// twist at z = loading_z, pressed along -y (normal to the mesh plane) by the path's displacement.
// Each roller starts touching the nearest link (wire radius sw_/dt_contact_radius) and acts on
// the links' axis segments (dem/include/dtwire/dem/roller.hpp: penalty, Coulomb friction, lever
// rule): the specimen's nodes are only at link ends, so the loading roller presses the DT link
// between its nodes and the supports the one-link arms. The lower grips are guided (x, z and
// rotations held, free along y), the upper grips free, as in the FE run. Limits: a one-link arm
// is straight and cannot wrap a roller; the twist's section is a circle of radius
// dt_contact_radius (the FE twist's envelope turns along its length).
//
// Parameters carry the wire type as a prefix: "sw.N0_N", "dt.EA_N" (the rest is a name of the
// law's schema, dtwire/dem/law_schema.hpp). Each set is given for its own reference length
// (sw./dt.reference_length_m, required: 0.06 / 0.04 m for the published sets) and scaled to each
// link's length L with r = reference_length / L (scale_to_link_length): stiffnesses and
// hardening rates per unit of elongation or rotation x r (EA_N, EI_Nm2_per_deg_convention, k_F,
// k_M and macro3d's axial/bending/shear/torsion stiffness, k_F_per_m, k_M_per_rad), damage
// energies x 1/r (W1_J, W2_J), everything else (forces, shape exponents, D_m) unchanged, so
// that a segment of the same wire gives the same force at the same strain.
//
// Quasi-static solution: per load increment the upper grips move by the increment over
// move_steps explicit steps, are then held, and the engine steps until every free node's
// unbalanced force + moment / link length is below tolerance x the largest link force (at least
// 1 N). Node masses and rotational inertias are set from the stiffness of the links at each node
// (a diagonal "density scaling": the static answer does not depend on them, convergence does).
#include <array>
#include <string>
#include <vector>

#include "dtwire/calibrate/simulator.hpp"
#include "dtwire/dem/contact_law.hpp"

namespace dtwire::calibrate {

struct SpecimenGeometry {
  double twist_length_m = 0.040;
  double arm_length_m = 0.030;
  double arm_angle_rad = 41.81 * 3.14159265358979323846 / 180.0;
  int arm_links = 1;  // SW links per arm
};

// The bending rig (defaults: experiments/dt/dt_bending.prm). The FE's supports are turned by
// 4.6 deg about z because its two wires leave the twist 1.4 mm apart in y; the DEM's arms lie in
// the mesh plane, where level supports (tilt 0) touch both arms as the FE's tilted ones do.
struct RollerRig {
  double radius_m = 0.020;
  std::array<double, 2> support_z_m = {-0.010, 0.050};
  double loading_z_m = 0.020;
  double support_tilt_rad = 0.0;          // about z; the +z support turned the other way
  double friction = 0.3;                  // Coulomb, roller-wire (the FE's)
  double normal_stiffness_N_per_m = 5e7;  // penalty (and shear spring)
  double sw_contact_radius_m = 0.00135;   // the arms' wire, d / 2
  double dt_contact_radius_m = 0.0027;    // the twist's half-thickness normal to the mesh plane (two wires)
};

struct QuasiStaticOptions {
  double local_damping = 0.7;    // PFC/YADE local damping alpha in [0, 1)
  int move_steps = 200;          // explicit steps over which the grips move by one increment (smooth profile)
  double tolerance = 1e-6;       // unbalanced force / largest link force (at least 1 N)
  long max_relax_steps = 20000;  // per increment; beyond: ComputationError (not converged)
  double safety = 0.5;           // fraction of the engine's critical time step
};

enum class SpecimenTest { Pull, ThreePointBending };

struct SpecimenPath {
  SpecimenTest test = SpecimenTest::Pull;
  // Pull: the upper grips' displacement along the pull direction; bending: the loading roller's
  // along -y. Waypoints from 0.
  std::vector<double> displacement_m;
  double pull_angle_rad = 0.0;         // from the twist axis z towards +x, in the mesh plane
  int increments_per_leg = 100;
};

// Throws std::invalid_argument for < 2 waypoints, a first waypoint other than 0, non-finite
// values or increments_per_leg < 1.
void validate(const SpecimenPath& path);
void validate(const SpecimenGeometry& geometry);
void validate(const QuasiStaticOptions& options);
void validate(const RollerRig& rig);

// The prefixes of the two parameter sets.
inline constexpr const char* kSwPrefix = "sw.";
inline constexpr const char* kDtPrefix = "dt.";

// One set (unprefixed names) scaled from its reference length to a link of `link_length`
// (r = reference_length / link_length, the rules above); reference_length_m set to link_length.
dem::ParameterMap scale_to_link_length(const dem::ParameterMap& set, double reference_length, double link_length);

// Result of one run beyond the curve, for tests and diagnosis.
struct SpecimenRunInfo {
  long steps = 0;                   // explicit steps in all
  long largest_relax_steps = 0;     // of one increment
  double time_step = 0.0;           // [s] (pseudo-units: the masses are scaled)
};

class DemSpecimenSimulator final : public Simulator {
 public:
  // `fixed`: the prefixed parameters that are not fitted (both sets; fitted ones override them).
  // Throws std::invalid_argument for a law other than thesis/macro3d, a fixed name without a
  // prefix or outside the law's schema, a missing reference_length_m of either set, or bad
  // geometry/options/path.
  DemSpecimenSimulator(std::string law, dem::ParameterMap fixed, SpecimenGeometry geometry,
                       QuasiStaticOptions options, SpecimenPath path, bool scale_to_link_length = true,
                       RollerRig rig = {});

  // Channels (SI): time (pseudo-time, leg k from k-1 to k), displacement (of the upper grips
  // along d; bending: of the loading roller along -y), force (sum over the upper grips of the
  // force they apply to the specimen, along d, tension > 0; bending: the loading roller's on
  // the specimen along -y), support1_force, support2_force (bending: the lower and upper
  // supports' on the specimen along +y; 0 in a pull), shear_force (the same along v = e_y x d), moment (of those forces and moments
  // about the upper grips' centroid, about e_y), dt_elongation (length change of the DT link),
  // dt_axial_force, dt_shear_force, dt_moment (the DT law's N, V_z, M_y: the in-plane shear
  // along -x and the moment about +y of the undeformed twist), arm1_force..arm4_force (axial
  // force of the grip-end link of each arm: 1 upper +x, 2 upper -x, 3 lower +x, 4 lower -x).
  // Throws ComputationError if the law rejects the parameters, an increment does not converge
  // within max_relax_steps, a link breaks before the path's end or a value is not finite.
  Curve simulate(const ParameterValues& parameters) const override;
  Curve simulate(const ParameterValues& parameters, SpecimenRunInfo& info) const;
  std::string identity() const override;
  bool thread_safe() const override { return true; }  // every run builds its own engine and laws
  std::vector<std::pair<std::string, Dimension>> channels() const override;
  std::vector<std::string> parameter_names() const override;

  const std::string& law() const { return law_; }
  const SpecimenGeometry& geometry() const { return geometry_; }
  const QuasiStaticOptions& options() const { return options_; }
  const SpecimenPath& path() const { return path_; }
  const RollerRig& rig() const { return rig_; }

 private:
  std::string law_;
  dem::ParameterMap fixed_;
  SpecimenGeometry geometry_;
  QuasiStaticOptions options_;
  SpecimenPath path_;
  bool scale_ = true;
  RollerRig rig_;
};

}  // namespace dtwire::calibrate
