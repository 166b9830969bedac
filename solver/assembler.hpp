// SPDX-License-Identifier: MIT
// solver/assembler.hpp — scatter dense local matrices into a matrix with a fixed pattern.
#pragma once

#include "contact/key_set.hpp"
#include "solver/linear_solver.hpp"
#include "solver/sparsity.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace nmm {

/// Assembles the step's symmetric matrix and right-hand side into a fixed SparsityPattern.
///
/// The matrix is stored as SparseMatrix with the upper triangle only, values in the
/// pattern's order, so analysis by a LinearSolver is valid for as long as the pattern is.
/// Scattering never changes the structure (DESIGN.md "Measured facts": assembly into a
/// fixed pattern is several times faster than triplets plus setFromTriplets).
///
/// Two ways to add a local matrix:
/// - add(dofs, local) finds every position by binary search in its column;
/// - plan(dofs) once per coupling and pattern, then add(plan, local) on every open-close
///   iteration: the positions are precomputed, no searching.
///
/// In every add, @p dofs maps local row/column a to global dof dofs[a]; dofs may be
/// unsorted and hold repeats (contributions to one global entry are summed, as in
/// P^T local P); a negative entry is an eliminated dof whose row and column are skipped.
/// Only the upper triangle (a <= b) of a local matrix is read: it must be symmetric.
class Assembler {
public:
  /// An assembler with zero values and no plans for @p pattern (copied).
  explicit Assembler(const SparsityPattern& pattern);

  /// Rebinds to a new pattern (the next step's), reusing storage: values are zeroed and
  /// every plan is dropped.
  void reset(const SparsityPattern& pattern);

  /// Number of rows and columns.
  [[nodiscard]] int n_dofs() const { return static_cast<int>(matrix_.rows()); }

  /// Sets every matrix value and the right-hand side to zero; the pattern and plans stay.
  void zero();

  /// The matrix values in the pattern's order: to keep the part that does not change within
  /// a step (elements, supports) while open-close iterations add contact springs.
  [[nodiscard]] std::span<const double> values() const;
  /// Replaces every matrix value (same size and order as values()).
  void assign_values(std::span<const double> values);

  /// Adds the upper triangle of the symmetric k x k @p local at @p dofs (k = dofs.size()),
  /// searching each position.
  /// @pre local is k x k; 0 <= dofs[a] < n_dofs() or negative; every coupled pair is in
  ///      the pattern (both checked by NMM_ASSERT; a pair outside the pattern never writes
  ///      outside the value array, but lands on a wrong entry of its column).
  void add(std::span<const int> dofs, const Eigen::Ref<const Eigen::MatrixXd>& local);

  /// Adds @p local (size k) to the right-hand side at @p dofs; negative dofs are skipped.
  void add_vector(std::span<const int> dofs, const Eigen::Ref<const Eigen::VectorXd>& local);

  /// Adds @p value to diagonal entry (dof, dof), which every pattern holds. O(1).
  /// @pre 0 <= dof < n_dofs().
  void add_diagonal(int dof, double value);

  /// Precomputes the value positions of a coupling and returns its plan id (0, 1, 2, ...),
  /// valid until reset() or clear_plans(). Same preconditions on @p dofs as add().
  [[nodiscard]] int plan(std::span<const int> dofs);
  /// The same, or -1 (and no plan) when a pair of @p dofs is not in the pattern: one walk
  /// down each column instead of a search for every pair and then the walk.
  [[nodiscard]] int plan_if_in_pattern(std::span<const int> dofs);
  /// A plan for the same dofs as plan @p plan_id, sharing its positions (another contact
  /// point on the same unknowns): returns its id. @pre 0 <= plan_id < n_plans() (NMM_ASSERT).
  [[nodiscard]] int plan_as(int plan_id);

  /// Adds the upper triangle of the symmetric @p local with the positions of plan
  /// @p plan_id: the same result as add(dofs, local) with that plan's dofs, without search.
  /// @pre local is k x k for the plan's k dofs (NMM_ASSERT).
  void add(int plan_id, const Eigen::Ref<const Eigen::MatrixXd>& local);

