// Covariance and identifiability at a least-squares answer.
#include <Eigen/SVD>
#include <numeric>
#include <stdexcept>

#include "ceres_problem.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/lsq/least_squares.hpp"

namespace dtwire::lsq {
namespace {

Eigen::MatrixXd dense(const ceres::CRSMatrix& crs) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row)
    for (int k = crs.rows[static_cast<std::size_t>(row)]; k < crs.rows[static_cast<std::size_t>(row) + 1]; ++k)
      J(row, crs.cols[static_cast<std::size_t>(k)]) = crs.values[static_cast<std::size_t>(k)];
  return J;
}

// Grouped sandwich C (sum_g s_g^2 J_g^T J_g) C with C = (J^T J)^-1 and s_g^2 = sum r_g^2 over
// the group's share of the m - n degrees of freedom. Residuals are weighted by the user, not
// necessarily by their noise, so each group gets its own variance.
Eigen::MatrixXd grouped_sandwich(const Eigen::MatrixXd& C, const Eigen::MatrixXd& J,
                                 const std::vector<double>& r, std::vector<std::size_t> groups) {
  const auto m = J.rows(), n = J.cols();
  if (groups.empty()) groups.push_back(static_cast<std::size_t>(m));
  if (std::accumulate(groups.begin(), groups.end(), std::size_t{0}) != static_cast<std::size_t>(m))
    throw std::invalid_argument("least squares: residual groups do not add up to the residual count");
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(n, n);
  const double dof_share = static_cast<double>(m - n) / static_cast<double>(m);
  Eigen::Index begin = 0;
  for (std::size_t group : groups) {
    const auto size = static_cast<Eigen::Index>(group);
    double ss = 0;
    for (Eigen::Index i = begin; i < begin + size; ++i) ss += r[static_cast<std::size_t>(i)] * r[static_cast<std::size_t>(i)];
    const double variance = ss / (dof_share * static_cast<double>(size));
    const auto Jg = J.middleRows(begin, size);
    meat += variance * Jg.transpose() * Jg;
    begin += size;
  }
  return C * meat * C;
}

}  // namespace

Uncertainty uncertainty_at(const Problem& problem, const Options& options, const std::vector<double>& x_in) {
  const std::size_t n = problem.parameter_count, m = problem.residual_count;
  if (m <= n) throw std::invalid_argument("least squares: the uncertainty needs more residuals than parameters");
  std::vector<double> x = x_in;
  CeresProblem ceres_problem(problem, options, x);
  ceres::CRSMatrix crs;
  Uncertainty out;
  double cost = 0;
  const bool evaluated =
      ceres_problem.problem->Evaluate(ceres::Problem::EvaluateOptions(), &cost, &out.residuals, nullptr, &crs);
  ceres_problem.shared.rethrow_fatal_error();
  if (!evaluated)
    throw ComputationError("the residuals could not be evaluated at the answer: " + ceres_problem.shared.last_failure());
  out.jacobian = dense(crs);

  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.null_space_rank = -1;  // pseudo-inverse: drop directions below the threshold
  covariance_options.min_reciprocal_condition_number = 1e-14;
  covariance_options.num_threads = 1;
  ceres::Covariance covariance(covariance_options);
  const std::vector<std::pair<const double*, const double*>> blocks{{x.data(), x.data()}};
  if (covariance.Compute(blocks, ceres_problem.problem.get())) {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(n, n);
    covariance.GetCovarianceBlock(x.data(), x.data(), c.data());
    out.covariance = grouped_sandwich(c, out.jacobian, out.residuals, problem.residual_groups);
  }

  Eigen::MatrixXd normalised = out.jacobian;
  for (Eigen::Index j = 0; j < normalised.cols(); ++j) {
    const double norm = normalised.col(j).norm();
    if (norm > 0) normalised.col(j) /= norm;
    else out.insensitive.push_back(static_cast<std::size_t>(j));
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(normalised, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  for (Eigen::Index i = 0; i < sv.size(); ++i) out.singular_values.push_back(sv(i));
  out.singular_directions = svd.matrixV();
  return out;
}

}  // namespace dtwire::lsq
