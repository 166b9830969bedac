// SPDX-License-Identifier: MIT
// contact/detection.hpp — contact detection with Shi's entrance theory (1997, chapter 3.1-3.2
// and 6.1): a broad phase over boundary edges, then angle-to-edge and angle-to-angle
// contacts chosen by the distance and angle-overlap criteria, edge-to-edge contacts between
// facing parallel edges.
#pragma once

#include "mesh/geometry.hpp"

#include <cstdint>
#include <vector>

namespace nmm {

/// The boundary of the bodies at the start of a step, flattened: every loop vertex has a
/// global id, and edge i runs from vertex i to vertex next[i] with the material on its left.
struct ContactBoundary {
  std::vector<Point2> position; ///< current position of each vertex
  std::vector<int> next;        ///< next vertex of the same loop
  std::vector<int> previous;    ///< previous vertex of the same loop
  std::vector<int> block;       ///< block of the loop of each vertex
  /// Area of each block (edge-to-edge contacts take the larger block's edge as master); may
  /// be empty (the higher edge id is the master).
  std::vector<double> block_area;

  [[nodiscard]] int n_vertices() const noexcept { return static_cast<int>(position.size()); }
  /// Angle of the material wedge at vertex v (radians, in (0, 2 pi]): pi on a straight
  /// boundary, 2 pi at a crack tip (a slit's end), < pi at a convex corner.
  [[nodiscard]] double angle(int v) const;
  /// Unit direction of edge e.
  [[nodiscard]] Point2 direction(int e) const;
  /// Unit outward normal of edge e (to the right of its direction: the void side).
  [[nodiscard]] Point2 outward_normal(int e) const;
  /// Whether edges e and f share a vertex (so they cannot touch each other).
  [[nodiscard]] bool adjacent(int e, int f) const;
};

/// The rounding of the coordinates of @p boundary: 512 units in the last place of its largest
/// coordinate, m. Points closer than this are one point, and gaps and motions smaller than it
/// decide no contact mode (a body at rest moves by about one unit in a step).
[[nodiscard]] double rounding_length(const ContactBoundary& boundary);

/// What a contact is in Shi's entrance theory.
enum class ContactKind : std::uint8_t {
  vertex_edge, ///< an angle against an entrance line (angle-to-edge, or the chosen line of
               ///< an angle-to-angle contact)
  edge_edge    ///< two facing parallel edges: springs integrated along their overlap
};

/// A contact found at the start of a step. Its identity is stable from step to step (loop
/// vertices keep their ids), so states and shear history transfer (Shi 1997, chapter 3.3).
struct ContactCandidate {
  ContactKind kind = ContactKind::vertex_edge;
  /// vertex_edge: the angle's vertex. edge_edge: the slave edge (its vertices give the points).
  int slave = -1;
  /// The entrance line (an edge id).
  int master = -1;
  /// For an angle-to-angle contact between two convex angles, the alternative contact (the
  /// other vertex against the other entrance line): the open-close iteration uses the one
  /// passed first (Shi 3.2 [1]); -1 otherwise.
  int alternative_slave = -1;
  int alternative_master = -1;
  /// vertex_edge: the vertex lies at a straight end of the master (or inside it by no more
  /// than an edge-to-edge contact leaves out as touching) and one of its edges, @c end_face,
  /// is in edge-to-edge contact with @c end_beyond, the master's straight continuation
  /// there: the end of a face on a joint. Its spring stiffens the end of that pair and
  /// represents no length of its own; -1 when the vertex ends no such pair.
  int end_face = -1;
  int end_beyond = -1;

  [[nodiscard]] std::uint64_t key() const noexcept {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(slave)) << 33) |
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(master)) << 1) |
           (kind == ContactKind::edge_edge ? 1U : 0U);
  }
};

/// Whether a ContactCandidate::key() (and so a ContactPoint's key) is an edge-to-edge pair's.
[[nodiscard]] constexpr bool is_edge_pair(std::uint64_t key) noexcept { return (key & 1U) != 0; }

/// Two edges whose projections overlap by no more than this fraction of the master edge only
/// touch at their ends: no edge-to-edge contact (the neighbouring pairs hold the ends).
inline constexpr double touching_end = 1e-6;

/// Criteria of the detection (Shi 3.1).
struct DetectionOptions {
  /// Largest distance between an angle and an edge, or two angles, that can close in one
  /// step: twice the maximum step displacement (criteria [1] and [2]), m.
  double distance = 0.0;
  /// Largest overlap of the angles when translated without rotation: twice the maximum
  /// step edge rotation (criteria [3] and [4]); Shi's program sets delta = 1.5 degrees.
  double angle_overlap = 2.0 * 1.5 * 3.14159265358979323846 / 180.0;
  /// Largest penetration a new contact may start with (closed contacts carried over from the
  /// last step may have more: their springs' own penetration), m.
  double penetration = 0.0;
};

/// Counters of one detection, for benchmarks and summary.json.
struct DetectionStats {
  long edge_pairs = 0;    ///< pairs of boxes overlapping in the broad phase
  long vertex_edge = 0;   ///< angle-to-edge contacts
  long vertex_vertex = 0; ///< angle-to-angle contacts
  long edge_edge = 0;     ///< edge-to-edge contacts
};

/// Finds every contact that can close within the step.
/// @param keep  keys of contacts closed at the end of the last step: they are kept even if
///              their penetration exceeds options.penetration.
/// Broad phase: a uniform grid of the edges' boxes grown by options.distance, O(n + pairs).
[[nodiscard]] std::vector<ContactCandidate> detect_contacts(const ContactBoundary& boundary,
                                                            const DetectionOptions& options,
                                                            const std::vector<std::uint64_t>& keep,
                                                            DetectionStats* stats = nullptr);

} // namespace nmm
