// SPDX-License-Identifier: MIT
// contact/detail/contact_support.hpp — what the files of ContactSystem share inside contact/:
// index conversion, the perpendicular, the Gauss points of edge-to-edge pairs, the gap
// profile along an overlap and the interpolation of what a pair's points carry. Not part of
// the public interface (included only from contact/*.cpp).
#pragma once

#include "contact/contact_system.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

namespace nmm::detail {

/// An index as the size_t of a container's subscript.
inline std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// perp(w) = (w.y, -w.x): cross(u, w) = u . perp(w).
inline Point2 perp(const Point2& w) { return {w.y(), -w.x()}; }

/// Whether a contact in mode @p m has springs (slide or lock).
inline bool closed(ContactMode m) { return m != ContactMode::open; }

// Gauss-Legendre points on [0, 1]: two for order-0 covers (the squared gap along an edge is
// of degree 2), three for order 1 (degree 4).
inline constexpr std::array<double, 2> xi2{0.21132486540518712, 0.78867513459481288};
inline constexpr std::array<double, 2> w2{0.5, 0.5};
inline constexpr std::array<double, 3> xi3{0.11270166537925831, 0.5, 0.88729833462074169};
inline constexpr std::array<double, 3> w3{5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

/// The gap along an edge-to-edge overlap [lo, hi] (slave parameters): linear from its values
/// at the ends (order-0 covers), or quadratic through the ends and the middle (order 1).
class GapProfile {
public:
  GapProfile(double lo, double hi, std::span<const double> g) : lo_(lo), hi_(hi), c_(g.front()) {
    b_ = g.back() - g.front();
    if (g.size() == 3) {
      b_ = 4.0 * g[1] - 3.0 * g[0] - g[2];
      a_ = 2.0 * g[2] + 2.0 * g[0] - 4.0 * g[1];
    }
  }

  [[nodiscard]] double at(double u) const {
    const double s = hi_ > lo_ ? (u - lo_) / (hi_ - lo_) : 0.0;
    return (a_ * s + b_) * s + c_;
  }

  /// The part where the gap is negative (for a quadratic, the hull of its negative parts).
  /// Parts shorter than 1e-6 of the overlap count as none.
  [[nodiscard]] OverlapPart negative() const {
    // The ends and the roots in [0, 1], sorted.
    std::array<double, 4> cuts{0.0, 1.0};
    std::size_t n = 2;
    auto cut = [&](double s) {
      if (s >= 0.0 && s <= 1.0)
        cuts[n++] = s;
    };
    if (std::abs(a_) > 1e-14 * (std::abs(b_) + std::abs(c_))) {
      const double disc = b_ * b_ - 4.0 * a_ * c_;
      if (disc > 0.0) {
        const double q = -0.5 * (b_ + std::copysign(std::sqrt(disc), b_)); // stable roots
        cut(q / a_);
        if (q != 0.0)
          cut(c_ / q);
      }
    } else if (b_ != 0.0) {
      cut(-c_ / b_);
    }
    // Insertion sort of at most four values (std::sort's inlined introsort on a prefix of the
    // array trips GCC 12's -Warray-bounds: it cannot see n <= 4).
    for (std::size_t k = 1; k < n; ++k)
      for (std::size_t j = k; j > 0 && cuts[j] < cuts[j - 1]; --j)
        std::swap(cuts[j], cuts[j - 1]);
    double first = 2.0;
    double last = -1.0;
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const double mid = 0.5 * (cuts[k] + cuts[k + 1]);
      if (cuts[k + 1] > cuts[k] && (a_ * mid + b_) * mid + c_ < 0.0) {
        first = std::min(first, cuts[k]);
        last = std::max(last, cuts[k + 1]);
      }
    }
    if (last - first < 1e-6)
      return {};
    return {true, lo_ + (hi_ - lo_) * first, lo_ + (hi_ - lo_) * last};
  }

  /// Integral of |gap| du over [from, to] (Simpson's rule on a quadratic: exact where the
  /// gap keeps its sign).
  [[nodiscard]] double magnitude(double from, double to) const {
    if (to <= from)
      return 0.0;
    return (to - from) / 6.0 *
           (std::abs(at(from)) + 4.0 * std::abs(at(0.5 * (from + to))) + std::abs(at(to)));
  }

  /// Integral of |gap| du over the parts of [f1, t1] outside [f2, t2].
  [[nodiscard]] double outside(double f1, double t1, double f2, double t2) const {
    return magnitude(f1, std::min(t1, f2)) + magnitude(std::max(f1, t2), t1);
  }

private:
  double lo_;
  double hi_;
  double a_ = 0.0;
  double b_ = 0.0;
  double c_;
};

/// Lagrange interpolation of the (u, value) pairs at u (constant for one pair).
inline double interpolate(const std::vector<std::pair<double, double>>& values, double u) {
  if (values.size() == 1)
    return values.front().second;
  double result = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    double basis = 1.0;
    for (std::size_t j = 0; j < values.size(); ++j) {
      if (j == i)
        continue;
      const double span = values[i].first - values[j].first;
      if (std::abs(span) < 1e-12) // points on a vanishing part: take their mean
        return values.front().second;
      basis *= (u - values[j].first) / span;
    }
    result += basis * values[i].second;
  }
  return result;
}

/// The shear offset of a locked edge-to-edge pair at slave parameter u, from the offsets
/// (anchor minus the projection of the slave point on the master, in master parameters) of
/// its points: interpolated between them, and the nearest one's beyond them. The springs of
/// a pair move when the part that presses grows or shrinks; extrapolating anchors (or a
/// polynomial of the offsets) from a short part to a long one multiplies the rounding-size
/// differences between the points by the ratio of the lengths (millimetres of shear that
/// never happened, a pressed part growing from 1e-5 m to 1e-3 m; examples/10).
inline double offset_at(const std::vector<std::pair<double, double>>& offsets, double u) {
  double lo = offsets.front().first;
  double hi = lo;
  for (const auto& [v, offset] : offsets) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return interpolate(offsets, std::clamp(u, lo, hi));
}

} // namespace nmm::detail
