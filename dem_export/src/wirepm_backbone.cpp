// Per-bond WirePM curve: the engineering backbone turned into force-elongation points, the
// Bertrand et al. 2008 double-twist scaling and the Thoeni et al. 2013 stochastic distortion.
#include <cmath>
#include <stdexcept>
#include <string>

#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr const char* kLaw = "wirepm";

double optional_parameter(const ParameterMap& parameters, const std::string& field, double fallback) {
  const auto found = parameters.find(field);
  return found == parameters.end() ? fallback : found->second;
}

double finite_parameter(const ParameterMap& parameters, const std::string& field) {
  const double value = require_parameter(parameters, kLaw, field);
  if (!std::isfinite(value)) throw std::invalid_argument(std::string(kLaw) + ": '" + field + "' is not finite");
  return value;
}

void require_positive(double value, const std::string& field) {
  if (!(value > 0.0))
    throw std::invalid_argument(std::string(kLaw) + ": '" + field + "' must be > 0, got " + std::to_string(value));
}

void require_flag(double value, const std::string& field) {
  if (value != 0.0 && value != 1.0)
    throw std::invalid_argument(std::string(kLaw) + ": '" + field + "' must be 0 or 1");
}

struct StrainStress {
  double strain;
  double stress;
};

std::vector<StrainStress> read_curve(const ParameterMap& parameters) {
  std::vector<StrainStress> curve;
  for (std::size_t i = 0;; ++i) {
    const std::string strain_key = "backbone_" + std::to_string(i) + "_strain_1";
    const std::string stress_key = "backbone_" + std::to_string(i) + "_stress_Pa";
    if (!parameters.count(strain_key)) break;
    const StrainStress point{finite_parameter(parameters, strain_key), finite_parameter(parameters, stress_key)};
    if (point.strain == 0.0 && point.stress == 0.0 && curve.empty()) continue;  // the origin is implicit
    if (!(point.strain > (curve.empty() ? 0.0 : curve.back().strain)))
      throw std::invalid_argument(std::string(kLaw) + ": '" + strain_key +
                                  "' must be > 0 and greater than the previous strain");
    if (!(point.stress > 0.0)) throw std::invalid_argument(std::string(kLaw) + ": '" + stress_key + "' must be > 0");
    curve.push_back(point);
  }
  if (curve.size() < 2)
    throw std::invalid_argument(std::string(kLaw) +
                                ": need at least two backbone points besides the origin "
                                "(backbone_<i>_strain_1, backbone_<i>_stress_Pa)");
  return curve;
}

std::uint64_t splitmix64(std::uint64_t state) {
  // Steele, Lea and Flood 2014 (the finaliser of SplittableRandom).
  std::uint64_t z = state + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double distortion_variate(const ParameterMap& parameters) {
  const double seed = optional_parameter(parameters, "seed", 0.0);
  if (seed == -1.0) return 1.0;  // YADE's seed = -1: the full shift lambda_u l0
  if (!(seed >= 0.0) || seed != std::floor(seed) || seed > 9007199254740992.0)
    throw std::invalid_argument(std::string(kLaw) + ": 'seed' must be -1 or an integer in [0, 2^53]");
  return triangular_variate_from_seed(static_cast<std::uint64_t>(seed));
}

}  // namespace

double triangular_variate_from_seed(std::uint64_t seed) {
  const double uniform = static_cast<double>(splitmix64(seed) >> 11) * 0x1.0p-53;  // [0, 1)
  // Inverse CDF of the triangular distribution on [0, 1] with mode 0.5.
  return uniform < 0.5 ? std::sqrt(uniform / 2.0) : 1.0 - std::sqrt((1.0 - uniform) / 2.0);
}

