// Thoeni et al. 2013 distortion: YADE's random stream and the shift decorator (distortion.hpp).
#include "dtwire/dem/distortion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtwire::dem {
namespace {

constexpr std::uint64_t kModulus = 2147483647;  // 2^31 - 1
constexpr std::uint64_t kMultiplier = 48271;    // minstd_rand (Park, Miller and Stockmeyer 1993)

std::uint64_t power_mod(std::uint64_t base, std::uint64_t exponent) {
  std::uint64_t result = 1;
  base %= kModulus;
  while (exponent > 0) {  // products stay below 2^62
    if (exponent & 1U) result = result * base % kModulus;
    base = base * base % kModulus;
    exponent >>= 1U;
  }
  return result;
}

}  // namespace

DistortionMode distortion_mode_from_name(const std::string& name) {
  if (name == "none") return DistortionMode::None;
  if (name == "constant") return DistortionMode::Constant;
  if (name == "random") return DistortionMode::Random;
  throw std::invalid_argument("expected none, constant or random, found '" + name + "'");
}

std::string distortion_mode_name(DistortionMode mode) {
  switch (mode) {
    case DistortionMode::Constant: return "constant";
    case DistortionMode::Random: return "random";
    default: return "none";
  }
}

double yade_triangular_variate(std::int64_t seed, std::uint64_t k) {
  if (seed < 1 || seed > kLargestDistortionSeed)
    throw std::invalid_argument("distortion seed must be an integer in [1, 2147483646], got " + std::to_string(seed));
  const std::uint64_t x = static_cast<std::uint64_t>(seed) * power_mod(kMultiplier, k + 1) % kModulus;
  // boost::uniform_01 on an integer engine (min 1, max m - 1): (x - min) * (1 / (max - min + 1)).
  const double factor = 1.0 / static_cast<double>(kModulus - 1);
  const double u = static_cast<double>(x - 1) * factor;
  // boost::triangle_distribution(a = 0, b = 0.5, c = 1): d1 = 0.5, d2 = 1, d3 = sqrt(0.5),
  // q1 = 0.5, p1 = sqrt(0.5); the same operations in the same order.
  const double d1 = 0.5, d2 = 1.0, d3 = std::sqrt(0.5), q1 = 0.5, p1 = std::sqrt(0.5);
  if (u <= q1) return 0.0 + p1 * std::sqrt(u);
  return 1.0 - d3 * std::sqrt(d2 * u - d1);
}

double distortion_variate(const Distortion& distortion, std::uint64_t link_index) {
  switch (distortion.mode) {
    case DistortionMode::Constant: return 1.0;
    case DistortionMode::Random: return yade_triangular_variate(distortion.seed, link_index);
    default: return 0.0;
  }
}

DistortedLaw::DistortedLaw(std::unique_ptr<ContactLaw> wrapped, double slack)
    : wrapped_(std::move(wrapped)), slack_(slack) {
  if (!wrapped_) throw std::invalid_argument("distortion: no law to wrap");
  if (!(slack_ >= 0.0) || !std::isfinite(slack_))
    throw std::invalid_argument("distortion: the slack must be finite and >= 0, got " + std::to_string(slack_));
}

DistortedLaw::DistortedLaw(const DistortedLaw& other)
    : ContactLaw(other), wrapped_(other.wrapped_->clone()), slack_(other.slack_), axial_(other.axial_) {}

void DistortedLaw::update(const Vector6& displacement_increment) {
  const double before = std::max(axial_ - slack_, 0.0);
  axial_ += displacement_increment(0);
  Vector6 fed = displacement_increment;
  fed(0) = std::max(axial_ - slack_, 0.0) - before;
  wrapped_->update(fed);
}

Vector6 DistortedLaw::forces() const {
  Vector6 result = wrapped_->forces();
  if (axial_ < slack_) result(0) = 0.0;
  return result;
}

}  // namespace dtwire::dem
