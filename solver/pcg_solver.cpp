// SPDX-License-Identifier: MIT
#include "solver/pcg_solver.hpp"

#include "mesh/error.hpp"
#include "mesh/parallel.hpp"
#include "solver/cholmod_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace nmm {

namespace {

/// Largest diagonal block of the preconditioner: an order-2 cover has 12 unknowns. Longer
/// runs of unknowns with one pattern (a small dense system) are split.
constexpr int max_block = 12;

/// The preconditioner's blocks go to the worker threads from twice this many on (a DDA
/// block's product with its 6 x 6 inverse is a few dozen operations; fewer blocks than this
/// per thread are not worth a thread's start). The results are the same either way.
constexpr std::size_t parallel_blocks = 4096;

} // namespace

struct PcgSolver::Impl {
  PcgOptions options;
  SparseMatrix matrix;     ///< pattern of analyze(), values of the last factorize()
  bool analysed = false;   ///< analyze() succeeded: matrix has the pattern
  bool factorised = false; ///< factorize() succeeded: matrix has the values, blocks inverted
  /// CHOLMOD does the work: the pattern lacks a diagonal entry (until the next analyze()),
  /// or conjugate gradients gave up on a system of it (until then or the next start_step()).
  bool singular_pattern = false;
  bool gave_up = false;
  bool loose = false; ///< set_loose(): solves stop at options.loose_tolerance
  /// This step was tried by conjugate gradients, and they gave up in it (gave_up is reset by
  /// analyze(), these only by start_step()).
  bool tried = false;
  bool failed = false;
  /// After steps they gave up in (start_step()): the length of the next run of steps done by
  /// CHOLMOD alone, the steps of the current run still to come, whether this step is one.
  int next_skip = 0;
  int skip_left = 0;
  bool skipping = false;
  std::vector<int> diagonal; ///< index of (j, j) among the values, per column
  /// Diagonal blocks: unknowns block_start[b] .. block_start[b + 1] - 1; for each, the index
  /// among the values of every entry (i, j), i <= j, of its upper triangle (column by
  /// column), -1 where the pattern has none; and the inverse of the block after factorize(),
  /// column-major, from inverse_start[b].
  std::vector<int> block_start;
  std::vector<int> block_entry;
  std::vector<int> entry_start;
  std::vector<double> inverse;
  std::vector<int> inverse_start;
  /// The values each block was inverted with (as block_entry, 0 where the pattern has no
  /// entry), and whether the inverses are theirs (false after analyze()).
  std::vector<double> block_values;
  bool inverses_kept = false;
  /// CHOLMOD for the solves conjugate gradients cannot do: analysed and factorised on demand.
  CholmodSolver direct;
  bool direct_analysed = false;
  bool direct_factorised = false;
  long failed_column = -1;
  Eigen::VectorXd r, z, p, q; ///< the iteration's vectors, reused
  SolverCounters counters;

  /// The product's two halves: columns [0, split) and [split, n), about half the upper
  /// triangle's entries each, summed into y and into other_half (see multiply()).
  int split = 0;
  Eigen::VectorXd other_half;

  /// The entries above the diagonal in runs of consecutive rows: column j's are runs
  /// column_runs[j] .. column_runs[j + 1] - 1, run r the rows run_row[r] ..
  /// run_row[r] + run_length[r] - 1, its values consecutive from the column's start (a DDA
  /// block couples with another's six unknowns: one index for six entries).
  std::vector<int> column_runs;
  std::vector<int> run_row;
  std::vector<int> run_length;

