#pragma once
// Gauss-point contact of a deformable body against a rigid analytic tool: gap and normal from
// the closest point on the tool surface, penalty normal traction with an augmented-Lagrange
// multiplier, and Coulomb friction by a tangential elastic predictor / return map with its
// consistent tangent. Wriggers (2006) "Computational Contact Mechanics", 2nd ed., sec. 5.2
// (penalty, augmented Lagrangian) and 10.5 (friction return map); Laursen (2002)
// "Computational Contact and Impact Mechanics", ch. 5-6; Simo & Laursen (1992) Comput. Struct.
// 42 (Uzawa augmentation). Plain deal.II tensors only: testable without a mesh.
#include <deal.II/base/tensor.h>

namespace dtwire::fem::contact {

using Vector3 = dealii::Tensor<1, 3>;
using Matrix3 = dealii::Tensor<2, 3>;

enum class ToolShape { plane, cylinder, grooved_plate };

// Closest-point projection of a point x onto the tool surface.
struct Projection {
  double gap = 0.0;          // signed distance, > 0 separated, < 0 penetration
  Vector3 normal;            // unit outward normal of the tool at the closest point
  Matrix3 normal_gradient;   // d normal / d x (symmetric; zero for a plane)
};

// A rigid tool in its current (moved) position. A grooved plate is a plane (point, outward
// normal `direction`) with a circular channel of radius `radius` cut into it, its axis along
// `groove_axis` (unit, in the plane) through `point`: the solid {h < 0} minus {rho < radius},
// h the height above the plane and rho the distance from the groove axis. Its gap is
// max(h, radius - rho): the exact signed distance inside the solid, positive outside.
struct ToolGeometry {
  ToolShape shape = ToolShape::plane;
  Vector3 point;      // plane, grooved plate: a point on the surface; cylinder: a point on the axis
  Vector3 direction;  // plane, grooved plate: unit outward normal; cylinder: unit axis
  double radius = 0.0;  // cylinder, groove
  Vector3 groove_axis;  // grooved plate

  // Throws std::domain_error for a point on the cylinder axis (no unique normal).
  Projection project(const Vector3& x) const;
};

struct ContactLaw {
  double normal_penalty = 0.0;      // Pa/m, epsilon_N
  double tangential_penalty = 0.0;  // Pa/m, epsilon_T (stick compliance 1/epsilon_T)
  double friction = 0.0;            // Coulomb mu
};

// Committed history of one contact quadrature point.
struct ContactHistory {
  Vector3 tangential_traction;  // t_T at the end of the last converged step
  double multiplier = 0.0;      // augmented-Lagrange pressure lambda_N (Pa), >= 0
  double slip = 0.0;            // accumulated slip length (m)
};

struct ContactResponse {
  bool active = false, slipping = false;
  double gap = 0.0, pressure = 0.0;  // p = <lambda_N - epsilon_N g>, Pa
  Vector3 traction;            // on the body, per reference area: p n + t_T
  Vector3 tangential_traction; // t_T (the new history)
  Matrix3 stiffness;           // d traction / d x (consistent, non-symmetric with friction)
  double slip_increment = 0.0; // |slip| in this step (m), Delta gamma
  double dissipation = 0.0;    // friction work in this step per reference area (J/m^2), mu p Delta gamma
};

// Stick/slip decision: free (the return map decides) or frozen by the wire-wire chattering guard
// (a point whose status flipped too often within one step keeps its last status).
enum class FrictionStatus { free, stick, slip };

// Traction at the current point x. `anchor` is the point's position at the last converged step
// plus the tool displacement over the step, so that x - anchor is the motion relative to the
// tool (rigid translation of the tool).
ContactResponse evaluate_contact(const ToolGeometry& tool, const ContactLaw& law, const ContactHistory& history,
                                 const Vector3& x, const Vector3& anchor,
                                 FrictionStatus forced = FrictionStatus::free);

}  // namespace dtwire::fem::contact
