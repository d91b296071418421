#include "dtwire/calibrate/emulator.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "dtwire/core/error.hpp"
#include "dtwire/lsq/least_squares.hpp"

namespace dtwire::calibrate {
namespace {

struct Factored {
  Eigen::LLT<Eigen::MatrixXd> llt;
  Eigen::VectorXd alpha;           // A^-1 t
  Eigen::VectorXd inverse_diagonal;  // diag(A^-1) = column sums of squares of L^-1
};

// A = R(X, X) + tau I and its inverse; ComputationError (the engine then shortens its step)
// where the factorisation fails.
Factored factor(const std::vector<std::vector<double>>& x, const std::vector<double>& t,
                const std::vector<double>& length_scales, double nugget) {
  const auto n = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd a(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    a(i, i) = 1.0 + nugget;
    for (Eigen::Index j = 0; j < i; ++j)
      a(i, j) = a(j, i) = matern52(x[static_cast<std::size_t>(i)], x[static_cast<std::size_t>(j)], length_scales);
  }
  Factored out;
  out.llt.compute(a);
  if (out.llt.info() != Eigen::Success) throw ComputationError("emulator: the correlation matrix is not positive definite");
  out.alpha = out.llt.solve(Eigen::Map<const Eigen::VectorXd>(t.data(), n));
  const Eigen::MatrixXd l_inverse = out.llt.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
  out.inverse_diagonal = l_inverse.colwise().squaredNorm().transpose();
  return out;
}

}  // namespace

double matern52(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& length_scales) {
  double r2 = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double d = (a[k] - b[k]) / length_scales[k];
    r2 += d * d;
  }
  const double s = std::sqrt(5.0 * r2);
  return (1.0 + s + s * s / 3.0) * std::exp(-s);
}

GaussianProcessEmulator::GaussianProcessEmulator(const std::vector<std::vector<double>>& x, const std::vector<double>& f)
    : x_(x) {
  if (x.size() < 3 || f.size() != x.size()) throw std::invalid_argument("emulator: needs at least 3 points, one figure each");
  const std::size_t d = x.front().size();
  for (const auto& row : x) {
    if (row.size() != d) throw std::invalid_argument("emulator: points of unequal length");
    for (double v : row)
      if (!std::isfinite(v)) throw std::invalid_argument("emulator: a coordinate is not finite");
  }
  for (double v : f)
    if (!std::isfinite(v)) throw std::invalid_argument("emulator: a figure is not finite");
  length_scales_.assign(d, kLengthScaleBounds[1]);
  loo_residuals_.assign(f.size(), 0.0);
  loo_sd_.assign(f.size(), 0.0);
  mean_ = f.front();
  if (std::all_of(f.begin(), f.end(), [&](double v) { return v == mean_; })) return;  // constant: no spread
  // Shifted by the first value, so that the sums stay small (band_statistics.cpp does the same).
  const double n = static_cast<double>(f.size());
  double shift = 0.0;
  for (double v : f) shift += (v - f.front()) / n;
  mean_ = f.front() + shift;
  double square = 0.0;
  for (double v : f) square += (v - mean_) * (v - mean_);
  scale_ = std::sqrt(square / (n - 1.0));
  for (double v : f) t_.push_back((v - mean_) / scale_);

  // Step 3: ln(length scales), ln(tau) by leave-one-out cross-validation.
  lsq::Problem problem;
  problem.parameter_count = d + 1;
  problem.residual_count = f.size();
  problem.lower.assign(d, std::log(kLengthScaleBounds[0]));
  problem.upper.assign(d, std::log(kLengthScaleBounds[1]));
  problem.lower.push_back(std::log(kNuggetBounds[0]));
  problem.upper.push_back(std::log(kNuggetBounds[1]));
  problem.residuals = [this, d](const std::vector<double>& p, std::vector<double>& residuals) {
    std::vector<double> scales(d);
    for (std::size_t k = 0; k < d; ++k) scales[k] = std::exp(p[k]);
    const Factored fa = factor(x_, t_, scales, std::exp(p[d]));
    residuals.resize(t_.size());
    for (std::size_t j = 0; j < t_.size(); ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      residuals[j] = fa.alpha(jj) / fa.inverse_diagonal(jj);
    }
  };
  problem.difference_step = 1e-4;
  lsq::Options options;
  options.max_iterations = 100;
  std::vector<std::vector<double>> starts;
  for (const auto& [scale, nugget] : {std::pair{1.0, 1e-2}, std::pair{3.0, 1e-4}, std::pair{0.5, 1e-1}}) {
    std::vector<double> start(d, std::log(scale));
    start.push_back(std::log(nugget));
    starts.push_back(start);
  }
  const lsq::Summary summary = lsq::solve(problem, options, lsq::starts_at(starts));
  if (!summary.best) throw ComputationError("emulator: no start of the cross-validation fit ended");
  train(summary.x);
}

