#include "ceres_problem.hpp"

#include <cstring>
#include <stdexcept>

#include "dtwire/core/error.hpp"

namespace dtwire::lsq {
namespace {

// The user's residual function as Ceres' numeric differentiation wants it.
struct ResidualFunctor {
  const Problem* problem;
  bool operator()(double const* const* x, double* r) const {
    std::vector<double> point(x[0], x[0] + problem->parameter_count), residuals;
    problem->residuals(point, residuals);
    if (residuals.size() != problem->residual_count)
      throw ComputationError("residual function returned " + std::to_string(residuals.size()) +
                             " residuals, expected " + std::to_string(problem->residual_count));
    std::copy(residuals.begin(), residuals.end(), r);
    return true;
  }
};

// One residual as a Ceres residual block.
class PointResidual final : public ceres::CostFunction {
 public:
  PointResidual(SharedEvaluation& shared, std::size_t index, int parameter_count)
      : shared_(shared), index_(index) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(parameter_count);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const bool need_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    if (!shared_.evaluate(parameters[0], need_jacobian)) return false;  // Ceres rejects the step
    residuals[0] = shared_.residual(index_);
    if (need_jacobian) {
      const double* row = shared_.jacobian_row(index_);
      std::copy(row, row + parameter_block_sizes()[0], jacobians[0]);
    }
    return true;
  }

 private:
  SharedEvaluation& shared_;
  std::size_t index_;
};

// All residuals as one Ceres residual block.
class WholeResidual final : public ceres::CostFunction {
 public:
  WholeResidual(SharedEvaluation& shared, int residual_count, int parameter_count) : shared_(shared) {
    set_num_residuals(residual_count);
    mutable_parameter_block_sizes()->push_back(parameter_count);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const bool need_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    if (!shared_.evaluate(parameters[0], need_jacobian)) return false;
    const auto m = static_cast<std::size_t>(num_residuals());
    for (std::size_t i = 0; i < m; ++i) residuals[i] = shared_.residual(i);
    if (need_jacobian) std::copy(shared_.jacobian_row(0), shared_.jacobian_row(0) + m * parameter_block_sizes()[0], jacobians[0]);
    return true;
  }

 private:
  SharedEvaluation& shared_;
};

ceres::LossFunction* make_loss(const Options& options) {
  switch (options.loss) {
    case Loss::Huber: return new ceres::HuberLoss(options.loss_scale);
    case Loss::Cauchy: return new ceres::CauchyLoss(options.loss_scale);
    case Loss::Squared: break;
  }
  return nullptr;
}

}  // namespace

SharedEvaluation::SharedEvaluation(const Problem& problem) : problem_(problem) {
  if (problem.residuals_and_jacobian) return;
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = problem.difference_step;
  auto* cost = new ceres::DynamicNumericDiffCostFunction<ResidualFunctor, ceres::CENTRAL>(
      new ResidualFunctor{&problem}, ceres::TAKE_OWNERSHIP, diff);
  cost->AddParameterBlock(static_cast<int>(problem.parameter_count));
  cost->SetNumResiduals(static_cast<int>(problem.residual_count));
  differences_.reset(cost);
}

void SharedEvaluation::compute(bool need_jacobian) {
  const std::size_t n = problem_.parameter_count, m = problem_.residual_count;
  if (problem_.residuals_and_jacobian && need_jacobian) {
    problem_.residuals_and_jacobian(x_, residuals_, jacobian_);
  } else if (!need_jacobian) {
    problem_.residuals(x_, residuals_);
  } else {
    residuals_.resize(m);
    jacobian_.resize(m * n);
    const double* parameters[] = {x_.data()};
    double* jacobians[] = {jacobian_.data()};
    if (!differences_->Evaluate(parameters, residuals_.data(), jacobians))
      throw ComputationError("central differences could not be evaluated");
  }
  if (residuals_.size() != m || (need_jacobian && jacobian_.size() != m * n))
    throw ComputationError("residual function returned the wrong number of residuals or Jacobian entries");
}

bool SharedEvaluation::evaluate(const double* x, bool need_jacobian) {
  if (fatal_) return false;
  const std::size_t n = problem_.parameter_count;
  const bool same = valid_ && std::memcmp(x, x_.data(), n * sizeof(double)) == 0;
  if (same && (!need_jacobian || has_jacobian_)) return !failed_;
  x_.assign(x, x + n);
  valid_ = true;
  has_jacobian_ = need_jacobian;
  failed_ = false;
  try {
    compute(need_jacobian);
  } catch (const ComputationError& error) {
    failed_ = true;
    last_failure_ = error.what();
  } catch (...) {
    failed_ = true;
    fatal_ = std::current_exception();  // not a bad point: ends the solve, rethrown after it
  }
  return !failed_;
}

void SharedEvaluation::rethrow_fatal_error() const {
  if (fatal_) std::rethrow_exception(fatal_);
}

CeresProblem::CeresProblem(const Problem& p, const Options& options, std::vector<double>& x) : shared(p) {
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  problem = std::make_unique<ceres::Problem>(problem_options);
  const int n = static_cast<int>(x.size());
  if (options.block_per_residual) {
    for (std::size_t i = 0; i < p.residual_count; ++i)
      problem->AddResidualBlock(new PointResidual(shared, i, n), make_loss(options), x.data());
  } else {
    if (options.loss != Loss::Squared)
      throw std::invalid_argument("least squares: a robust loss needs one residual block per residual");
    problem->AddResidualBlock(new WholeResidual(shared, static_cast<int>(p.residual_count), n), nullptr, x.data());
  }
  for (int j = 0; j < n; ++j) {
    if (!p.lower.empty()) problem->SetParameterLowerBound(x.data(), j, p.lower[static_cast<std::size_t>(j)]);
    if (!p.upper.empty()) problem->SetParameterUpperBound(x.data(), j, p.upper[static_cast<std::size_t>(j)]);
  }
}

}  // namespace dtwire::lsq
