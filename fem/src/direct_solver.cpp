#include "direct_solver.hpp"

#include <stdexcept>
#include <string>

namespace dtwire::fem {
namespace {

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc error in ") + what + " (" + std::to_string(code) + ")");
}

}  // namespace

void DirectSolver::reset() {
  if (ksp_) KSPDestroy(&ksp_);
  ksp_ = nullptr;
}

void DirectSolver::solve(const dealii::PETScWrappers::MPI::SparseMatrix& A, dealii::PETScWrappers::MPI::Vector& x,
                         const dealii::PETScWrappers::MPI::Vector& b) {
  if (!ksp_) {
    check(KSPCreate(comm_, &ksp_), "KSPCreate");
    check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
    PC pc;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    check(PCSetType(pc, PCLU), "PCSetType");
    check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    check(KSPSetErrorIfNotConverged(ksp_, PETSC_FALSE), "KSPSetErrorIfNotConverged");
    // Fill-reducing ordering (ICNTL(7)): approximate minimum degree (0) on small problems, where
    // it factorises 15 % faster than PORD (4) on the level-0 DT mesh (6426 dofs); PORD's nested
    // dissection above 20000 dofs, where it factorises 1.5x faster than AMD (level-1 DT, 42066
    // dofs; measured, dt_tension to 0.9 mm). Debian's MUMPS has no METIS or SCOTCH ordering in
    // its sequential analysis: asked for them (5, 3) it uses PORD. Set in PETSc's options
    // database, which MUMPS reads at each solver's first factorisation, unless PETSC_OPTIONS
    // (e.g. -mat_mumps_icntl_7 2) chose it when the process started.
    static const bool chosen_by_user = [] {
      PetscBool set = PETSC_FALSE;
      check(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_7", &set), "PetscOptionsHasName");
      return set == PETSC_TRUE;
    }();
    if (!chosen_by_user)
      check(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_7", A.m() > 20000 ? "4" : "0"), "PetscOptionsSetValue");
    check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  }
  // Same Mat object with the same nonzero state: PETSc keeps the symbolic factorisation.
  check(KSPSetOperators(ksp_, A, A), "KSPSetOperators");
  check(KSPSolve(ksp_, b, x), "KSPSolve");
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
  if (reason < 0) {
    reset();  // a failed factorisation is not reused
    throw std::runtime_error("MUMPS factorisation failed (KSP reason " + std::to_string(reason) + ")");
  }
}

void DirectSolver::solve_again(dealii::PETScWrappers::MPI::Vector& x, const dealii::PETScWrappers::MPI::Vector& b) {
  check(KSPSolve(ksp_, b, x), "KSPSolve");
}

}  // namespace dtwire::fem