  /// y = A x, A symmetric with its upper triangle read (up to the diagonal of each column).
  /// Always as two halves of the columns, each summed on its own and then added: on two
  /// threads when the matrix is large (a product with 1.6e6 entries at 10,004 DDA blocks is
  /// bound by memory, 80 % of an iteration), and the same numbers on one. A column's entries
  /// go by runs of consecutive rows (a quarter less to read than a row index per entry, and
  /// a run's updates of y in one vectorised loop); each sum takes its terms in the order of
  /// the entries, as an entry-by-entry walk does.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    const int n = static_cast<int>(matrix.rows());
    const int* start = matrix.outerIndexPtr();
    const double* value = matrix.valuePtr();
    const double* xs = x.data();
    auto columns = [&](int first, int last, Eigen::VectorXd& out) {
      out.setZero(n);
      double* os = out.data();
      for (int j = first; j < last; ++j) {
        const double xj = xs[j];
        double sum = value[diagonal[static_cast<std::size_t>(j)]] * xj;
        const double* v = value + start[j];
        for (int run = column_runs[static_cast<std::size_t>(j)];
             run < column_runs[static_cast<std::size_t>(j) + 1]; ++run) {
          const int i = run_row[static_cast<std::size_t>(run)];
          const int length = run_length[static_cast<std::size_t>(run)];
          double* o = os + i;
          for (int t = 0; t < length; ++t)
            o[t] += v[t] * xj;
          const double* xi = xs + i;
          for (int t = 0; t < length; ++t)
            sum += v[t] * xi[t];
          v += length;
        }
        os[j] += sum;
      }
    };
    const bool large = matrix.nonZeros() >= options.parallel_entries;
    parallel_for(2, large ? 1 : 2, [&](std::size_t first, std::size_t last, int /*chunk*/) {
      for (std::size_t half = first; half < last; ++half) {
        if (half == 0)
          columns(0, split, y);
        else
          columns(split, n, other_half);
      }
    });
    y += other_half;
  }

  /// z = B^-1 r, B the block diagonal of A (blocks on as many threads as there are when
  /// there are many). The blocks of a DDA block (6 unknowns) and of a cover or a VEM vertex
  /// (2) by a product of their size known to the compiler: Eigen's product of a size known
  /// only at run time cost three times as much over 10,000 blocks of 6 (measured alone), for
  /// the same sums in the same order (column after column).
  void precondition(const Eigen::VectorXd& residual, Eigen::VectorXd& result) const {
    result.resize(residual.size());
    const std::size_t blocks = block_start.empty() ? 0 : block_start.size() - 1;
    parallel_for(blocks, parallel_blocks, [&](std::size_t first, std::size_t last, int /*chunk*/) {
      for (std::size_t b = first; b < last; ++b) {
        const int s = block_start[b];
        const int m = block_start[b + 1] - s;
        const double* block = inverse.data() + inverse_start[b];
        if (m == 6) {
          block_product<6>(block, residual.data() + s, result.data() + s);
        } else if (m == 2) {
          block_product<2>(block, residual.data() + s, result.data() + s);
        } else {
          result.segment(s, m).noalias() =
              Eigen::Map<const Eigen::MatrixXd>(block, m, m) * residual.segment(s, m);
        }
      }
    });
  }

  /// y = B x for the column-major M x M matrix @p block, column after column.
  template <int M> static void block_product(const double* block, const double* x, double* y) {
    for (int i = 0; i < M; ++i)
      y[i] = 0.0;
    for (int j = 0; j < M; ++j) {
      const double xj = x[j];
      const double* column = block + static_cast<std::ptrdiff_t>(j) * M;
      for (int i = 0; i < M; ++i)
        y[i] += column[i] * xj;
    }
  }

  /// CHOLMOD's factorisation of the matrix factorize() was given, analysing it first if
  /// needed.
  SolveStatus factorize_directly() {
    if (!direct_analysed) {
      const SolveStatus status = direct.analyze(matrix);
      if (status != SolveStatus::ok)
        return status;
      direct_analysed = true;
    }
    const SolveStatus status = direct.factorize(matrix);
    direct_factorised = status == SolveStatus::ok;
    if (status == SolveStatus::ok)
      ++counters.factorizations;
    else
      failed_column = direct.failed_column();
    return status;
  }

  /// CHOLMOD's solve of the system factorize() was given, factorising it first if needed.
  SolveStatus solve_directly(const Eigen::VectorXd& rhs, Eigen::VectorXd& solution) {
    if (!direct_factorised) {
      const SolveStatus status = factorize_directly();
      if (status != SolveStatus::ok)
        return status;
    }
    return direct.solve(rhs, solution);
  }
};

PcgSolver::PcgSolver(PcgOptions options) : impl_(std::make_unique<Impl>()) {
  NMM_ASSERT(options.tolerance > 0.0 && options.max_iterations > 0,
             "the conjugate-gradient tolerance and iteration limit must be positive");
  impl_->options = options;
}

PcgSolver::~PcgSolver() = default;

