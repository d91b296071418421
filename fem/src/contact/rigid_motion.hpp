#pragma once
// Rigid motions of the wire's ends (the top grips follow the load path and the rotation path).
#include "../parameters.hpp"
#include "contact_kernel.hpp"

namespace dtwire::fem::contact {

// A rigid motion X -> X + translation + (R - I)(X - centre).
struct RigidMotion {
  Matrix3 rotation;
  Vector3 translation, centre;
  Vector3 displacement(const Vector3& X) const { return translation + rotation * (X - centre) - (X - centre); }
};
RigidMotion identity_motion();

// The top end's rigid motion at pseudo-time t: the load path along `direction` and the rotation
// path about the rotation axis through `centre` (Rodrigues), as the clamped top end moves.
RigidMotion top_end_motion(const LoadParameters& load, const Vector3& direction, const Vector3& centre, double t);

}  // namespace dtwire::fem::contact
