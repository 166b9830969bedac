// SPDX-License-Identifier: MIT
#include "solver/cholmod_solver.hpp"

#include "mesh/error.hpp"
#include "solver/threads.hpp"

#include <Eigen/Core>
#include <cholmod.h>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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
  long nonzeros = -1; ///< of the matrix analysed: a factorised one has its pattern
  long failed_column = -1;
  /// The matrix as factorised: the lower triangle of P A P^T (P the fill-reducing ordering
  /// of analyze()), in compressed columns, with for each of its entries the index of the
  /// same entry among the upper triangle's values of A (see analyze()).
  std::vector<int> permutation; ///< P: row k of P A P^T is row permutation[k] of A
  std::vector<int> lower_start;
  std::vector<int> lower_row;
  std::vector<double> lower_value;
  std::vector<int> source;
  Eigen::VectorXd permuted; ///< P b of a solve
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

  // A non-owning CHOLMOD view of compressed columns of an n x n symmetric matrix, of which
  // only the upper (stype 1) or lower (stype -1) triangle is read. CHOLMOD's C interface takes
  // non-const pointers but does not write through them here.
  static cholmod_sparse view(std::size_t n,
                             std::size_t nonzeros,
                             const int* start,
                             const int* row,
                             const double* value,
                             int stype) {
    cholmod_sparse a{};
    a.nrow = n;
    a.ncol = n;
    a.nzmax = nonzeros;
    a.p = const_cast<int*>(start);    // NOLINT(cppcoreguidelines-pro-type-const-cast)
    a.i = const_cast<int*>(row);      // NOLINT(cppcoreguidelines-pro-type-const-cast)
    a.x = const_cast<double*>(value); // NOLINT(cppcoreguidelines-pro-type-const-cast)
    a.stype = stype;
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    return a;
  }
  // An Eigen matrix's upper triangle.
  static cholmod_sparse view(const SparseMatrix& matrix) {
    return view(static_cast<std::size_t>(matrix.rows()),
                static_cast<std::size_t>(matrix.nonZeros()), matrix.outerIndexPtr(),
                matrix.innerIndexPtr(), matrix.valuePtr(), 1);
  }
  // The permuted lower triangle.
  [[nodiscard]] cholmod_sparse lower_view() const {
    return view(permutation.size(), lower_row.size(), lower_start.data(), lower_row.data(),
                lower_value.data(), -1);
  }
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>()) {}
CholmodSolver::~CholmodSolver() = default;

// The numeric factorisation wants the lower triangle of the permuted matrix, P A P^T: given A
// and the ordering, CHOLMOD forms it by a permuted transpose at every factorisation (5 % of the
// 70-block wall's steps, with its allocations). The pattern stays from one analysis to the
// next, so analyze() builds that permuted lower triangle once, with where each of its entries
// comes from, and has CHOLMOD analyse it in its natural order without a postorder (the
// ordering, postorder included, is in P already): the same elimination tree, supernodes and
// arithmetic, so the same factor to the last bit. A factorisation then only gathers the
// values, and a solve permutes the right-hand side and the solution (as CHOLMOD would).
SolveStatus CholmodSolver::analyze(const SparseMatrix& matrix) {
  NMM_ASSERT(matrix.rows() == matrix.cols(), "CHOLMOD needs a square matrix");
  NMM_ASSERT(matrix.isCompressed(), "CHOLMOD needs a compressed matrix");
  Impl& m = *impl_;
  cholmod_free_factor(&m.factor, &m.common);
  m.n = -1;
  // The fill-reducing ordering (with its postorder) of A's pattern: a simplicial analysis,
  // which orders and postorders as the supernodal one does, without its supernodes.
  cholmod_sparse a = Impl::view(matrix);
  m.common.supernodal = CHOLMOD_SIMPLICIAL;
  cholmod_factor* ordering = cholmod_analyze(&a, &m.common);
  m.common.supernodal = CHOLMOD_SUPERNODAL;
  if (ordering == nullptr || m.common.status < CHOLMOD_OK) {
    cholmod_free_factor(&ordering, &m.common);
    return SolveStatus::failed;
  }
  const auto n = static_cast<std::size_t>(matrix.rows());
  const auto* perm = static_cast<const int*>(ordering->Perm);
  m.permutation.assign(perm, perm + n);
  cholmod_free_factor(&ordering, &m.common);
  std::vector<int> inverse(n);
  for (std::size_t k = 0; k < n; ++k)
    inverse[static_cast<std::size_t>(m.permutation[k])] = static_cast<int>(k);
  // The lower triangle of P A P^T from A's upper triangle: entry (i, j), i <= j, goes to
  // row max(P'i, P'j) of column min(P'i, P'j) (P' the inverse); columns counted, then filled,
  // then each column's rows sorted.
  const int* outer = matrix.outerIndexPtr();
  const int* inner = matrix.innerIndexPtr();
  m.lower_start.assign(n + 1, 0);
  auto upper = [&](std::size_t j, int k) { return static_cast<std::size_t>(inner[k]) <= j; };
  for (std::size_t j = 0; j < n; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      if (!upper(j, k))
        continue; // (a lower entry: not read, as CHOLMOD reads only the upper triangle)
      const int pi = inverse[static_cast<std::size_t>(inner[k])];
      const int pj = inverse[j];
      ++m.lower_start[static_cast<std::size_t>(std::min(pi, pj)) + 1];
    }
  for (std::size_t j = 0; j < n; ++j)
    m.lower_start[j + 1] += m.lower_start[j];
  const auto nonzeros = static_cast<std::size_t>(m.lower_start[n]);
  m.lower_row.resize(nonzeros);
  m.source.resize(nonzeros);
  m.lower_value.assign(nonzeros, 0.0);
  std::vector<int> next(m.lower_start.begin(), m.lower_start.end() - 1);
  for (std::size_t j = 0; j < n; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      if (!upper(j, k))
        continue;
      const int pi = inverse[static_cast<std::size_t>(inner[k])];
      const int pj = inverse[j];
      const auto slot =
          static_cast<std::size_t>(next[static_cast<std::size_t>(std::min(pi, pj))]++);
      m.lower_row[slot] = std::max(pi, pj);
      m.source[slot] = k;
    }
  std::vector<std::pair<int, int>> column;
  for (std::size_t j = 0; j < n; ++j) {
    const auto first = static_cast<std::size_t>(m.lower_start[j]);
    const auto last = static_cast<std::size_t>(m.lower_start[j + 1]);
    column.clear();
    for (std::size_t k = first; k < last; ++k)
      column.emplace_back(m.lower_row[k], m.source[k]);
    std::sort(column.begin(), column.end());
    for (std::size_t k = first; k < last; ++k)
      std::tie(m.lower_row[k], m.source[k]) = column[k - first];
  }
  // Its analysis in the natural order, without a postorder.
  cholmod_sparse lower = m.lower_view();
  const int methods = m.common.nmethods;
  const int method = m.common.method[0].ordering;
  const int postorder = m.common.postorder;
  m.common.nmethods = 1;
  m.common.method[0].ordering = CHOLMOD_NATURAL;
  m.common.postorder = 0;
  m.factor = cholmod_analyze(&lower, &m.common);
  m.common.nmethods = methods;
  m.common.method[0].ordering = method;
  m.common.postorder = postorder;
  if (m.factor == nullptr || m.common.status < CHOLMOD_OK)
    return SolveStatus::failed;
  m.n = matrix.rows();
  m.nonzeros = matrix.nonZeros();
  m.flops = m.common.fl;
  ++m.counters.symbolic_analyses;
  return SolveStatus::ok;
}

