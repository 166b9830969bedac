// SPDX-License-Identifier: MIT
#include "solver/dof_map.hpp"

#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace nmm {

namespace {

/// A slave: raw unknown = sum coefficient * raw free unknown + constant (terms sorted by
/// unknown).
struct Expression {
  std::vector<std::pair<int, double>> terms;
  double constant = 0.0;
};

using Terms = std::vector<std::pair<int, double>>;

/// A row's coefficients summed per raw unknown in a dense array (a std::map per row allocated
/// a node for every term, in every step of an order-1 model): add() sums in the order
/// called, take() hands the sums out sorted by unknown and clears the array for the next row.
class RowSum {
public:
  explicit RowSum(std::size_t n) : sum_(n, 0.0), touched_(n, 0) {}
  void add(int raw, double c) {
    const auto r = static_cast<std::size_t>(raw);
    if (touched_[r] == 0) {
      touched_[r] = 1;
      order_.push_back(raw);
    }
    sum_[r] += c;
  }
  void take(Terms& out) {
    std::sort(order_.begin(), order_.end());
    out.clear();
    for (const int raw : order_) {
      const auto r = static_cast<std::size_t>(raw);
      out.emplace_back(raw, sum_[r]);
      sum_[r] = 0.0;
      touched_[r] = 0;
    }
    order_.clear();
  }

private:
  std::vector<double> sum_;
  std::vector<char> touched_;
  std::vector<int> order_;
};

/// @p e's terms with @p c times @p fresh's added (both sorted by unknown; a term only in
/// fresh starts from 0, as a new entry would), and @p u among the users of every unknown
/// that is new to @p e.
void add_terms(Expression& e,
               double c,
               const Terms& fresh,
               int u,
               std::vector<std::vector<int>>& users,
               Terms& merged) {
  merged.clear();
  auto old = e.terms.begin();
  for (const auto& [raw, d] : fresh) {
    for (; old != e.terms.end() && old->first < raw; ++old)
      merged.push_back(*old);
    if (old != e.terms.end() && old->first == raw) {
      merged.emplace_back(raw, old->second + c * d);
      ++old;
    } else {
      users[static_cast<std::size_t>(raw)].push_back(u);
      merged.emplace_back(raw, 0.0 + c * d);
    }
  }
  merged.insert(merged.end(), old, e.terms.end());
  e.terms.swap(merged);
}

} // namespace