WirePmBackbone make_wirepm_backbone(const ParameterMap& parameters) {
  const double reference_length = finite_parameter(parameters, "reference_length_m");
  const double diameter = finite_parameter(parameters, "diameter_m");
  require_positive(reference_length, "reference_length_m");
  require_positive(diameter, "diameter_m");
  const double double_twist = optional_parameter(parameters, "double_twist", 0.0);
  const double double_twist_model = optional_parameter(parameters, "double_twist_model", 0.0);
  require_flag(double_twist, "double_twist");
  require_flag(double_twist_model, "double_twist_model");
  const double lambda_u = optional_parameter(parameters, "lambda_u", 0.0);
  const double lambda_f = optional_parameter(parameters, "lambda_F", 1.0);
  if (!(lambda_u >= 0.0)) throw std::invalid_argument(std::string(kLaw) + ": 'lambda_u' must be >= 0");
  if (!(lambda_f >= 0.0 && lambda_f <= 1.0))
    throw std::invalid_argument(std::string(kLaw) + ": 'lambda_F' must be in [0, 1]");
  const std::vector<StrainStress> curve = read_curve(parameters);

  // Thoeni 2013: shift dL = lambda_u l0 r; the strains then refer to l0 + dL (as in YADE).
  const double shift = lambda_u > 0.0 ? lambda_u * reference_length * distortion_variate(parameters) : 0.0;
  const double length = reference_length + shift;
  const double wire_area = kPi * diameter * diameter / 4.0;
  const bool own_double_twist_curve = double_twist == 1.0 && double_twist_model == 1.0;
  const double area = own_double_twist_curve ? 2.0 * wire_area : wire_area;

  std::vector<ForceElongationPoint> points;  // unshifted elongations for now
  for (const StrainStress& p : curve) points.push_back({p.strain * length, p.stress * area});
  double stiffness = points.front().force / points.front().elongation;

  if (double_twist == 1.0 && double_twist_model == 0.0) {
    // Bertrand et al. 2008: helix of the twist, stiffness of the helix k_h mixed by lambda_k,
    // failure strains scaled by lambda_eps.
    const double lambda_k = optional_parameter(parameters, "lambda_k", 0.73);
    const double lambda_eps = optional_parameter(parameters, "lambda_eps", 0.47);
    const double poisson = optional_parameter(parameters, "poisson_1", 0.3);
    if (!(lambda_k >= 0.0 && lambda_k <= 1.0)) throw std::invalid_argument(std::string(kLaw) + ": 'lambda_k' must be in [0, 1]");
    if (!(lambda_eps > 0.0)) throw std::invalid_argument(std::string(kLaw) + ": 'lambda_eps' must be > 0");
    if (!(poisson > -1.0 && poisson < 0.5)) throw std::invalid_argument(std::string(kLaw) + ": 'poisson_1' must be in (-1, 0.5)");
    const double alpha = std::atan(length / (3.0 * kPi * diameter));
    const double tan_alpha = std::tan(alpha);
    const double helix_stiffness = stiffness * (length * diameter / wire_area) /
                                   (48.0 * std::cos(alpha) *
                                    (41.0 / 9.0 * (1.0 + poisson) + 17.0 / 4.0 * tan_alpha * tan_alpha));
    const double twist_stiffness = 2.0 * (lambda_k * helix_stiffness + (1.0 - lambda_k) * stiffness);
    const double force_scale = twist_stiffness / stiffness;
    points.front().force *= force_scale;
    for (std::size_t i = 1; i < points.size(); ++i) {
      points[i].elongation *= lambda_eps;
      points[i].force *= force_scale;
    }
    stiffness = twist_stiffness;
    for (std::size_t i = 1; i < points.size(); ++i)
      if (!(points[i].elongation > points[i - 1].elongation))
        throw std::invalid_argument(std::string(kLaw) +
                                    ": 'lambda_eps' makes the double-twist elongations non-increasing");
  }

  WirePmBackbone backbone;
  backbone.unloading_stiffness = stiffness;
  backbone.shift = shift;
  backbone.points.push_back({0.0, 0.0});
  if (lambda_f < 1.0 && (shift > 0.0 || lambda_f > 0.0))
    // Thoeni 2013: intermediate point giving the soft initial branch.
    backbone.points.push_back({shift + lambda_f * points.front().elongation, lambda_f * points.front().force});
  for (const ForceElongationPoint& p : points) backbone.points.push_back({p.elongation + shift, p.force});
  return backbone;
}

}  // namespace dtwire::dem
