#pragma once
// WirePM: the tension-only piecewise-linear wire law of Bertrand et al. 2008 and Thoeni et al.
// 2013 (open source in YADE as WireMat / Ip2_WireMat_WireMat_WirePhys /
// Law2_ScGeom_WirePhys_WirePM), reimplemented with exact energy bookkeeping and a per-bond
// deterministic random stream. Equations: docs/dem_driver_export.md.
//
// Parameters (ParameterMap, SI):
//   reference_length_m, diameter_m                      required
//   backbone_<i>_strain_1, backbone_<i>_stress_Pa       i = 0, 1, ... contiguous; engineering
//                                                       stress-strain; an origin point is dropped;
//                                                       at least two points besides the origin
//   double_twist        0 | 1                           (default 0)
//   double_twist_model  0: Bertrand scaling of the curve (lambda_k, lambda_eps, poisson_1)
//                       1: the curve is the double twist's own, on twice the wire area
//   lambda_k, lambda_eps, poisson_1                     (defaults 0.73, 0.47, 0.3)
//   lambda_u, lambda_F                                  Thoeni distortion (defaults 0, 1)
//   seed                per-bond seed of the distortion; -1 means r = 1 (YADE's seed = -1)
#include <cstdint>
#include <vector>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

struct ForceElongationPoint {
  double elongation;  // [m]
  double force;       // [N]
};

// The per-bond curve after the double-twist scaling and the distortion.
struct WirePmBackbone {
  std::vector<ForceElongationPoint> points;  // starts at (0, 0), strictly increasing elongation
  double unloading_stiffness = 0.0;          // kn [N/m]
  double shift = 0.0;                        // dL [m]
};

// SplitMix64 of the seed mapped to a triangular variate on [0, 1] with mode 0.5 (inverse CDF).
double triangular_variate_from_seed(std::uint64_t seed);

// Builds the per-bond curve; throws std::invalid_argument naming a missing or invalid field.
WirePmBackbone make_wirepm_backbone(const ParameterMap& parameters);

class WirePmLaw final : public ContactLaw {
 public:
  explicit WirePmLaw(WirePmBackbone backbone);

  void update(const Vector6& displacement_increment) override;
  Vector6 forces() const override;
  EnergyAccount energy() const override { return energy_; }
  bool broken() const override { return broken_; }
  std::string_view name() const override { return "wirepm"; }
  std::unique_ptr<ContactLaw> clone() const override { return std::make_unique<WirePmLaw>(*this); }

  const WirePmBackbone& backbone() const { return backbone_; }
  double plastic_elongation() const { return plastic_elongation_; }

 private:
  double backbone_force(double elongation) const;
  double elastic_force(double elongation) const;
  void move_to(double elongation);

  WirePmBackbone backbone_;
  Vector6 displacement_ = Vector6::Zero();
  double max_elongation_ = 0.0;  // historical maximum on the backbone
  double plastic_elongation_ = 0.0;
  double axial_force_ = 0.0;
  bool broken_ = false;
  EnergyAccount energy_;
};

}  // namespace dtwire::dem
