// SPDX-License-Identifier: MIT
#include "manifold/material.hpp"

#include "mesh/error.hpp"

#include <cmath>
#include <sstream>

namespace nmm {

Eigen::Matrix3d elasticity_matrix(const ElasticMaterial& material) {
  const double e = material.young;
  const double nu = material.poisson;
  Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
  if (material.plane == PlaneCondition::stress) {
    const double f = e / (1.0 - nu * nu);
    d << f, f * nu, 0.0, f * nu, f, 0.0, 0.0, 0.0, f * (1.0 - nu) / 2.0;
  } else {
    const double f = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    d << f * (1.0 - nu), f * nu, 0.0, f * nu, f * (1.0 - nu), 0.0, 0.0, 0.0,
        f * (1.0 - 2.0 * nu) / 2.0;
  }
  return d;
}

void validate_material(const ElasticMaterial& material) {
  auto fail = [&](const std::string& what) {
    throw InputError("material \"" + material.name + "\": " + what);
  };
  if (!std::isfinite(material.young) || !(material.young > 0.0))
    fail("Young's modulus must be a positive number of pascals");
  if (!std::isfinite(material.poisson) || !(material.poisson > -1.0) || !(material.poisson < 0.5))
    fail("Poisson's ratio must lie in (-1, 0.5)");
  if (!std::isfinite(material.density) || material.density < 0.0)
    fail("density must be zero or a positive number of kg/m³");
  if (!std::isfinite(material.thickness) || !(material.thickness > 0.0))
    fail("thickness must be a positive number of metres");
}

} // namespace nmm
