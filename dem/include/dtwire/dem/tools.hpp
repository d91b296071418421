#pragma once
// Rigid tools that touch the net's nodes: a plane wall, the semi-spheroid punch platter and a
// truncated-cube boulder. Each tool is a rigid body (position, orientation, velocity, spin);
// kinematic tools move as prescribed, the boulder moves freely in 6 DOF.
// Node-tool contact: linear normal spring kn on the penetration, incremental linear shear spring
// ks capped by Coulomb friction (Cundall & Strack 1979), evaluated by the engine.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace dtwire::dem {

struct ToolContactLaw {
  double normal_stiffness = 1e9;  // kn [N/m]
  double shear_stiffness = 1e8;   // ks [N/m]
  double friction = 0.2;          // Coulomb coefficient
};

// Where a sphere touches a tool surface.
struct SurfacePoint {
  double distance = 0.0;                                // signed, centre to surface, > 0 outside [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();    // outward unit normal at the surface point
};

class Tool {
 public:
  virtual ~Tool() = default;
  // The surface point nearest to `point` (world frame), or false if the point is farther than
  // `reach` from the tool (no contact possible).
  virtual bool nearest(const Eigen::Vector3d& point, double reach, SurfacePoint& out) const = 0;
  virtual std::string kind() const = 0;
  // Radius of a sphere about `position` that holds the whole tool (infinite for a wall): the
  // engine skips the surface search for nodes farther than it.
  virtual double bounding_radius() const = 0;

  // Rigid-body state (world frame).
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // reference point (centre)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  ToolContactLaw contact;
  // Free rigid body (boulder) if mass > 0; otherwise kinematic (velocity prescribed).
  double mass = 0.0;
  double rotational_inertia = 0.0;  // isotropic [kg m^2]

 protected:
  Eigen::Vector3d to_local(const Eigen::Vector3d& p) const { return orientation.conjugate() * (p - position); }
  Eigen::Vector3d to_world_direction(const Eigen::Vector3d& d) const { return orientation * d; }
};

// Half-space below the plane through `position` with outward normal `normal` (world frame).
class PlaneWall final : public Tool {
 public:
  explicit PlaneWall(const Eigen::Vector3d& outward_normal);
  bool nearest(const Eigen::Vector3d& point, double reach, SurfacePoint& out) const override;
  std::string kind() const override { return "wall"; }
  double bounding_radius() const override;

 private:
  Eigen::Vector3d normal_;
};

// Semi-spheroid (x^2 + y^2)/a^2 + z^2/h^2 <= 1, z >= 0 in the tool frame: base radius a, height
// h, dome along +z, flat base at z = 0 (Pol et al. 2017 punch platter).
class SemiSpheroidPlatter final : public Tool {
 public:
  SemiSpheroidPlatter(double base_radius, double height);
  bool nearest(const Eigen::Vector3d& point, double reach, SurfacePoint& out) const override;
  std::string kind() const override { return "platter"; }
  double bounding_radius() const override { return std::max(a_, h_); }  // position: the base centre
  double base_radius() const { return a_; }
  double height() const { return h_; }

 private:
  double a_, h_;
};

// Cube of side s with its eight corners cut by the planes |x| + |y| + |z| = c (tool frame,
// centred); c = 1.5 s/2 is the plain cube, smaller c cuts deeper. The signed distance is the
// largest of the 14 face-plane distances: exact on faces, slightly short (early contact) near
// edges and corners outside the body.
class TruncatedCube final : public Tool {
 public:
  TruncatedCube(double side, double corner_plane);
  bool nearest(const Eigen::Vector3d& point, double reach, SurfacePoint& out) const override;
  std::string kind() const override { return "boulder"; }
  double bounding_radius() const override { return 0.5 * std::sqrt(3.0) * side_; }  // the cube's corners
  double side() const { return side_; }
  double corner_plane() const { return corner_; }

 private:
  double side_, corner_;
};

// Nearest point of the ellipse (x/A)^2 + (y/B)^2 = 1 to (x, y), x, y >= 0; returns the point and
// the distance (Newton on the Lagrange parameter, monotone from a bracketing start).
Eigen::Vector2d nearest_on_ellipse(double A, double B, double x, double y);

}  // namespace dtwire::dem
