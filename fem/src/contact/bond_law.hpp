#pragma once
// Bonded interface between the wire surface and a rigid grip: a penalty spring of stiffness k per
// unit area ties a wire point to its anchor on the grip. The normal part is elastic (bonded in
// tension and compression); the tangential part is rigid-perfectly plastic with a constant limit
// |t_T| <= tau_b (a coating whose interface with the steel fails in shear and then slides at its
// strength), integrated by an elastic predictor and a radial return, as Coulomb friction with the
// limit tau_b in place of mu p (Wriggers 2006, Computational Contact Mechanics, sec. 5.2 and
// 10.5; Simo & Hughes 1998, Computational Inelasticity, ch. 1 for the 1D rigid-plastic return
// map). Everything here is in the grip's frame, whose surface normal is fixed: the tangent is
// symmetric. Plain deal.II tensors: testable without a mesh.
#include "contact_kernel.hpp"

namespace dtwire::fem::contact {

struct BondLaw {
  double stiffness = 0.0;  // k, Pa/m
  double strength = 0.0;   // tau_b, Pa
  bool slides = true;      // false: elastic bond without a limit
};

// Committed history of one bond point.
struct BondHistory {
  Vector3 slip_vector;  // plastic slip s_p in the grip frame (tangential), m
  double slip = 0.0;    // accumulated slip length, m
};

struct BondResponse {
  Vector3 traction;          // on the wire per reference area, grip frame: -k (g_N n + g_T - s_p)
  Matrix3 stiffness;         // d traction / d g (consistent)
  bool slipping = false;
  double slip_increment = 0.0;  // Delta gamma, m
  BondHistory history;          // updated history (committed when the step converges)
  double energy = 0.0;          // J/m^2 stored in the spring: k g_N^2 / 2 + |t_T|^2 / (2 k)
  double dissipation = 0.0;     // J/m^2 in this step: tau_b Delta gamma
};

// `gap` = wire point - anchor, `normal` the unit surface normal, both in the grip frame.
BondResponse evaluate_bond(const BondLaw& law, const BondHistory& committed, const Vector3& normal, const Vector3& gap);

}  // namespace dtwire::fem::contact
