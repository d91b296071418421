#pragma once
// The double twist as made (issue 19): every fibre of a wire bent from straight wire into the
// mesh's axis. A fibre at offset y from the axis, where the axis has curvature vector k (towards
// the centre of curvature), is stretched to the logarithmic axial strain ln(1 - k.y) (plane
// sections stay plane: Bernoulli-Euler bending, e.g. Timoshenko & Gere, "Theory of elastic
// stability", or any strength-of-materials text; the logarithm keeps fibre lengths exact).
// The fibre is driven along that strain in uniaxial stress with the solver's own material
// (J2LogPlasticity: hardening, backstress, damage), and its state is then expressed with the
// bent (mesh) geometry as the reference: b_e = F Cp^-1 F^T becomes the plastic metric, so the
// mesh held in its shape carries the forming stress. Released, it springs back
// (solver_forming.cpp). Not modelled: the twisting of each wire about its own axis and the
// contact pressure of the twisting tool (the machine's pinions), see docs/fem_dt.md.
// Only deal.II's tensor classes are used here, so this is tested without a mesh.
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <vector>

#include "dtwire/core/axis_csv.hpp"
#include "j2_log_plasticity.hpp"

namespace dtwire::fem {

// The uniaxial forming path of one fibre: the state after stretching it to `axial_log_strain`
// along `tangent` (unit) in `increments` equal steps, lateral stresses zero, given in the bent
// configuration (the reference of the mesh). The stress it carries there is the forming stress.
PlasticState formed_state(const J2LogPlasticity& material, const dealii::Tensor<1, 3>& tangent,
                          double axial_log_strain, unsigned increments);

// Where a material point lies relative to its wire's axis.
struct AxisLocation {
  dealii::Point<3> point;        // x's foot point on the axis
  dealii::Tensor<1, 3> tangent;  // unit
  double bending_strain = 0.0;   // ln(1 - k.y), the axial log strain of the fibre from straight
  double arc_length = 0.0;       // m along the wire's axis
  unsigned station = 0;          // nearest station (for profiles)
};

// The wire axes of a mesh (`X.axis.csv`, written by `dtwire mesh`; mm in the file, m here).
class WireAxes {
 public:
  // From the stations of dtwire/core/axis_csv.hpp (read_axis_csv names a bad file's line).
  explicit WireAxes(const std::vector<std::vector<AxisStation>>& wires);
  unsigned wires() const { return static_cast<unsigned>(stations_.size()); }
  unsigned stations(unsigned wire) const { return static_cast<unsigned>(stations_.at(wire).size()); }
  double arc_length(unsigned wire, unsigned station) const { return stations_.at(wire).at(station).arc_length; }
  double height(unsigned wire, unsigned station) const { return stations_.at(wire).at(station).point[2]; }
  // Axis, tangent and curvature interpolated between the two stations around x's foot point.
  AxisLocation locate(unsigned wire, const dealii::Point<3>& x) const;

 private:
  struct Station {
    double arc_length;
    dealii::Point<3> point;
    dealii::Tensor<1, 3> tangent, curvature;
  };
  std::vector<std::vector<Station>> stations_;
};

}  // namespace dtwire::fem
