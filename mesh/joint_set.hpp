// SPDX-License-Identifier: MIT
// mesh/joint_set.hpp — joints generated from a statistical description (a joint set: angle,
// spacing, trace, gap, origin, deviations), clipped to the material, as UDEC's `jset` does.
// The case file's `[[joint_set]]` tables (docs/case-file.md) are read by io/ into
// JointSetParameters; the segments returned here become joints of the physical mesh exactly
// like drawn Physical Curves.
#pragma once

#include "mesh/geometry.hpp"
#include "mesh/physical_mesh.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace nmm {

/// One joint set: parallel lines `spacing` apart, normal to them, with joints of length
/// `trace` separated by rock bridges of length `gap` along each line (UDEC's `jset`).
struct JointSetParameters {
  /// Where the set was given, for messages ("case.toml:12: [[joint_set]]").
  std::string where;
  /// Direction of the traces, degrees counter-clockwise from +x.
  double angle_degrees = 0.0;
  /// Distance between neighbouring lines of the set, measured normal to them (m), > 0.
  double spacing = 0.0;
  /// Length of each joint along its line (m), > 0; empty: persistent (the whole line).
  std::optional<double> trace;
  /// Rock bridge between consecutive traces of one line (m), >= 0.
  double gap = 0.0;
  /// A point on one joint of the set: the line through it is a line of the set and, for
  /// non-persistent joints, a trace starts there (in the direction of the angle).
  Point2 origin = Point2::Zero();
  /// Half-widths of the uniform distributions each value is drawn from:
  /// spacing in [spacing - d, spacing + d] for each line, the angle of each line (persistent)
  /// or trace, each trace length and each gap. Each < its mean (the angle's < 90 degrees).
  double spacing_deviation = 0.0;
  double angle_deviation_degrees = 0.0;
  double trace_deviation = 0.0;
  double gap_deviation = 0.0;
  /// Seed of the std::mt19937_64 the deviations are drawn from.
  std::uint64_t seed = 0;
  /// Indices of PhysicalMesh::regions the joints are clipped to; empty: all material.
  std::vector<int> regions;
  /// Joints closer than this (m) to a boundary, a drawn joint or each other are snapped or
  /// dropped; 0: automatic (default_snap_tolerance()).
  double snap_tolerance = 0.0;
  /// Most joints (pieces of traces inside the material) this set may make.
  long max_joints = 20'000;
  /// Most blocks the joints of this and the sets before it may cut (an upper bound counted
  /// from the crossings, see JointSetResult::block_bound).
  long max_blocks = 100'000;
};

/// One generated joint: a straight segment (m).
struct JointSegment {
  Point2 a;
  Point2 b;
};

/// What generate_joint_sets() made.
struct JointSetResult {
  /// Per set (in the order given), its joints. An end on a material boundary lies a little
  /// beyond it (1e-3 of the snap tolerance, in the void or the neighbouring material), so that
  /// the joint cuts through the boundary exactly rather than stopping a rounding error short.
  std::vector<std::vector<JointSegment>> joints;
  /// Per set, the snap tolerance used (m).
  std::vector<double> snap_tolerance;
  /// Upper bound of the number of blocks the generated joints cut the material into: the
  /// number of material polygons plus, for every generated joint, the number of points at
  /// which it meets a boundary, a drawn joint or a generated joint before it, less one (a
  /// segment that meets the lines before it at k points splits at most k - 1 faces). Exact
  /// for persistent sets across a convex region without drawn joints; blocks the drawn
  /// joints cut on their own are not counted.
  long block_bound = 0;
  /// Notes for the user (joints dropped or snapped, and why), each starting with `where`.
  std::vector<std::string> notes;
};

/// The automatic snap tolerance: 2e-3 of the diagonal of the material's bounding box, at most
/// a tenth of the smallest spacing of the sets (so that the lines of a set never snap onto
/// each other).
[[nodiscard]] double default_snap_tolerance(const PhysicalMesh& physical,
                                            std::span<const JointSetParameters> sets);

/// Generates the joints of every set (docs/case-file.md, `[[joint_set]]`).
///
/// Each set's lines cover the bounding box of its regions; each line is cut into traces and
/// gaps starting at the origin's line and trace, values drawn in a fixed order (lines from
/// the origin's upwards then downwards in the normal direction, along each line forwards
/// then backwards) from uniform distributions made from the raw 64-bit output of
/// std::mt19937_64, so the joints do not depend on the standard library's distributions.
/// Each trace is clipped to the region's polygons; then, with tol the snap tolerance:
/// - an end within tol of the boundary (along its line) is moved onto the boundary;
/// - an end inside the material within tol of a drawn or an earlier generated joint is
///   extended (or shortened) to it;
/// - a piece shorter than tol, a piece lying everywhere within tol of the boundary or of
///   other joints, and a piece passing within tol of a corner of the boundary (turning by
///   more than 10 degrees) or of a point where earlier joints meet each other or the
///   boundary is dropped (it would cut a sliver block); each drop and snap is counted in
///   `notes`.
/// @param drawn_joints  PhysicalMesh::curves indices of the drawn joints.
/// @pre @p physical is validated; every set's parameters are in range (io/ checks them).
/// @throws InputError naming the set's `where` when a set would make more than its
///         max_joints joints or more than max_blocks blocks, saying how many and how to raise
///         the limit.
[[nodiscard]] JointSetResult generate_joint_sets(const PhysicalMesh& physical,
                                                 std::span<const int> drawn_joints,
                                                 std::span<const JointSetParameters> sets);

} // namespace nmm
