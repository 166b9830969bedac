// SPDX-License-Identifier: MIT
// mesh/detail/cgal_types.hpp — the CGAL types of the cover mesher. Included only from
// mesh/*.cpp: CGAL headers are slow to compile and stay out of every public header.
#pragma once

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>

namespace nmm::detail {

/// Exact predicates and exact (lazy) constructions: intersection points of joints and math
/// edges are exact rationals, so topology never depends on rounding.
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPoint = Kernel::Point_2;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;

/// Face data of the global arrangement of physical segments.
struct PhysicalFaceInfo {
  int material = -2; ///< region index; -1 void; -2 not yet known
  int index = -1;    ///< dense face index
};

/// The global arrangement: every edge carries the ids of the source segments overlapping it
/// (region loop edges, named-curve edges), consolidated where segments overlap; halfedge
/// data is the dense edge index.
using PhysicalTraits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, int>;
using PhysicalDcel = CGAL::Arr_extended_dcel<PhysicalTraits, int, int, PhysicalFaceInfo>;
using PhysicalArrangement = CGAL::Arrangement_2<PhysicalTraits, PhysicalDcel>;

/// Curve data of a local (one math triangle) arrangement: which triangle edges (bit k for
/// the edge from node k to node k+1) and which global physical edge an edge lies on.
/// Two global edges never overlap (they are edges of one arrangement), so one id suffices.
struct LocalCurveData {
  unsigned triangle_edges = 0;
  int physical_edge = -1;
  friend bool operator==(const LocalCurveData&, const LocalCurveData&) = default;
};

struct MergeLocalCurveData {
  LocalCurveData operator()(const LocalCurveData& a, const LocalCurveData& b) const {
    return {a.triangle_edges | b.triangle_edges, std::max(a.physical_edge, b.physical_edge)};
  }
};

/// Face data of a local arrangement: atom index, -1 for none, -2 outside the triangle.
using LocalTraits =
    CGAL::Arr_curve_data_traits_2<SegmentTraits, LocalCurveData, MergeLocalCurveData>;
using LocalDcel = CGAL::Arr_extended_dcel<LocalTraits, int, int, int>;
using LocalArrangement = CGAL::Arrangement_2<LocalTraits, LocalDcel>;

} // namespace nmm::detail
