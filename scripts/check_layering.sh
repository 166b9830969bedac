#!/usr/bin/env bash
# Fails when an #include points against the module order of DESIGN.md
# (io -> solver -> contact -> manifold -> mesh), or when CGAL, CHOLMOD, gmsh, VTK, toml++
# or CLI11 appear outside the module that owns them (CGAL: mesh/*.cpp only).
# Usage: check_layering.sh [SOURCE_ROOT]
# One grep reads every include line of the tree; the rest is bash without a fork per line
# (the check took 11 s of a test run forking a subshell per include, 0.1 s this way).
set -u
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root" || exit 2
modules=(mesh manifold contact solver io)
declare -A rank
for i in "${!modules[@]}"; do rank[${modules[$i]}]=$i; done
# Third-party headers each have one owner: pattern (after "#include <" or '#include "'),
# owning module, name.
owners=('CGAL/|mesh|CGAL' 'cholmod|suitesparse/|solver|CHOLMOD' 'gmsh|io|gmsh' 'vtk|io|VTK'
        'toml\+\+|io|toml++' 'CLI/|io|CLI11')
status=0
declare -A said
complain() { [ -n "${said[$1]+set}" ] && return; said[$1]=1; echo "layering: $1"; status=1; }

dirs=()
for module in "${modules[@]}"; do [ -d "$module" ] && dirs+=("$module"); done
[ ${#dirs[@]} -eq 0 ] && { echo "layering: ok"; exit 0; }
include_re='^[[:space:]]*#[[:space:]]*include[[:space:]]*([<"])([^">]+)[">]'
while IFS= read -r hit; do
  file=${hit%%:*}
  rest=${hit#*:}
  line=${rest%%:*}
  text=${rest#*:}
  [[ "$text" =~ $include_re ]] || continue
  delimiter=${BASH_REMATCH[1]}
  include=${BASH_REMATCH[2]}
  module=${file%%/*}
  if [ "$delimiter" = '"' ]; then
    target=${include%%/*}
    if [ -n "${rank[$target]+set}" ] && [ "${rank[$target]}" -gt "${rank[$module]}" ]; then
      complain "$file:$line includes \"$include\": $module/ may not depend on $target/ (order: io -> solver -> contact -> manifold -> mesh)"
    fi
  fi
  for entry in "${owners[@]}"; do
    name=${entry##*|}
    owner=${entry%|*}
    owner=${owner##*|}
    pattern=${entry%|*|*}
    if [[ "$include" =~ ^($pattern) ]]; then
      [ "$module" != "$owner" ] && complain "$file includes $name headers; only $owner/ may"
      if [ "$name" = CGAL ] && [ "$module" = mesh ] && [[ "$file" == *.hpp || "$file" == *.h ]] &&
         [[ "$file" != mesh/detail/* ]]; then
        complain "$file is a public header including CGAL; keep CGAL in mesh/*.cpp (or mesh/detail/)"
      fi
    fi
  done
done < <(find "${dirs[@]}" -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) -print0 |
         sort -z | xargs -0 -r grep -nHE '^[[:space:]]*#[[:space:]]*include' /dev/null)
[ "$status" -eq 0 ] && echo "layering: ok"
exit "$status"