// The pattern's diagonal blocks: unknowns j and j + 1 share a block when their columns of the
// symmetric pattern are the same set (the unknowns of one cover or DDA block couple with the
// same unknowns, each other included).
SolveStatus PcgSolver::analyze(const SparseMatrix& matrix) {
  NMM_ASSERT(matrix.rows() == matrix.cols(), "conjugate gradients need a square matrix");
  NMM_ASSERT(matrix.isCompressed(), "conjugate gradients need a compressed matrix");
  Impl& m = *impl_;
  m.analysed = m.factorised = m.direct_analysed = m.direct_factorised = false;
  m.inverses_kept = false;
  m.singular_pattern = m.gave_up = false;
  m.failed_column = -1;
  m.matrix = matrix;
  const int n = static_cast<int>(matrix.rows());
  const int* start = matrix.outerIndexPtr();
  const int* row = matrix.innerIndexPtr();
  m.diagonal.assign(static_cast<std::size_t>(n), -1);
  // The symmetric pattern by columns: the upper triangle's rows, then the transposed entries.
  // Rows are sorted, so the diagonal ends the upper part of its column (entries below it, of
  // a lower triangle, are not read); without one, the matrix is singular.
  std::vector<int> count(static_cast<std::size_t>(n) + 1, 0);
  for (int j = 0; j < n; ++j) {
    const int* diagonal = std::lower_bound(row + start[j], row + start[j + 1], j);
    if (diagonal == row + start[j + 1] || *diagonal != j) {
      // A singular matrix: CHOLMOD's factorisation will say so, and where.
      m.singular_pattern = m.analysed = true;
      ++m.counters.symbolic_analyses;
      return SolveStatus::ok;
    }
    m.diagonal[static_cast<std::size_t>(j)] = static_cast<int>(diagonal - row);
    count[static_cast<std::size_t>(j) + 1] += static_cast<int>(diagonal - (row + start[j])) + 1;
    for (const int* i = row + start[j]; i != diagonal; ++i)
      ++count[static_cast<std::size_t>(*i) + 1];
  }
  for (int j = 0; j < n; ++j)
    count[static_cast<std::size_t>(j) + 1] += count[static_cast<std::size_t>(j)];
  std::vector<int> full(static_cast<std::size_t>(count.back()));
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (int j = 0; j < n; ++j) {
    for (int k = start[j]; k <= m.diagonal[static_cast<std::size_t>(j)]; ++k)
      full[static_cast<std::size_t>(fill[static_cast<std::size_t>(j)]++)] = row[k];
  }
  for (int j = 0; j < n; ++j) { // column j's entries (i, j), i < j, as (j, i): increasing j
    for (int k = start[j]; k < m.diagonal[static_cast<std::size_t>(j)]; ++k)
      full[static_cast<std::size_t>(fill[static_cast<std::size_t>(row[k])]++)] = j;
  }
  auto same_pattern = [&](int a, int b) {
    const auto* first = full.data() + count[static_cast<std::size_t>(a)];
    const auto* last = full.data() + count[static_cast<std::size_t>(a) + 1];
    const auto* other = full.data() + count[static_cast<std::size_t>(b)];
    const auto* other_last = full.data() + count[static_cast<std::size_t>(b) + 1];
    return last - first == other_last - other && std::equal(first, last, other);
  };
  m.block_start.assign(1, 0);
  for (int j = 1; j < n; ++j) {
    if (!same_pattern(j - 1, j) || j - m.block_start.back() >= max_block)
      m.block_start.push_back(j);
  }
  if (n > 0)
    m.block_start.push_back(n);
  // Where each block's upper-triangle entries are among the values.
  m.block_entry.clear();
  m.entry_start.assign(1, 0);
  m.inverse_start.assign(1, 0);
  for (std::size_t b = 0; b + 1 < m.block_start.size(); ++b) {
    const int s = m.block_start[b];
    const int e = m.block_start[b + 1];
    for (int j = s; j < e; ++j) {
      for (int i = s; i <= j; ++i) {
        const int* end = row + m.diagonal[static_cast<std::size_t>(j)] + 1;
        const int* found = std::lower_bound(row + start[j], end, i);
        m.block_entry.push_back(found != end && *found == i ? static_cast<int>(found - row) : -1);
      }
    }
    m.entry_start.push_back(static_cast<int>(m.block_entry.size()));
    m.inverse_start.push_back(m.inverse_start.back() + (e - s) * (e - s));
  }
  m.inverse.assign(static_cast<std::size_t>(m.inverse_start.back()), 0.0);
  m.block_values.assign(m.block_entry.size(), 0.0);
  m.inverses_kept = false;
  // The runs of consecutive rows above each column's diagonal, for multiply().
  m.column_runs.assign(1, 0);
  m.run_row.clear();
  m.run_length.clear();
  for (int j = 0; j < n; ++j) {
    for (int k = start[j]; k < m.diagonal[static_cast<std::size_t>(j)]; ++k) {
      if (k > start[j] && row[k] == row[k - 1] + 1) {
        ++m.run_length.back();
      } else {
        m.run_row.push_back(row[k]);
        m.run_length.push_back(1);
      }
    }
    m.column_runs.push_back(static_cast<int>(m.run_row.size()));
  }
  // The product's halves: the column where the upper triangle's entries reach half (counted
  // in the upper triangle alone, so that a matrix stored whole splits as its upper triangle).
  auto upper_in = [&](int j) { return m.diagonal[static_cast<std::size_t>(j)] - start[j] + 1; };
  long upper_entries = 0;
  for (int j = 0; j < n; ++j)
    upper_entries += upper_in(j);
  m.split = 0;
  for (long so_far = 0; m.split < n && 2 * so_far < upper_entries; ++m.split)
    so_far += upper_in(m.split);
  m.analysed = true;
  ++m.counters.symbolic_analyses;
  return SolveStatus::ok;
}

