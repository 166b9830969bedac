#!/usr/bin/env bash
# Fails when an #include points against the module order of DESIGN.md
# (io -> solver -> contact -> manifold -> mesh), or when CGAL, CHOLMOD, gmsh, VTK, toml++
# or CLI11 appear outside the module that owns them (CGAL: mesh/*.cpp only).
# Usage: check_layering.sh [SOURCE_ROOT]
set -u
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root" || exit 2
modules=(mesh manifold contact solver io)
rank() { local i; for i in "${!modules[@]}"; do [ "${modules[$i]}" = "$1" ] && echo "$i" && return; done; echo -1; }
status=0
complain() { echo "layering: $1"; status=1; }

for module in "${modules[@]}"; do
  [ -d "$module" ] || continue
  own=$(rank "$module")
  while IFS= read -r file; do
    while IFS=: read -r line include; do
      target=${include%%/*}
      r=$(rank "$target")
      if [ "$r" -gt "$own" ]; then
        complain "$file:$line includes \"$include\": $module/ may not depend on $target/ (order: io -> solver -> contact -> manifold -> mesh)"
      fi
    done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$file" | sed -E 's/^([0-9]+):[^"]*"([^"]+)".*/\1:\2/')
    # Third-party headers each have one owner.
    check_owner() {  # pattern owner description
      if grep -qE "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"]($1)" "$file" && [ "$module" != "$2" ]; then
        complain "$file includes $3 headers; only $2/ may"
      fi
    }
    check_owner 'CGAL/' mesh CGAL
    check_owner 'cholmod|suitesparse/' solver CHOLMOD
    check_owner 'gmsh' io gmsh
    check_owner 'vtk' io VTK
    check_owner 'toml\+\+' io toml++
    check_owner 'CLI/' io CLI11
    if [ "$module" = mesh ] && [[ "$file" == *.hpp || "$file" == *.h ]] && [[ "$file" != mesh/detail/* ]] &&
       grep -qE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]CGAL/' "$file"; then
      complain "$file is a public header including CGAL; keep CGAL in mesh/*.cpp (or mesh/detail/)"
    fi
  done < <(find "$module" -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) | sort)
done
[ "$status" -eq 0 ] && echo "layering: ok"
exit "$status"
