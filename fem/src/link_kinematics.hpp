#pragma once
// The double twist as a DEM link: its generalised displacements and forces read off an FE run,
// so that a link-level fit compares the element with the twist itself rather than with the whole
// specimen (arms and grips included).
//
// A section of the twist is four material points: the two wires' axis points (a, b) and one
// point in each wire off its axis, both offset the same way (qa, qb), fixing the section's roll.
// Its frame is origin o = (a + b)/2, e1 = (b - a)/|b - a|, e2 = the part of the mean offset
// ((qa - a) + (qb - b))/2 normal to e1 (normalised), e3 = e1 x e2; the same construction on the
// deformed points gives the current frame, and the section's rotation is R = E E0^T (E, E0:
// current and reference frames as columns). Averaging the two wires' offsets cancels the roll
// of each wire's own cross-section as its helix straightens (the two wires' helix tangents at a
// section tilt oppositely), which one wire's offset alone would read as bending of the link.
// The link joins the bottom section's origin to the top section's:
//   elongation  = |o_t - o_b| - |o_t0 - o_b0|          (chord, as a DEM bond measures it)
//   rotation    = log(R_t R_b^T)                        (relative rotation vector, global axes)
//   axial force = F . c,  shear force = |F - (F . c) c|  (c: current chord direction)
//   moment      = M_e + (x_e - m) x F                   (about the current link midpoint m)
// where F and M_e are the force and moment of the load on the top end (M_e about the end centre
// x_e). Without loads between the top end and the link (none act on the arms), F and M_e are
// what the twist transmits; the moment about the midpoint is the mean of the two end sections'
// moments, the bending moment of a bond that carries shear (Timoshenko beam, antisymmetric part
// V L/2 at its ends removed).
#include <array>

namespace dtwire::fem {

using Point3 = std::array<double, 3>;
using SectionPoints = std::array<Point3, 4>;  // a, b (wire axes), qa, qb (offsets in each wire)

struct LinkState {
  double length = 0.0;      // current chord [m]
  double elongation = 0.0;  // [m]
  Point3 rotation{};        // relative rotation vector of the top section [rad]
  double axial_force = 0.0, shear_force = 0.0;  // [N]
  Point3 moment{};          // about the link midpoint [N m]
};

// Throws std::invalid_argument if a section's axis points coincide or its mean offset is
// (nearly) along their line.
void check_section(const SectionPoints& reference);

// The link state from the sections' reference points and their current positions and the load
// on the top end.
LinkState link_state(const SectionPoints& bottom_reference, const SectionPoints& bottom_current,
                     const SectionPoints& top_reference, const SectionPoints& top_current, const Point3& end_force,
                     const Point3& end_moment, const Point3& end_centre);

// Rotation vector (axis x angle, angle in [0, pi]) of a proper rotation matrix (rows).
Point3 rotation_vector(const std::array<Point3, 3>& rotation);

}  // namespace dtwire::fem