SolveStatus CholmodSolver::factorize(const SparseMatrix& matrix) {
  Impl& m = *impl_;
  if (m.factor == nullptr || matrix.rows() != m.n || matrix.nonZeros() != m.nonzeros)
    return SolveStatus::failed;
  const double* values = matrix.valuePtr();
  for (std::size_t k = 0; k < m.source.size(); ++k)
    m.lower_value[k] = values[m.source[k]];
  cholmod_sparse lower = m.lower_view();
  const auto single = m.single_thread_if_small();
  const int ok = cholmod_factorize(&lower, m.factor, &m.common);
  m.failed_column = -1;
  if (m.common.status == CHOLMOD_NOT_POSDEF || (ok != 0 && m.factor->minor < m.factor->n)) {
    // minor counts columns of the permuted matrix: map it back to the matrix's own column.
    const auto minor = static_cast<std::size_t>(m.factor->minor);
    m.failed_column =
        minor < m.permutation.size() ? m.permutation[minor] : static_cast<long>(minor);
    return SolveStatus::not_positive_definite;
  }
  if (ok == 0 || m.common.status < CHOLMOD_OK)
    return SolveStatus::failed;
  ++m.counters.factorizations;
  return SolveStatus::ok;
}

SolveStatus CholmodSolver::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& solution) {
  Impl& m = *impl_;
  if (m.factor == nullptr || rhs.size() != m.n || m.failed_column >= 0)
    return SolveStatus::failed;
  const std::size_t n = m.permutation.size();
  m.permuted.resize(rhs.size());
  for (std::size_t k = 0; k < n; ++k)
    m.permuted(static_cast<Eigen::Index>(k)) = rhs(m.permutation[k]);
  cholmod_dense b{};
  b.nrow = static_cast<std::size_t>(rhs.size());
  b.ncol = 1;
  b.nzmax = b.nrow;
  b.d = b.nrow;
  b.x = m.permuted.data();
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  // The triangular solves of a factor that was made on one thread run on one thread too:
  // OpenBLAS parallelises their larger dgemv calls, and the second thread it wakes for them
  // then spins in sched_yield between the solve's calls (3.3 s of system time in a 3.6 s run
  // of a 1,003-block rock mass, at the same speed), and the result depends on the thread
  // count.
  const auto single = m.single_thread_if_small();
  const int ok = cholmod_solve2(CHOLMOD_A, m.factor, &b, nullptr, &m.solution, nullptr, &m.work_y,
                                &m.work_e, &m.common);
  if (ok == 0 || m.solution == nullptr)
    return SolveStatus::failed;
  solution.resize(rhs.size());
  const auto* x = static_cast<const double*>(m.solution->x);
  for (std::size_t k = 0; k < n; ++k)
    solution(m.permutation[k]) = x[k];
  ++m.counters.solves;
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
