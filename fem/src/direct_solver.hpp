#pragma once
// Sparse LU by MUMPS through a PETSc KSP that lives across Newton iterations: while the matrix
// keeps its nonzero pattern, PETSc repeats only the numeric factorisation and reuses MUMPS's
// analysis (ordering and symbolic factorisation), which on the small contact problems here
// costs as much as the factorisation itself. `reset()` when the matrix is rebuilt.
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <petscksp.h>

namespace dtwire::fem {

class DirectSolver {
 public:
  explicit DirectSolver(MPI_Comm comm) : comm_(comm) {}
  ~DirectSolver() { reset(); }
  DirectSolver(const DirectSolver&) = delete;
  DirectSolver& operator=(const DirectSolver&) = delete;

  // x = A^-1 b; throws std::runtime_error if the factorisation fails (e.g. a zero pivot).
  void solve(const dealii::PETScWrappers::MPI::SparseMatrix& A, dealii::PETScWrappers::MPI::Vector& x,
             const dealii::PETScWrappers::MPI::Vector& b);
  // x = A^-1 b with the factors of the last solve (modified Newton): the matrix must not have
  // been changed since. Only when factorised().
  void solve_again(dealii::PETScWrappers::MPI::Vector& x, const dealii::PETScWrappers::MPI::Vector& b);
  bool factorised() const { return ksp_ != nullptr; }
  void reset();

 private:
  MPI_Comm comm_;
  KSP ksp_ = nullptr;
};

}  // namespace dtwire::fem
