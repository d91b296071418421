#pragma once
// Sparse LU by MUMPS through a PETSc KSP that lives across Newton iterations: while the matrix
// keeps its nonzero pattern, PETSc repeats only the numeric factorisation and reuses MUMPS's
// analysis (ordering and symbolic factorisation), which on the small contact problems here
// costs as much as the factorisation itself. `pattern_changed()` when the matrix is rebuilt.
//
// Lagged factors (Newton-Krylov with a lagged preconditioner; Knoll & Keyes 2004, J. Comput.
// Phys. 193, 357-397): GMRES on the current tangent, preconditioned by the LU factors of
// an earlier one. A forward and a backward substitution cost about 1/20 of a factorisation on the
// level-1 double twist (42k dofs), so a few GMRES iterations replace a factorisation while the
// tangent changes little; when GMRES does not converge within its budget, the tangent is
// factorised anew.
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
  // x = A^-1 b with the factors of the last factorisation (modified Newton). Only when factorised().
  void solve_again(dealii::PETScWrappers::MPI::Vector& x, const dealii::PETScWrappers::MPI::Vector& b);
  // x with |b - A x| <= relative_tolerance |b| by right-preconditioned GMRES with the last factors,
  // in at most maximum_iterations; otherwise (or without factors) A is factorised and x = A^-1 b.
  // Returns the GMRES iterations, 0 when A was factorised.
  unsigned solve_lagged(const dealii::PETScWrappers::MPI::SparseMatrix& A, dealii::PETScWrappers::MPI::Vector& x,
                        const dealii::PETScWrappers::MPI::Vector& b, double relative_tolerance,
                        unsigned maximum_iterations);
  bool factorised() const { return ksp_ != nullptr; }
  // The matrix was rebuilt with another pattern: the factors stay usable by solve_again and
  // solve_lagged; the next factorisation starts with a new analysis.
  void pattern_changed() { pattern_changed_ = true; }
  std::size_t factorisations() const { return factorisations_; }
  void reset();

 private:
  static PetscErrorCode apply_factors(PC pc, Vec x, Vec y);  // GMRES's preconditioner: ksp_'s factors

  MPI_Comm comm_;
  KSP ksp_ = nullptr;    // LU by MUMPS
  KSP gmres_ = nullptr;  // lagged-lu: GMRES preconditioned by ksp_
  bool pattern_changed_ = false;
  std::size_t factorisations_ = 0;
};

}  // namespace dtwire::fem
