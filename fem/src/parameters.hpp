#pragma once
// The .prm file of a virtual experiment: one struct per concern (as in deal.II step-44), parsed
// with dealii::ParameterHandler. Values are converted to SI here; the file uses mm and MPa.
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "checks_parameters.hpp"
#include "contact/contact_parameters.hpp"  // contact (issue 5)
#include "dtwire/core/axis_csv.hpp"
#include "hardening.hpp"
#include "j2_log_plasticity.hpp"

namespace dtwire::fem {

struct GeometryParameters {
  double diameter = 2.7e-3;      // m
  double length = 60e-3;         // m, along z from 0 to length
  bool quarter = true;           // quarter cross-section with symmetry planes x = 0, y = 0
  unsigned radial_refinements = 1;
  unsigned axial_cells = 30;
  double imperfection = 0.0;     // relative radius reduction at the imperfection centre
  double imperfection_centre = 30e-3;      // m
  double imperfection_half_width = 30e-3;  // m, cosine profile
  double mesh_distortion = 0.0;            // random interior-vertex shift, fraction of cell size
  std::filesystem::path mesh_file;  // gmsh .msh of a SW (meshes/ module); empty: generated
  double bow = 0.0;  // m, lateral (x) imperfection e (1 - cos(2 pi z / L)) / 2: fixed-fixed buckling mode
  // Set when the mesh file is a double twist (two wires: material ids 1-6 and 11-16); its
  // boundary ids are then kept as written by `dtwire mesh dt` (docs/meshes.md).
  bool double_twist = false;
  // Cleared when a single-wire mesh file's axis leaves the z axis (`dtwire mesh segment`): the
  // diameter is then read off its end face and no neck section is tracked.
  bool straight_axis = true;
  // Local refinement at the twist's junctions (junction_refinement.hpp): the active cells whose
  // centre lies within junction_half_width of a junction plane z = const are refined,
  // junction_cycles times (0: the mesh as read or generated).
  unsigned junction_cycles = 0;
  double junction_half_width = 4e-3;     // m
  std::vector<double> junction_planes;   // m, z of the planes
};

struct MaterialParameters {
  double young = 200e9;  // Pa
  double poisson = 0.3;
  HardeningParameters hardening;
  FailureParameters failure;
  KinematicParameters kinematic;  // Armstrong-Frederick, off by default
  bool stop_at_failure = true;
  double stop_force_fraction = 0.1;  // with softening: stop once |force| <= this x its peak
};

// The double twist as made (forming_history.hpp, issue 19): the wires start with the plastic
// strain, backstress, damage and stress of being bent from straight wire into the mesh's axes,
// and are released (springback, bottom grips held) before the load path begins.
struct FormingParameters {
  bool enabled = false;
  double scale = 1.0;            // fraction of the bending strain taken (0: tight and stress-free)
  std::filesystem::path axis_file;  // the mesh's X.axis.csv
  std::vector<std::vector<AxisStation>> axes;  // as read from it (per wire), checked with the .prm
  unsigned increments = 20;      // steps of each fibre's uniaxial forming path
  double initial_release_step = 0.25;  // fraction of the forming stress released in the first step
  std::filesystem::path state_file;  // start from this run's as_made_state.bin instead (empty: form here)
  // A twisting run: after the paths the top grips let go (springback), and the pair's state is
  // written for the twist of a DT mesh (solver_twisted_pair.cpp).
  bool release_after_path = false;
  std::filesystem::path twisted_pair_state;  // that file, mapped onto this mesh's twist (empty: bending only)
};

struct FormulationParameters {
  bool fbar = true;
  unsigned degree = 1;
};

// free: top end only (bending on rollers); guided (u_x = u_z = 0): bottom end only.
enum class EndCondition { clamped, axial, guided, symmetry, free };
enum class LoadDirection { axial, lateral };  // top displacement along z, or along x

// How the grips hold the wire (`Grip interface`). clamped: the grip surfaces are Dirichlet
// boundaries. bonded: a penalty bond ties them to the grips' rigid motion; the top grips' bond
// slides once its shear stress reaches the strength (contact/bonded_grip.hpp).
struct GripParameters {
  bool bonded = false;
  double strength = 0.0;          // Pa, tau_b: shear strength of the top grips' bond
  double stiffness_factor = 1.0;  // penalty k = factor E / h, h the smallest grip face
};

struct LoadParameters {
  EndCondition bottom = EndCondition::clamped;  // z = 0
  EndCondition top = EndCondition::clamped;     // z = length, carries the prescribed displacement
  LoadDirection direction = LoadDirection::axial;
  std::vector<std::pair<double, double>> path;  // (pseudo-time, top displacement in m)
  // Force control: the top face moves as one (all its u_z equal) under the total axial force
  // force_path(t) (N, whole specimen); `path` then holds the same knots with zero displacement.
  bool force_control = false;
  std::vector<std::pair<double, double>> force_path;  // (pseudo-time, force in N)
  // Boundary ids of the two ends: SW meshes 1 (z = 0) and 2 (z = L); a DT mesh its grips.
  std::vector<unsigned> bottom_ids{1}, top_ids{2};
  // Clamped top only: the displacement of the load path acts along this unit vector (pull at an
  // angle) instead of z / x; empty: the Load direction decides.
  std::vector<double> pull_direction;
  // Clamped top only: rigid rotation of the top end about `rotation_axis` through
  // `rotation_centre` (m, reference configuration), (pseudo-time, angle in rad).
  std::vector<std::pair<double, double>> rotation_path;
  std::array<double, 3> rotation_axis{{0.0, 1.0, 0.0}};
  std::array<double, 3> rotation_centre{};  // set by the solver when not given
  bool rotation_centre_given = false;
  GripParameters grip;
};

struct SteppingParameters {
  double initial_step = 0.01;  // pseudo-time
  double minimum_step = 1e-6;
  double maximum_step = 0.05;
  double growth_factor = 1.5;
  double cutback_factor = 0.5;
  unsigned easy_iterations = 4;  // grow the step when Newton needs at most this many
};

struct NewtonParameters {
  unsigned maximum_iterations = 15;
  double relative_tolerance = 1e-10;  // free residual vs internal-force norm
  bool line_search = true;
  unsigned maximum_line_search_steps = 5;
  bool krylov = false;                 // GMRES + PETSc GAMG with rigid-body modes instead of MUMPS
  // GMRES preconditioned by the last MUMPS factors, factorised anew when GMRES needs more than
  // this many iterations (0: a factorisation every iteration, the plain direct solver).
  unsigned lagged_lu_iterations = 0;  // the .prm default is 15
  double linear_tolerance = 1e-12;     // Krylov: relative residual of each linear solve
  unsigned maximum_linear_iterations = 2000;
  // Modified Newton (direct solver): the next iteration keeps the last factorisation while the
  // residual fell below this fraction of the one before (0: a fresh tangent every iteration).
  double tangent_reuse_contraction = 0.0;
};

struct OutputParameters {
  unsigned field_interval = 0;       // VTU every n steps (0: none); the last step is always written
  unsigned checkpoint_interval = 0;  // steps between checkpoints (0: none)
  bool fields = true;
  // Material points (m, reference configuration) whose displacement is written every step: a
  // virtual extensometer / image-analysis marker.
  std::vector<std::array<double, 3>> probe_points;
  // Virtual extensometer (a clip gauge, or the image analysis of a double twist): pairs of
  // material points, stored as indices into probe_points (their points are appended there).
  // Its elongation is the mean change of distance between the points of each pair.
  std::vector<std::array<std::size_t, 2>> extensometer;
  // The curve's displacement_mm column holds the extensometer elongation (the load-path
  // displacement moves to grip_displacement_mm), as a laboratory curve measured that way.
  bool extensometer_as_displacement = false;
  // The twist as a DEM link (link_kinematics.hpp): its bottom and top sections, four material
  // points each (indices into probe_points), or empty. Adds the link_* columns to the curve.
  std::vector<std::array<std::size_t, 4>> link_sections;
};

struct Parameters {
  GeometryParameters geometry;
  MaterialParameters material;
  FormulationParameters formulation;
  FormingParameters forming;
  LoadParameters load;
  SteppingParameters stepping;
  NewtonParameters newton;
  OutputParameters output;
  contact::ContactParameters contact;  // contact (issue 5): rigid tools, none by default
  contact::WireContactParameters wire_contact;  // contact between the two wires of a DT mesh
  RunChecks checks;  // the run's self-checks (issue 37)

  // Generalised end forces, moment and energy split in the curve (DT meshes, pull angles,
  // rotations, bonded grips).
  bool generalised_output() const {
    return geometry.double_twist || !load.pull_direction.empty() || !load.rotation_path.empty() || load.grip.bonded;
  }
};

// Throws InputError naming the file (and line, when deal.II reports it) and what was expected.
// `settings` ("Section/Entry=value", as `dtwire run --set`) override the file's entries.
Parameters read_parameters(const std::filesystem::path& file, const std::vector<std::string>& settings = {});

// deal.II's exception text reduced to its "Additional information", on one line.
std::string deal_ii_message(const std::string& what);

// Top displacement (m) at pseudo-time t, piecewise linear in the load path.
double path_displacement(const LoadParameters& load, double t);
// Rotation (rad) of the top end at pseudo-time t (0 without a rotation path).
double path_rotation(const LoadParameters& load, double t);
// Prescribed total force (N) at pseudo-time t under force control (0 otherwise).
double path_force(const LoadParameters& load, double t);

}  // namespace dtwire::fem
