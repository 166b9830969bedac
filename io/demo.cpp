// SPDX-License-Identifier: MIT
#include "io/demo.hpp"

#include "manifold/regular_shapes.hpp"
#include "manifold/simplex_integration.hpp"

#include <cmath>
#include <iomanip>
#include <numbers>

namespace nmm {

bool run_simplex_integration_demo(std::ostream& out) {
  // Closed forms from the tables of Shi's second paper (Figures 3 and 4).
  const double s3 = std::sqrt(3.0);
  const double s5 = std::sqrt(5.0);
  struct PolygonRow {
    const char* name;
    int n;
    double area;
  };
  const PolygonRow polygons[] = {{"triangle", 3, 0.75 * s3},
                                 {"square", 4, 2.0},
                                 {"pentagon", 5, 0.625 * std::sqrt(10.0 + 2.0 * s5)},
                                 {"hexagon", 6, 1.5 * s3}};
  bool all_match = true;
  auto matches = [&](double value, double expected) {
    const bool ok = std::abs(value - expected) <= 1e-12 * std::max(1.0, std::abs(expected));
    all_match = all_match && ok;
    return ok ? "ok" : "MISMATCH";
  };

  out << "Simplex integration (Shi 1997, second paper): exact integrals from boundary vertices\n\n"
      << "Regular polygons in the unit circle\n"
      << "  polygon     area (simplex)    area (closed form)  centroid            polar moment\n";
  out << std::fixed << std::setprecision(12);
  for (const PolygonRow& row : polygons) {
    const Moments2 m = polygon_moments(regular_polygon(row.n), 2, Point2::Zero());
    const Point2 c = m.centroid();
    out << "  " << std::left << std::setw(10) << row.name << std::right << std::setw(16) << m.area()
        << std::setw(20) << row.area << "  (" << std::setprecision(1) << std::abs(c.x()) << ", "
        << std::abs(c.y()) << ")" << std::setprecision(12) << std::setw(20) << m(2, 0) + m(0, 2)
        << "  " << matches(m.area(), row.area) << '\n';
  }

  struct SolidRow {
    const char* name;
    RegularSolid kind;
    double volume;
  };
  const SolidRow solids[] = {
      {"tetrahedron", RegularSolid::tetrahedron, 8.0 / 27.0 * s3},
      {"cube", RegularSolid::cube, 8.0 / (3.0 * s3)},
      {"dodecahedron", RegularSolid::dodecahedron, 2.0 / 3.0 / s3 * std::sqrt(10.0 * (3.0 + s5))}};
  out << "\nRegular solids in the unit sphere\n"
      << "  solid         volume (simplex)  volume (closed form)\n";
  for (const SolidRow& row : solids) {
    const Moments3 m = polyhedron_moments(regular_solid(row.kind), 4, Point3::Zero());
    out << "  " << std::left << std::setw(12) << row.name << std::right << std::setw(18)
        << m.volume() << std::setw(20) << row.volume << "  " << matches(m.volume(), row.volume)
        << '\n';
  }
  out << "\nShi's tables: 1.299038, 2.000000, 2.377641, 2.598076; 0.51320, 1.53960, 2.78516.\n";
  return all_match;
}

} // namespace nmm
