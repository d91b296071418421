#pragma once
// The state a twisting run leaves in a straight pair of wires (As made/Release after path), and
// its transfer onto the twist of a double-twist mesh (As made/Twisted pair state), issue 19.
//
// The file (`twisted_pair_state.csv`, written by the run, read here) is a dtwire curve CSV
// (dtwire/core/csv.hpp) with metadata `twisted_from_z_ref_mm` and `twisted_to_z_ref_mm` (the
// reference heights between the pair's grips) and one row per steel quadrature point:
//   wire_1, station_z_ref_mm (mean reference height of the point's axis station),
//   axis_x_mm, axis_y_mm, axis_z_mm (that station's deformed centroid),
//   x_mm, y_mm, z_mm (the point, deformed), b_e_xx_1 ... b_e_yz_1 (elastic left Cauchy-Green
//   tensor F Cp^-1 F^T), equivalent_plastic_strain_1, plastic_dissipation_density_MPa (J/m3 in
//   MPa), damage_1, backstress_xx_MPa ... backstress_yz_MPa.
// With the deformed pair as the new reference, b_e is the plastic metric that reproduces its
// stress (Simo 1992, CMAME 99: b_e is the elastic state of multiplicative plasticity) and the
// backstress is spatial already, so a point of the DT mesh takes them rotated into its frame.
//
// The transfer: the DT mesh's twist lies between the heights z_lo, z_hi where the two wire
// axes are at the helix's radius from their midpoint; a point of wire w there, with axis foot
// point p at height z, is mapped to the pair's reference height z_ref = Z0 + (z - z_lo) / (z_hi
// - z_lo) (Z1 - Z0); its offset from p, turned about z by the difference of the two wires'
// azimuths about their midpoints (pair at z_ref minus mesh at z), is added to the pair's
// deformed axis there, and the pair's nearest point of the same wire (within one station)
// gives the state. Closest-point transfer, as in remeshing of plastic solids (Ortiz & Quigley
// 1991, CMAME 90; Peric et al. 1996, IJNME 39): no averaging of plastic states.
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <filesystem>
#include <ostream>
#include <vector>

#include "dtwire/core/axis_csv.hpp"
#include "j2_log_plasticity.hpp"

namespace dtwire::fem {

struct TwistedPairPoint {
  unsigned wire = 0;
  double station_z_ref = 0.0;  // m
  dealii::Point<3> axis, position;  // m, deformed
  PlasticState state;  // plastic metric = b_e, backstress spatial
};

// Writes the file (temporary name, then renamed). Units as in the header above.
void write_twisted_pair_csv(const std::filesystem::path& file, double z0, double z1,
                            const std::vector<TwistedPairPoint>& points);

struct TransferredState {
  bool inside = false;  // the point lies in the mesh's twist
  PlasticState state;
  double distance = 0.0;  // m, from the mapped position to the pair point it took the state from
};

class TwistedPairState {
 public:
  // Reads the file (errors name its line) and the DT mesh's axes. Throws InputError naming the
  // file when the mesh has no twist, the pair has not two wires, or the two twists turn the other
  // way or put the wires on opposite sides.
  TwistedPairState(const std::filesystem::path& file, const std::vector<std::vector<AxisStation>>& mesh_axes);
  // The state for a point `x` of wire `wire` whose axis foot point is `foot`.
  TransferredState at(unsigned wire, const dealii::Point<3>& x, const dealii::Point<3>& foot) const;
  double twist_bottom() const { return z_lo_; }  // m, the mesh's twist
  double twist_top() const { return z_hi_; }

 private:
  struct Station {
    double z_ref;
    dealii::Point<3> axis;
  };
  dealii::Point<3> pair_axis(unsigned wire, double z_ref) const;
  dealii::Point<3> mesh_axis(unsigned wire, double z) const;
  double turn(unsigned wire, double z) const;  // rad, pair azimuth minus mesh azimuth
  double to_pair_height(double z) const { return z0_ + (z - z_lo_) / (z_hi_ - z_lo_) * (z1_ - z0_); }

  std::filesystem::path file_;
  double z0_ = 0.0, z1_ = 0.0, z_lo_ = 0.0, z_hi_ = 0.0, window_ = 0.0;
  std::vector<std::vector<TwistedPairPoint>> points_;  // per wire, by station_z_ref
  std::vector<std::vector<Station>> stations_;          // per wire, by z_ref
  std::vector<std::vector<AxisStation>> mesh_axes_;
};

}  // namespace dtwire::fem
