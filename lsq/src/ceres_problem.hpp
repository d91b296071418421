#pragma once
// The Ceres side of the engine: one shared evaluation of all residuals (and the Jacobian) at
// the point Ceres asks for, served to one residual block per residual so that robust losses act
// point by point.
#include <ceres/ceres.h>

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "dtwire/lsq/least_squares.hpp"

namespace dtwire::lsq {

class SharedEvaluation {
 public:
  explicit SharedEvaluation(const Problem& problem);

  // False when the point cannot be evaluated (a ComputationError, or another error that ends
  // the solve: see rethrow_fatal_error).
  bool evaluate(const double* x, bool need_jacobian);
  double residual(std::size_t i) const { return residuals_[i]; }
  const double* jacobian_row(std::size_t i) const { return jacobian_.data() + i * problem_.parameter_count; }
  const std::string& last_failure() const { return last_failure_; }
  bool has_fatal_error() const { return static_cast<bool>(fatal_); }
  void rethrow_fatal_error() const;

 private:
  void compute(bool need_jacobian);

  const Problem& problem_;
  std::unique_ptr<ceres::DynamicCostFunction> differences_;  // central differences of residuals
  std::vector<double> x_, residuals_, jacobian_;
  bool valid_ = false, has_jacobian_ = false, failed_ = false;
  std::string last_failure_;
  std::exception_ptr fatal_;
};

// The problem on the parameter block x (owned by the caller), with bounds and the loss.
struct CeresProblem {
  CeresProblem(const Problem& problem, const Options& options, std::vector<double>& x);
  SharedEvaluation shared;
  std::unique_ptr<ceres::Problem> problem;
};

}  // namespace dtwire::lsq