  /// Adds @p local to the right-hand side at the dofs of plan @p plan_id.
  void add_vector(int plan_id, const Eigen::Ref<const Eigen::VectorXd>& local);

  /// Number of plans made since construction, reset() or clear_plans().
  [[nodiscard]] int n_plans() const { return static_cast<int>(plans_.size()); }
  /// Drops every plan (keeps their storage), and the positions kept for plans made again.
  void clear_plans();
  /// Drops the plans from @p first on and keeps the earlier ones: the next plan() returns
  /// @p first. @pre 0 <= first <= n_plans() (NMM_ASSERT).
  ///
  /// The positions of a dropped plan stay with the assembler (until reset() or
  /// clear_plans()): a plan made again for the same dofs takes them instead of searching the
  /// pattern. The time stepper drops the contacts' plans every step and plans the next
  /// step's, which are mostly the same couplings (at 10,004 DDA blocks 92% of a step's
  /// 59,000), while a search reads a dozen columns of a matrix of megabytes. When over twice
  /// as many sets of dofs (and 1024) are kept as there were plans before the drop, only the
  /// positions of those plans are kept.
  void truncate_plans(int first);
  /// Plans whose positions were found by walking down the pattern's columns since
  /// construction (the others took a plan's that had the same dofs): for tests.
  [[nodiscard]] long searches() const noexcept { return searches_; }

  /// The assembled matrix: upper triangle, compressed, in the pattern's order.
  [[nodiscard]] const SparseMatrix& matrix() const { return matrix_; }
  /// The assembled right-hand side (n_dofs() entries).
  [[nodiscard]] const Eigen::VectorXd& rhs() const { return rhs_; }

private:
  // Where the positions of one plan live in the shared arrays below. Plans with the same
  // dofs share them (plan_as(), and plans made again for the same dofs).
  struct Plan {
    int n_local = 0;                // k: rows of the local matrix
    int n_kept = 0;                 // local indices with a non-negative dof
    std::size_t kept_begin = 0;     // into kept_local_ and kept_dofs_
    std::size_t position_begin = 0; // into positions_: n_kept (n_kept + 1) / 2 entries
    std::size_t repeat_begin = 0;   // into repeats_
    std::size_t repeat_end = 0;
  };
  // A pair a < b of local indices with the same dof: its diagonal entry also receives
  // local(b, a), which the upper-triangle loop does not visit.
  struct Repeat {
    int row = 0;
    int column = 0;
    int position = 0;
  };

  [[nodiscard]] int search_position(int row, int column) const;
  /// A hash of a plan's local size and kept (local index, dof) pairs: its key in index_.
  [[nodiscard]] static std::uint64_t plan_key(int n_local, const int* kept, const int* dofs, int m);
  /// Whether @p plan, with its data in @p kept_local and @p kept_dofs, has @p n_local local
  /// indices and the @p m kept pairs @p kept, @p dofs.
  [[nodiscard]] static bool has_pairs(const Plan& plan,
                                      const std::vector<int>& kept_local,
                                      const std::vector<int>& kept_dofs,
                                      int n_local,
                                      const int* kept,
                                      const int* dofs,
                                      int m);
  /// Shrinks the shared arrays to where @p plan's data begins (that plan and all later).
  void drop_data_from(const Plan& plan);
  /// Keeps only the data of the current plans (truncate_plans()).
  void compact();

  SparseMatrix matrix_;
  Eigen::VectorXd rhs_;
  std::vector<Plan> plans_;
  std::vector<int> kept_local_;
  std::vector<int> kept_dofs_;
  std::vector<int> positions_;
  std::vector<Repeat> repeats_;
  std::vector<int> sorted_;        // plan() scratch: kept local indices in dof order
  std::vector<int> scratch_local_; // plan() scratch: the kept pairs of the dofs asked for
  std::vector<int> scratch_dofs_;
  // One plan for each set of dofs whose data are in the shared arrays, found by plan_key():
  // what a plan for the same dofs takes.
  std::vector<Plan> known_;
  KeyIndex index_;
  long searches_ = 0;
};

} // namespace nmm
