#pragma once
// A Gaussian-process emulator of a model's figure over its parameters, trained on the runs a
// propagation made (`dtwire dem propagate --emulator`), so that the figure's band over many
// thousand parameter sets costs predictions, not runs.
//
// Contract. Inputs are n points x_j in d coordinates of order one (the caller scales them: a
// propagation divides each parameter's sampled coordinate by its sampled spread) and their
// figure f_j (finite). The emulator predicts f at any x with a mean and two variances: the
// latent one (what the n runs leave unknown about the response) and the noise one (the run-
// to-run scatter the response shows at a fixed x, e.g. a DEM net's failure order). A new run's
// figure at x is normal with the mean and the sum of the two.
//
// Algorithm (Sacks, Welch, Mitchell & Wynn 1989, Stat. Sci. 4:409; Rasmussen & Williams 2006,
// Gaussian Processes for Machine Learning, MIT Press, ch. 2 and 5):
//  1. t_j = (f_j - mean f) / sd f. Prior: t is a zero-mean Gaussian process with covariance
//     sigma^2 (R(x, x') + tau delta(x, x')), R the Matern 5/2 correlation with one length
//     scale per coordinate (R&W eq. 4.17; the smoothness Stein 1999 recommends for computer
//     models over the squared exponential), tau the nugget ratio (noise / signal variance).
//  2. A = R(X, X) + tau I, Cholesky-factored. The leave-one-out residuals and variances follow
//     from A^-1 without n refits (R&W eq. 5.12): e_j = [A^-1 t]_j / [A^-1]_jj and
//     v_j = sigma^2 / [A^-1]_jj.
//  3. ln(length scales) and ln(tau) minimise sum e_j^2 (leave-one-out cross-validation, R&W
//     5.4.2) on dtwire's least-squares engine, bounded (kLengthScaleBounds, kNuggetBounds) and
//     from three starts; cross-validation rather than the marginal likelihood because it
//     stays a fair estimator when the correlation family is not the true one (Bachoc 2013,
//     Comput. Stat. Data Anal. 66:55).
//  4. sigma^2 = (1/n) sum e_j^2 [A^-1]_jj (Bachoc 2013's cross-validation estimator: the
//     standardised leave-one-out residuals e_j / sqrt(v_j) then have unit mean square).
//  5. Prediction at x with r = R(X, x): mean = mean f + sd f r^T A^-1 t; latent variance
//     (sd f)^2 sigma^2 (1 - r^T A^-1 r) (>= 0); noise variance (sd f)^2 sigma^2 tau.
// Quality: Q^2 = 1 - sum e_j^2 / sum t_j^2 (the leave-one-out coefficient of determination; 1 is
// a perfect predictor, 0 no better than the mean) and the share of standardised leave-one-out
// residuals within +-2 (about 0.95 when the predicted variances are right).
#include <cstdint>
#include <vector>

#include "dtwire/calibrate/band_statistics.hpp"

namespace dtwire::calibrate {

struct EmulatorPrediction {
  double mean = 0.0;
  double latent_sd = 0.0;  // what the training runs leave unknown
  double noise_sd = 0.0;   // run-to-run scatter at a fixed x
};

// Length scales in the caller's coordinate: below 0.05 the sampled spread holds twenty
// oscillations, which no affordable run count resolves; above 100 the coordinate has no effect
// over it (R varies by < 1e-3 across +-3 spreads).
inline constexpr double kLengthScaleBounds[2] = {0.05, 100.0};
// Nugget ratio: from numerically noise-free (1e-8 keeps A positive definite) to noise as large
// as the signal.
inline constexpr double kNuggetBounds[2] = {1e-8, 1.0};

class GaussianProcessEmulator {
 public:
  // Throws std::invalid_argument for fewer than 3 points, rows of unequal length or a non-finite
  // value. A figure with zero spread gives a constant emulator.
  GaussianProcessEmulator(const std::vector<std::vector<double>>& x, const std::vector<double>& f);

  EmulatorPrediction predict(const std::vector<double>& x) const;

  const std::vector<double>& length_scales() const { return length_scales_; }
  double nugget_ratio() const { return nugget_; }
  // Leave-one-out residual f_j - prediction without j, in the figure's unit, and its sd.
  const std::vector<double>& loo_residuals() const { return loo_residuals_; }
  const std::vector<double>& loo_sd() const { return loo_sd_; }
  double q_squared() const { return q_squared_; }
  double share_within_two_sd() const;  // of the standardised leave-one-out residuals

 private:
  void train(const std::vector<double>& log_hyper);

  std::vector<std::vector<double>> x_;
  std::vector<double> t_;
  double mean_ = 0.0, scale_ = 0.0;  // of f
  std::vector<double> length_scales_;
  double nugget_ = 0.0, variance_ = 0.0;  // tau, sigma^2 (of t)
  std::vector<double> alpha_;              // A^-1 t
  std::vector<std::vector<double>> inverse_;  // A^-1
  std::vector<double> loo_residuals_, loo_sd_;
  double q_squared_ = 1.0;
};

// The figure's band over `points` (drawn from the parameters' distribution, in the emulator's
// coordinates): of the predicted means alone, and of a new run's figure (each mean plus one
// normal draw of its latent and noise sd, from `seed`: std::mt19937_64 and Box-Muller, the same on
// every platform). `logarithmic`: the emulator was trained on ln f (a figure that is a positive
// magnitude, whose band then cannot reach 0), and each value is exp of the draw. The bootstrap
// standard errors of the ends are those of the emulated sample, i.e. of its Monte Carlo count,
// not of the emulator.
struct EmulatedBand {
  BandStatistics of_means;
  BandStatistics with_error;
};
EmulatedBand emulated_band(const GaussianProcessEmulator& emulator, const std::vector<std::vector<double>>& points,
                           std::uint64_t seed, bool logarithmic = false);

// The Matern 5/2 correlation of two points under the given length scales (step 1).
double matern52(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& length_scales);

}  // namespace dtwire::calibrate
