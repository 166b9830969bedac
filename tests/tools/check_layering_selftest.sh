#!/usr/bin/env bash
# The layering check must reject an upward include and a misplaced third-party header, and
# accept a clean tree. Usage: check_layering_selftest.sh PATH/TO/check_layering.sh
set -u
checker=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp"/{mesh,manifold,contact,solver,io}
echo '#include "mesh/geometry.hpp"' > "$tmp/manifold/ok.cpp"
bash "$checker" "$tmp" > /dev/null || { echo "clean tree rejected"; exit 1; }
echo '#include "solver/dof_map.hpp"' > "$tmp/mesh/bad.cpp"
bash "$checker" "$tmp" > /dev/null && { echo "upward include not detected"; exit 1; }
rm "$tmp/mesh/bad.cpp"
echo '#include <CGAL/Exact_predicates_exact_constructions_kernel.h>' > "$tmp/manifold/cgal.cpp"
bash "$checker" "$tmp" > /dev/null && { echo "CGAL outside mesh/ not detected"; exit 1; }
rm "$tmp/manifold/cgal.cpp"
echo '#include <CGAL/Arrangement_2.h>' > "$tmp/mesh/public.hpp"
bash "$checker" "$tmp" > /dev/null && { echo "CGAL in a public header not detected"; exit 1; }
echo "layering self-test: ok"
