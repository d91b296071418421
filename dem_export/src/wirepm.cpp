// WirePM law (Bertrand et al. 2008; Thoeni et al. 2013; behaviour of YADE's
// Law2_ScGeom_WirePhys_WirePM): tension only, loading along the backbone from the historical
// maximum, elastic unloading/reloading with kn from the plastic elongation, break past the last
// point. Energy is integrated exactly along each increment (the force is piecewise linear in the
// elongation), so external = elastic + plastic + damage to round-off.
#include <algorithm>
#include <stdexcept>

#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {

WirePmLaw::WirePmLaw(WirePmBackbone backbone) : backbone_(std::move(backbone)) {
  if (backbone_.points.size() < 2 || !(backbone_.unloading_stiffness > 0.0))
    throw std::invalid_argument("wirepm: the backbone needs the origin, one point and kn > 0");
}

double WirePmLaw::backbone_force(double elongation) const {
  const auto& p = backbone_.points;
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (elongation <= p[i].elongation) {
      const double slope = (p[i].force - p[i - 1].force) / (p[i].elongation - p[i - 1].elongation);
      return p[i - 1].force + (elongation - p[i - 1].elongation) * slope;
    }
  }
  return p.back().force;
}

double WirePmLaw::elastic_force(double elongation) const {
  return std::max(0.0, backbone_.unloading_stiffness * (elongation - plastic_elongation_));
}

void WirePmLaw::move_to(double target) {
  const double kn = backbone_.unloading_stiffness;
  const double start = displacement_(0);
  const auto stored = [&](double force) { return force * force / (2.0 * kn); };
  if (target <= start) {  // unloading: elastic, work = change of stored energy
    const double force_before = elastic_force(start);
    axial_force_ = elastic_force(target);
    energy_.external += stored(axial_force_) - stored(force_before);
    energy_.elastic = stored(axial_force_);
    return;
  }
  // Reloading on the elastic line up to the historical maximum.
  const double reload_end = std::min(target, max_elongation_);
  if (reload_end > start) {
    const double force_before = elastic_force(start);
    axial_force_ = elastic_force(reload_end);
    energy_.external += stored(axial_force_) - stored(force_before);
  }
  if (target > max_elongation_) {
    // Loading along the backbone: exact trapezoids between the curve's kinks.
    const auto& p = backbone_.points;
    const double from = std::max(start, max_elongation_);
    const double to = std::min(target, p.back().elongation);
    const double force_from = backbone_force(from);
    double work = 0.0, a = from, force_a = force_from;
    for (std::size_t i = 1; i < p.size() && a < to; ++i) {
      if (p[i].elongation <= a) continue;
      const double b = std::min(to, p[i].elongation);
      const double force_b = backbone_force(b);
      work += 0.5 * (force_a + force_b) * (b - a);
      a = b;
      force_a = force_b;
    }
    axial_force_ = backbone_force(to);
    energy_.external += work;
    energy_.plastic += work - (stored(axial_force_) - stored(force_from));
    max_elongation_ = to;
    plastic_elongation_ = to - axial_force_ / kn;
    if (target > p.back().elongation) {  // failure: the stored energy is released
      broken_ = true;
      energy_.damage += stored(axial_force_);
      axial_force_ = 0.0;
    }
  }
  energy_.elastic = stored(axial_force_);
}

void WirePmLaw::update(const Vector6& displacement_increment) {
  if (broken_) return;
  move_to(displacement_(0) + displacement_increment(0));
  displacement_ += displacement_increment;
}

Vector6 WirePmLaw::forces() const {
  Vector6 result = Vector6::Zero();
  result(0) = axial_force_;
  return result;
}

}  // namespace dtwire::dem