DofMap::DofMap(int n_raw,
               std::span<const LinearConstraint> constraints,
               double tolerance,
               double length,
               const DofMap* previous)
    : reduced_of_(static_cast<std::size_t>(n_raw), 0), slaves_(static_cast<std::size_t>(n_raw)) {
  std::vector<int> slave_of(static_cast<std::size_t>(n_raw), -1);
  std::vector<Expression> expressions;
  // For each raw unknown, the expressions that may mention it (stale entries are skipped).
  std::vector<std::vector<int>> users(static_cast<std::size_t>(n_raw));
  stats_.constraints = static_cast<int>(constraints.size());
  RowSum sum(static_cast<std::size_t>(n_raw));
  Terms all;
  Terms reduced;
  Terms merged;

  for (const LinearConstraint& row : constraints) {
    double scale = 0.0;
    for (const auto& [raw, c] : row.terms) {
      NMM_ASSERT(raw >= 0 && raw < n_raw, "constraint on an unknown out of range");
      scale = std::max(scale, std::abs(c));
    }
    // Substitute the slaves chosen so far: the row in free unknowns only.
    double rhs = row.value;
    for (const auto& [raw, c] : row.terms) {
      const int s = slave_of[static_cast<std::size_t>(raw)];
      if (s < 0) {
        sum.add(raw, c);
        continue;
      }
      const Expression& e = expressions[static_cast<std::size_t>(s)];
      rhs -= c * e.constant;
      for (const auto& [other, d] : e.terms)
        sum.add(other, c * d);
    }
    sum.take(all);
    double largest = 0.0;
    reduced.clear();
    for (const auto& term : all) {
      if (std::abs(term.second) > tolerance * scale) {
        reduced.push_back(term);
        largest = std::max(largest, std::abs(term.second));
      }
    }
    // A row whose remaining coefficients are all far below its own is numerically a
    // combination of the rows before it (e.g. one more point of a held straight edge under
    // order-1 covers, whose coefficients cancel only to rounding): pivoting on what is left
    // would divide rounding by rounding.
    if (largest <= 1e-8 * scale)
      reduced.clear();
    if (reduced.empty()) {
      if (std::abs(rhs) > std::max(tolerance * std::abs(row.value), 1e-9 * length)) {
        std::ostringstream message;
        message << "contradictory supports: " << row.origin
                << " cannot be met together with the supports before it (they leave it " << rhs
                << " off): either two supports impose different displacements on the same "
                   "point, or imposed displacements vary faster than the cover functions "
                   "near it can follow (e.g. on two edges meeting at a corner); remove one, "
                   "or use method = \"penalty\" there";
        throw InputError(message.str());
      }
      ++stats_.redundant;
      continue;
    }
    int pivot = -1;
    const auto preferred =
        std::lower_bound(reduced.begin(), reduced.end(), row.preferred_slave,
                         [](const std::pair<int, double>& t, int raw) { return t.first < raw; });
    if (preferred != reduced.end() && preferred->first == row.preferred_slave &&
        std::abs(preferred->second) >= 0.1 * largest) {
      pivot = preferred->first;
    } else if (previous != nullptr && previous->n_raw() == n_raw) {
      // The largest of the last step's slaves that is big enough, if any.
      double best = 0.1 * largest;
      for (const auto& [raw, c] : reduced) {
        if (previous->is_slave(raw) && std::abs(c) >= best) {
          best = std::abs(c);
          pivot = raw;
        }
      }
    }
    if (pivot < 0) {
      for (const auto& [raw, c] : reduced) {
        if (std::abs(c) == largest) {
          pivot = raw;
          break;
        }
      }
    }
    const double a = std::find_if(reduced.begin(), reduced.end(), [&](const auto& t) {
                       return t.first == pivot;
                     })->second;
    Expression fresh;
    fresh.constant = rhs / a;
    for (const auto& [raw, c] : reduced) {
      if (raw != pivot)
        fresh.terms.emplace_back(raw, -c / a);
    }
    // Back-substitute the new slave into every expression that mentions it.
    for (const int u : users[static_cast<std::size_t>(pivot)]) {
      Expression& e = expressions[static_cast<std::size_t>(u)];
      const auto found = std::find_if(e.terms.begin(), e.terms.end(),
                                      [&](const auto& t) { return t.first == pivot; });
      if (found == e.terms.end())
        continue;
      const double c = found->second;
      e.terms.erase(found);
      e.constant += c * fresh.constant;
      add_terms(e, c, fresh.terms, u, users, merged);
    }
    users[static_cast<std::size_t>(pivot)].clear();
    const int index = static_cast<int>(expressions.size());
    for (const auto& [raw, c] : fresh.terms)
      users[static_cast<std::size_t>(raw)].push_back(index);
    slave_of[static_cast<std::size_t>(pivot)] = index;
    expressions.push_back(std::move(fresh));
    ++stats_.eliminated;
  }

  for (int raw = 0; raw < n_raw; ++raw) {
    if (slave_of[static_cast<std::size_t>(raw)] < 0)
      reduced_of_[static_cast<std::size_t>(raw)] = n_reduced_++;
    else
      reduced_of_[static_cast<std::size_t>(raw)] = -1;
  }
  for (int raw = 0; raw < n_raw; ++raw) {
    const int s = slave_of[static_cast<std::size_t>(raw)];
    if (s < 0)
      continue;
    const Expression& e = expressions[static_cast<std::size_t>(s)];
    DofExpansion& out = slaves_[static_cast<std::size_t>(raw)];
    out.constant = e.constant;
    for (const auto& [free, c] : e.terms) {
      if (c != 0.0)
        out.terms.emplace_back(reduced_of_[static_cast<std::size_t>(free)], c);
    }
  }
}

DofExpansion DofMap::expansion(int raw) const {
  const int r = reduced(raw);
  if (r >= 0)
    return {{{r, 1.0}}, 0.0};
  return slaves_[static_cast<std::size_t>(raw)];
}

Eigen::VectorXd DofMap::expand(const Eigen::VectorXd& reduced_values) const {
  NMM_ASSERT(reduced_values.size() == n_reduced_, "wrong size of reduced vector");
  Eigen::VectorXd raw(n_raw());
  for (int i = 0; i < n_raw(); ++i) {
    const int r = reduced(i);
    if (r >= 0) {
      raw(i) = reduced_values(r);
      continue;
    }
    const DofExpansion& e = slaves_[static_cast<std::size_t>(i)];
    double v = e.constant;
    for (const auto& [j, c] : e.terms)
      v += c * reduced_values(j);
    raw(i) = v;
  }
  return raw;
}

Eigen::VectorXd DofMap::restrict(const Eigen::VectorXd& raw) const {
  NMM_ASSERT(raw.size() == n_raw(), "wrong size of raw vector");
  Eigen::VectorXd result = Eigen::VectorXd::Zero(n_reduced_);
  for (int i = 0; i < n_raw(); ++i) {
    const int r = reduced(i);
    if (r >= 0) {
      result(r) += raw(i);
      continue;
    }
    for (const auto& [j, c] : slaves_[static_cast<std::size_t>(i)].terms)
      result(j) += c * raw(i);
  }
  return result;
}

} // namespace nmm
