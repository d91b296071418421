#pragma once
// The interface every DEM contact law implements. Depends on the standard library and Eigen
// only, so a DEM code can embed the laws (see dtwire_contact.h for the C ABI).
//
// Generalised kinematics of a two-node bond, in the bond's local frame (x along the bond):
//   index 0: axial displacement u (elongation > 0)       [m]  <-> axial force N (tension > 0) [N]
//   index 1, 2: shear displacements v_y, v_z             [m]  <-> shear forces V_y, V_z       [N]
//   index 3: torsion rotation theta_x                    [rad] <-> torque T                  [N m]
//   index 4, 5: bending rotations theta_y, theta_z       [rad] <-> moments M_y, M_z          [N m]
// Planar laws (the thesis macro-element) use u and the bending rotation theta_y.
#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <string_view>

namespace dtwire::dem {

using Vector6 = Eigen::Matrix<double, 6, 1>;

enum class FailureMode { None, Necking, Shear, Elongation };

// Work done on the bond, split by where it went. external = elastic + plastic + damage
// (+ any other dissipation a law reports) up to round-off; every law keeps this balance.
struct EnergyAccount {
  double external = 0.0;  // integral of forces . d(displacement)           [J]
  double elastic = 0.0;   // stored, recoverable                             [J]
  double plastic = 0.0;   // dissipated by plastic flow                      [J]
  double damage = 0.0;    // dissipated by softening/damage                  [J]
};

// Named scalar parameters in SI (names carry the unit: "N0_N", "EA_N", "D_m", ...).
using ParameterMap = std::map<std::string, double>;

class ContactLaw {
 public:
  virtual ~ContactLaw() = default;

  // Advance the bond state by a generalised displacement increment (see the table above).
  virtual void update(const Vector6& displacement_increment) = 0;
  // Current generalised forces (N, V_y, V_z, T, M_y, M_z).
  virtual Vector6 forces() const = 0;
  virtual EnergyAccount energy() const = 0;
  virtual bool broken() const = 0;
  virtual FailureMode failure_mode() const { return broken() ? FailureMode::Elongation : FailureMode::None; }
  virtual std::string_view name() const = 0;
  virtual std::unique_ptr<ContactLaw> clone() const = 0;
};

// Looks up a parameter; throws std::invalid_argument naming the law and the missing field.
double require_parameter(const ParameterMap& parameters, const std::string& law,
                         const std::string& field);

// Creates a law by name ("thesis", "macro3d", "wirepm", "parallel_bond"); throws
// std::invalid_argument for an unknown name or a missing/invalid parameter.
std::unique_ptr<ContactLaw> make_contact_law(const std::string& name, const ParameterMap& parameters);

}  // namespace dtwire::dem