SolveStatus PcgSolver::factorize(const SparseMatrix& matrix) {
  Impl& m = *impl_;
  m.factorised = m.direct_factorised = false;
  m.failed_column = -1;
  if (!m.analysed || matrix.rows() != m.matrix.rows() || matrix.nonZeros() != m.matrix.nonZeros())
    return SolveStatus::failed;
  std::copy(matrix.valuePtr(), matrix.valuePtr() + matrix.nonZeros(), m.matrix.valuePtr());
  if (m.singular_pattern || m.gave_up || m.skipping) {
    const SolveStatus status = m.factorize_directly();
    m.factorised = status == SolveStatus::ok;
    return status;
  }
  const double* value = m.matrix.valuePtr();
  Eigen::MatrixXd block;
  Eigen::LLT<Eigen::MatrixXd> llt;
  for (std::size_t b = 0; b + 1 < m.block_start.size(); ++b) {
    const int s = m.block_start[b];
    const int size = m.block_start[b + 1] - s;
    // A block whose values are those it was inverted with keeps its inverse: an open-close
    // iteration changes the springs of a few contacts, and so a few blocks.
    const int* entry = m.block_entry.data() + m.entry_start[b];
    double* kept = m.block_values.data() + m.entry_start[b];
    const int entries = m.entry_start[b + 1] - m.entry_start[b];
    bool same = m.inverses_kept;
    for (int k = 0; k < entries; ++k) {
      const double v = entry[k] >= 0 ? value[entry[k]] : 0.0;
      same = same && kept[k] == v;
      kept[k] = v;
    }
    if (same)
      continue;
    block.resize(size, size); // every entry is set below
    for (int j = 0, k = 0; j < size; ++j) {
      for (int i = 0; i <= j; ++i, ++k)
        block(i, j) = block(j, i) = kept[k];
    }
    llt.compute(block);
    if (llt.info() != Eigen::Success) {
      // A diagonal block that is not positive definite: neither is the matrix, and CHOLMOD
      // says where, as it would without conjugate gradients. (Should rounding let it through
      // nonetheless, its factor does the solves.)
      m.inverses_kept = false;
      const SolveStatus status = m.factorize_directly();
      m.factorised = status == SolveStatus::ok;
      return status;
    }
    Eigen::Map<Eigen::MatrixXd>(m.inverse.data() + m.inverse_start[b], size, size) =
        llt.solve(Eigen::MatrixXd::Identity(size, size));
  }
  m.inverses_kept = true;
  m.factorised = true;
  return SolveStatus::ok;
}

