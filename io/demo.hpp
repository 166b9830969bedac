// SPDX-License-Identifier: MIT
// io/demo.hpp — the bundled demonstration run by `nmm` with no arguments.
#pragma once

#include <ostream>

namespace nmm {

/// Prints Shi's simplex-integration tables (areas and centroids of the regular polygons,
/// volumes of the regular solids in the unit sphere) computed by manifold/ next to the
/// published values. @return true when every value matches its closed form to 1e-12.
bool run_simplex_integration_demo(std::ostream& out);

} // namespace nmm
