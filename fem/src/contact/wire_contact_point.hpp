#pragma once
// One slave Gauss point of the wire-wire contact against one bilinear master face: its nodal
// forces on the 24 dofs (12 of the slave face, 12 of the master face) and their exact derivative,
// the consistent tangent. The closest-point parameters, the master normal and the anchor of the
// friction predictor all move with the 24 dofs; forward automatic differentiation (Sacado
// SFad, 24 directions) differentiates through them, the closest-point parameters by the implicit
// function theorem (one Newton correction in AD arithmetic from the converged projection).
// This is the full linearisation of the Gauss-point-to-surface penalty contact with Coulomb
// friction (Wriggers 2006, sec. 4.1 and 10.5.2; Laursen 2002, sec. 5.3): normal, curvature and
// projection-variation terms included, which the frozen-normal tangent drops.
#include <array>

#include "contact_kernel.hpp"

namespace dtwire::fem::contact {

struct WireContactPointInput {
  std::array<Vector3, 4> slave_reference, master_reference;  // face vertices, reference positions
  std::array<double, 12> slave_displacement{}, master_displacement{};  // vertex v, component c at 3 v + c
  std::array<double, 12> master_committed_displacement{};             // at the last converged step
  double master_sign = 1.0;                   // +1 if x_xi x x_eta points out of the master body
  double slave_xi = 0.0, slave_eta = 0.0;     // the Gauss point on the slave face
  double weight = 0.0;                        // reference area of the point
  double master_xi = 0.5, master_eta = 0.5;   // converged closest point (clamped to the face)
  Vector3 committed_slave_position;           // x_s at the last converged step
  double gap_offset = 0.0;                    // m, added to the gap
  ContactHistory history;                     // committed tangential traction; current multiplier
  FrictionStatus forced = FrictionStatus::free;
};

struct WireContactPointOutput {
  ContactResponse response;            // traction, pressure, gap, slip as the kernel reports them
  std::array<double, 24> force{};      // internal force on the dofs (slave +N t, master -N t, times -weight)
  std::array<std::array<double, 24>, 24> stiffness{};  // d force / d u
};

// With `with_tangent` false only the response and the force are computed (plain doubles).
WireContactPointOutput evaluate_wire_contact_point(const WireContactPointInput& input, const ContactLaw& law,
                                                   bool with_tangent);

}  // namespace dtwire::fem::contact