// Preconditioned conjugate gradients (Saad, Iterative Methods for Sparse Linear Systems,
// algorithm 9.1), stopped at ||r|| <= tolerance ||b||.
SolveStatus PcgSolver::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& solution) {
  Impl& m = *impl_;
  if (!m.factorised || rhs.size() != m.matrix.rows())
    return SolveStatus::failed;
  SolveStatus status = SolveStatus::ok;
  bool direct = m.direct_factorised;
  if (direct) {
    status = m.solve_directly(rhs, solution);
  } else {
    m.tried = true;
    const double tolerance =
        m.loose ? std::max(m.options.tolerance, m.options.loose_tolerance) : m.options.tolerance;
    const double target = tolerance * rhs.norm();
    if (solution.size() != rhs.size() || !solution.allFinite() || target == 0.0)
      solution.setZero(rhs.size()); // no guess, or the zero solution of a zero right side
    m.multiply(solution, m.q);
    m.r = rhs - m.q;
    bool converged = m.r.norm() <= target;
    if (!converged) {
      m.precondition(m.r, m.z);
      m.p = m.z;
      double rz = m.r.dot(m.z);
      for (int iteration = 0; iteration < m.options.max_iterations; ++iteration) {
        m.multiply(m.p, m.q);
        const double curvature = m.p.dot(m.q);
        ++m.counters.iterations;
        if (!(curvature > 0.0))
          break; // not positive definite (or singular): CHOLMOD will say where
        const double alpha = rz / curvature;
        solution += alpha * m.p;
        m.r -= alpha * m.q;
        if (m.r.norm() <= target) {
          converged = true;
          break;
        }
        m.precondition(m.r, m.z);
        const double rz_next = m.r.dot(m.z);
        m.p = m.z + (rz_next / rz) * m.p;
        rz = rz_next;
      }
    }
    if (!converged) {
      // Systems of this pattern are not for conjugate gradients (a static step, stiff springs
      // on light blocks): the step's next ones go to CHOLMOD at once, without the futile
      // iterations.
      m.gave_up = m.failed = direct = true;
      status = m.solve_directly(rhs, solution);
    }
  }
  if (direct)
    ++m.counters.fallbacks;
  if (status == SolveStatus::ok)
    ++m.counters.solves;
  return status;
}

const SolverCounters& PcgSolver::counters() const { return impl_->counters; }

std::string PcgSolver::name() const {
  return "conjugate gradients, block Jacobi (" + cholmod_version() + " when they do not converge)";
}

bool PcgSolver::set_loose(bool loose) {
  impl_->loose = loose;
  return impl_->options.loose_tolerance > impl_->options.tolerance;
}

long PcgSolver::failed_column() const { return impl_->failed_column; }

// A step conjugate gradients gave up in doubles the run of steps to skip (from 1, to at most
// max_skipped_steps); a step they went through starts it again. A static case with 1,000
// steps then tries them in 21 steps instead of 1,000; a dynamic scene whose iterations only
// failed for a while (a landing impact) is back on them after a few steps.
void PcgSolver::start_step() {
  Impl& m = *impl_;
  if (m.failed) {
    m.next_skip = std::min(std::max(1, 2 * m.next_skip), m.options.max_skipped_steps);
    m.skip_left = m.next_skip;
  } else if (m.tried) {
    m.next_skip = 0;
  }
  m.skipping = m.skip_left > 0;
  if (m.skipping)
    --m.skip_left;
  m.gave_up = m.tried = m.failed = false;
}

// Between steps: the last step's outcome is not yet in the run of steps to skip
// (start_step() puts it there), so it is carried too.
std::vector<int> PcgSolver::carried() const {
  const Impl& m = *impl_;
  return {m.next_skip, m.skip_left, m.tried ? 1 : 0, m.failed ? 1 : 0};
}

bool PcgSolver::restore_carried(const std::vector<int>& carried) {
  Impl& m = *impl_;
  if (carried.empty()) // a checkpoint of a run by CHOLMOD: nothing to skip
    return true;
  auto flag = [](int v) { return v == 0 || v == 1; };
  if (carried.size() != 4 || carried[0] < 0 || carried[1] < 0 || carried[1] > carried[0] ||
      !flag(carried[2]) || !flag(carried[3]))
    return false;
  m.next_skip = std::min(carried[0], m.options.max_skipped_steps);
  m.skip_left = std::min(carried[1], m.next_skip);
  m.tried = carried[2] != 0;
  m.failed = carried[3] != 0;
  return true;
}

bool PcgSolver::skipping() const { return impl_->skipping; }

std::vector<int> PcgSolver::block_sizes() const {
  std::vector<int> sizes;
  for (std::size_t b = 0; b + 1 < impl_->block_start.size(); ++b)
    sizes.push_back(impl_->block_start[b + 1] - impl_->block_start[b]);
  return sizes;
}

} // namespace nmm