void GaussianProcessEmulator::train(const std::vector<double>& log_hyper) {
  const std::size_t d = log_hyper.size() - 1;
  for (std::size_t k = 0; k < d; ++k) length_scales_[k] = std::exp(log_hyper[k]);
  nugget_ = std::exp(log_hyper[d]);
  const Factored fa = factor(x_, t_, length_scales_, nugget_);
  const std::size_t n = t_.size();
  alpha_.assign(fa.alpha.data(), fa.alpha.data() + n);
  const Eigen::MatrixXd inverse = fa.llt.solve(Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n)));
  inverse_.assign(n, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) inverse_[i][j] = inverse(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  // Step 4 and the quality figures.
  double sum = 0.0, squares = 0.0, total = 0.0;
  std::vector<double> e(n);
  for (std::size_t j = 0; j < n; ++j) {
    e[j] = alpha_[j] / inverse_[j][j];
    sum += e[j] * e[j] * inverse_[j][j];
    squares += e[j] * e[j];
    total += t_[j] * t_[j];
  }
  variance_ = sum / static_cast<double>(n);
  q_squared_ = total > 0.0 ? 1.0 - squares / total : 1.0;
  for (std::size_t j = 0; j < n; ++j) {
    loo_residuals_[j] = scale_ * e[j];
    loo_sd_[j] = scale_ * std::sqrt(variance_ / inverse_[j][j]);
  }
}

EmulatorPrediction GaussianProcessEmulator::predict(const std::vector<double>& x) const {
  EmulatorPrediction p;
  p.mean = mean_;
  if (t_.empty()) return p;
  if (x.size() != length_scales_.size()) throw std::invalid_argument("emulator: a point of the wrong length");
  const std::size_t n = t_.size();
  std::vector<double> r(n);
  for (std::size_t j = 0; j < n; ++j) r[j] = matern52(x_[j], x, length_scales_);
  double mean = 0.0, explained = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mean += r[i] * alpha_[i];
    double row = 0.0;
    for (std::size_t j = 0; j < n; ++j) row += inverse_[i][j] * r[j];
    explained += r[i] * row;
  }
  p.mean = mean_ + scale_ * mean;
  p.latent_sd = scale_ * std::sqrt(variance_ * std::max(0.0, 1.0 - explained));
  p.noise_sd = scale_ * std::sqrt(variance_ * nugget_);
  return p;
}

EmulatedBand emulated_band(const GaussianProcessEmulator& emulator, const std::vector<std::vector<double>>& points,
                           std::uint64_t seed, bool logarithmic) {
  if (points.empty()) throw std::invalid_argument("emulated_band: no points");
  std::mt19937_64 generator(seed);
  const auto uniform = [&] { return (static_cast<double>(generator() >> 11) + 0.5) * 0x1.0p-53; };
  std::vector<double> means, drawn;
  for (const auto& x : points) {
    const EmulatorPrediction p = emulator.predict(x);
    const double z = std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * M_PI * uniform());
    const double value = p.mean + std::hypot(p.latent_sd, p.noise_sd) * z;
    means.push_back(logarithmic ? std::exp(p.mean) : p.mean);
    drawn.push_back(logarithmic ? std::exp(value) : value);
  }
  return {band_statistics(means, seed, 200), band_statistics(drawn, seed, 200)};
}

double GaussianProcessEmulator::share_within_two_sd() const {
  if (loo_residuals_.empty()) return 1.0;
  std::size_t within = 0;
  for (std::size_t j = 0; j < loo_residuals_.size(); ++j)
    if (loo_sd_[j] == 0.0 ? loo_residuals_[j] == 0.0 : std::abs(loo_residuals_[j]) <= 2.0 * loo_sd_[j]) ++within;
  return static_cast<double>(within) / static_cast<double>(loo_residuals_.size());
}

}  // namespace dtwire::calibrate
