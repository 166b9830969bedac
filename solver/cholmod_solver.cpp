// SPDX-License-Identifier: MIT
#include "solver/cholmod_solver.hpp"

#include "mesh/error.hpp"
#include "solver/threads.hpp"

#include <cholmod.h>

#include <cstring>
#include <optional>
#include <string>

namespace nmm {

const char* to_string(SolveStatus status) {
  switch (status) {
  case SolveStatus::ok:
    return "ok";
  case SolveStatus::not_positive_definite:
    return "matrix not positive definite";
  case SolveStatus::failed:
    return "linear solver failed";
  }
  return "unknown";
}

struct CholmodSolver::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_dense* solution = nullptr; // solve2 workspaces, reused across solves
  cholmod_dense* work_y = nullptr;
  cholmod_dense* work_e = nullptr;
  long n = -1;
  long failed_column = -1;
  double flops = 0.0;
  double single_thread_flops = default_single_thread_flops;
  SolverCounters counters;

  /// BLAS on one thread while it lives when the factor is small (set_single_thread_flops()):
  /// for its factorization and for the solves with it alike.
  [[nodiscard]] std::optional<SingleBlasThread> single_thread_if_small() const {
    return flops < single_thread_flops ? std::optional<SingleBlasThread>(std::in_place)
                                       : std::optional<SingleBlasThread>();
  }

  Impl() {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.print = 0;
    common.error_handler = nullptr; // errors come back through common.status
  }
  ~Impl() {
    cholmod_free_factor(&factor, &common);
    cholmod_free_dense(&solution, &common);
    cholmod_free_dense(&work_y, &common);
    cholmod_free_dense(&work_e, &common);
    cholmod_finish(&common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  Impl(Impl&&) = delete;
  Impl& operator=(Impl&&) = delete;

  // A non-owning CHOLMOD view of an Eigen matrix: stype = 1, only the upper triangle read.
  static cholmod_sparse view(const SparseMatrix& matrix) {
    cholmod_sparse a{};
    a.nrow = static_cast<std::size_t>(matrix.rows());
    a.ncol = static_cast<std::size_t>(matrix.cols());
    a.nzmax = static_cast<std::size_t>(matrix.nonZeros());
    // CHOLMOD's C interface takes non-const pointers but does not write through them here.
    a.p = const_cast<int*>(matrix.outerIndexPtr()); // NOLINT(cppcoreguidelines-pro-type-const-cast)
    a.i = const_cast<int*>(matrix.innerIndexPtr()); // NOLINT(cppcoreguidelines-pro-type-const-cast)
    a.x = const_cast<double*>(matrix.valuePtr());   // NOLINT(cppcoreguidelines-pro-type-const-cast)
    a.stype = 1;
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    return a;
  }
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>()) {}
CholmodSolver::~CholmodSolver() = default;

SolveStatus CholmodSolver::analyze(const SparseMatrix& matrix) {
  NMM_ASSERT(matrix.rows() == matrix.cols(), "CHOLMOD needs a square matrix");
  NMM_ASSERT(matrix.isCompressed(), "CHOLMOD needs a compressed matrix");
  cholmod_free_factor(&impl_->factor, &impl_->common);
  cholmod_sparse a = Impl::view(matrix);
  impl_->factor = cholmod_analyze(&a, &impl_->common);
  if (impl_->factor == nullptr || impl_->common.status < CHOLMOD_OK)
    return SolveStatus::failed;
  impl_->n = matrix.rows();
  impl_->flops = impl_->common.fl;
  ++impl_->counters.symbolic_analyses;
  return SolveStatus::ok;
}

SolveStatus CholmodSolver::factorize(const SparseMatrix& matrix) {
  if (impl_->factor == nullptr || matrix.rows() != impl_->n)
    return SolveStatus::failed;
  cholmod_sparse a = Impl::view(matrix);
  const auto single = impl_->single_thread_if_small();
  const int ok = cholmod_factorize(&a, impl_->factor, &impl_->common);
  impl_->failed_column = -1;
  if (impl_->common.status == CHOLMOD_NOT_POSDEF ||
      (ok != 0 && impl_->factor->minor < impl_->factor->n)) {
    // minor counts columns of the permuted matrix: map it back to the matrix's own column.
    const auto minor = static_cast<std::size_t>(impl_->factor->minor);
    const auto* permutation = static_cast<const int*>(impl_->factor->Perm);
    impl_->failed_column = permutation != nullptr && minor < impl_->factor->n
                               ? permutation[minor]
                               : static_cast<long>(minor);
    return SolveStatus::not_positive_definite;
  }
  if (ok == 0 || impl_->common.status < CHOLMOD_OK)
    return SolveStatus::failed;
  ++impl_->counters.factorizations;
  return SolveStatus::ok;
}

SolveStatus CholmodSolver::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& solution) {
  if (impl_->factor == nullptr || rhs.size() != impl_->n || impl_->failed_column >= 0) {
    return SolveStatus::failed;
  }
  cholmod_dense b{};
  b.nrow = static_cast<std::size_t>(rhs.size());
  b.ncol = 1;
  b.nzmax = b.nrow;
  b.d = b.nrow;
  b.x = const_cast<double*>(rhs.data()); // NOLINT(cppcoreguidelines-pro-type-const-cast)
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  // The triangular solves of a factor that was made on one thread run on one thread too:
  // OpenBLAS parallelises their larger dgemv calls, and the second thread it wakes for them
  // then spins in sched_yield between the solve's calls (3.3 s of system time in a 3.6 s run
  // of a 1,003-block rock mass, at the same speed), and the result depends on the thread
  // count.
  const auto single = impl_->single_thread_if_small();
  const int ok = cholmod_solve2(CHOLMOD_A, impl_->factor, &b, nullptr, &impl_->solution, nullptr,
                                &impl_->work_y, &impl_->work_e, &impl_->common);
  if (ok == 0 || impl_->solution == nullptr)
    return SolveStatus::failed;
  solution.resize(rhs.size());
  std::memcpy(solution.data(), impl_->solution->x,
              static_cast<std::size_t>(rhs.size()) * sizeof(double));
  ++impl_->counters.solves;
  return SolveStatus::ok;
}

const SolverCounters& CholmodSolver::counters() const { return impl_->counters; }

std::string CholmodSolver::name() const { return cholmod_version() + " supernodal"; }

void CholmodSolver::set_single_thread_flops(double flops) { impl_->single_thread_flops = flops; }

double CholmodSolver::factor_flops() const { return impl_->flops; }

long CholmodSolver::failed_column() const { return impl_->failed_column; }

std::string cholmod_version() {
  return "CHOLMOD " + std::to_string(CHOLMOD_MAIN_VERSION) + "." +
         std::to_string(CHOLMOD_SUB_VERSION) + "." + std::to_string(CHOLMOD_SUBSUB_VERSION);
}

} // namespace nmm
