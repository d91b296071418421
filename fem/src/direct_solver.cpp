#include "direct_solver.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

// OpenBLAS's own call, when the BLAS loaded is OpenBLAS (Debian's default); null otherwise.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace dtwire::fem {
namespace {

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc error in ") + what + " (" + std::to_string(code) + ")");
}

// One BLAS thread per process unless OPENBLAS_NUM_THREADS says otherwise. OpenBLAS starts one
// thread per core in every process and its idle threads spin; MUMPS's fronts here are small
// (level-0 DT: 6426 dofs), so alone the second thread gains nothing (103 s vs 101 s to failure),
// while two runs side by side on 2 cores (campaign --jobs 2, ctest -j2) spun each other's cores:
// solve 342 s -> 42 s, run 528 s -> 152 s (docs/fem_dt.md, "Speed").
void use_one_blas_thread_unless_asked() {
  static const bool once = [] {
    if (openblas_set_num_threads && !std::getenv("OPENBLAS_NUM_THREADS")) openblas_set_num_threads(1);
    return true;
  }();
  (void)once;
}

}  // namespace

void DirectSolver::reset() {
  if (gmres_) KSPDestroy(&gmres_);
  gmres_ = nullptr;
  if (ksp_) KSPDestroy(&ksp_);
  ksp_ = nullptr;
  pattern_changed_ = false;
}

void DirectSolver::solve(const dealii::PETScWrappers::MPI::SparseMatrix& A, dealii::PETScWrappers::MPI::Vector& x,
                         const dealii::PETScWrappers::MPI::Vector& b) {
  if (pattern_changed_) reset();  // PETSc would take the new pattern's matrix for the old one
  if (!ksp_) {
    use_one_blas_thread_unless_asked();
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
  check(KSPSetReusePreconditioner(ksp_, PETSC_FALSE), "KSPSetReusePreconditioner");
  check(KSPSetOperators(ksp_, A, A), "KSPSetOperators");
  check(KSPSolve(ksp_, b, x), "KSPSolve");
  ++factorisations_;
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
  if (reason < 0) {
    reset();  // a failed factorisation is not reused
    throw std::runtime_error("MUMPS factorisation failed (KSP reason " + std::to_string(reason) + ")");
  }
}

void DirectSolver::solve_again(dealii::PETScWrappers::MPI::Vector& x, const dealii::PETScWrappers::MPI::Vector& b) {
  // The matrix the factors came from may have been reassembled since: keep the factors.
  check(KSPSetReusePreconditioner(ksp_, PETSC_TRUE), "KSPSetReusePreconditioner");
  check(KSPSolve(ksp_, b, x), "KSPSolve");
}

// PETSc's GMRES, not deal.II's: deal.II's solvers keep a global pool of PETSc vectors that the
// command line's static MPI_InitFinalize would release after the pool is gone (a crash at exit).
unsigned DirectSolver::solve_lagged(const dealii::PETScWrappers::MPI::SparseMatrix& A,
                                    dealii::PETScWrappers::MPI::Vector& x, const dealii::PETScWrappers::MPI::Vector& b,
                                    double relative_tolerance, unsigned maximum_iterations) {
  if (factorised()) {
    if (!gmres_) {
      check(KSPCreate(comm_, &gmres_), "KSPCreate");
      check(KSPSetType(gmres_, KSPGMRES), "KSPSetType");
      // Right preconditioning: the criterion is on the true residual b - A x.
      check(KSPSetPCSide(gmres_, PC_RIGHT), "KSPSetPCSide");
      check(KSPSetNormType(gmres_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
      PC pc;
      check(KSPGetPC(gmres_, &pc), "KSPGetPC");
      check(PCSetType(pc, PCSHELL), "PCSetType");
      check(PCShellSetContext(pc, this), "PCShellSetContext");
      check(PCShellSetApply(pc, &DirectSolver::apply_factors), "PCShellSetApply");
    }
    check(KSPGMRESSetRestart(gmres_, static_cast<PetscInt>(maximum_iterations) + 1), "KSPGMRESSetRestart");
    check(KSPSetTolerances(gmres_, relative_tolerance, 0.0, PETSC_DEFAULT, static_cast<PetscInt>(maximum_iterations)),
          "KSPSetTolerances");
    check(KSPSetOperators(gmres_, A, A), "KSPSetOperators");
    check(KSPSolve(gmres_, b, x), "KSPSolve");
    KSPConvergedReason reason;
    PetscInt iterations = 0;
    check(KSPGetConvergedReason(gmres_, &reason), "KSPGetConvergedReason");
    check(KSPGetIterationNumber(gmres_, &iterations), "KSPGetIterationNumber");
    if (reason > 0) return std::max<unsigned>(1, static_cast<unsigned>(iterations));
    // the factors are too old for this tangent: a new factorisation below
  }
  solve(A, x, b);
  return 0;
}

PetscErrorCode DirectSolver::apply_factors(PC pc, Vec x, Vec y) {
  void* context = nullptr;
  PetscErrorCode code = PCShellGetContext(pc, &context);
  if (code != 0) return code;
  KSP factors = static_cast<DirectSolver*>(context)->ksp_;
  code = KSPSetReusePreconditioner(factors, PETSC_TRUE);
  return code != 0 ? code : KSPSolve(factors, x, y);
}

}  // namespace dtwire::fem
