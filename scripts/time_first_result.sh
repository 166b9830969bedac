#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Times the README's first result as a newcomer gets it: a fresh Debian 12 system, a fresh
# clone, `bash scripts/run.sh` (it installs the Debian packages, builds nmm and runs the
# bundled example). The figure in the README's "The two commands" comes from this script.
#
# Usage (as root: debootstrap, mount and chroot need it):
#   scripts/time_first_result.sh [ROOT]     ROOT: where the fresh root is made (default
#                                           build/first-result-root, removed first)
# Steps, each timed: debootstrap --variant=minbase bookworm (not part of the figure: the
# newcomer has a Debian 12 already), apt-get install git ca-certificates (the newcomer's
# "install git"), git clone of this repository's committed HEAD (by the host's git), then
# scripts/run.sh in the clone. Nothing comes from the host's package cache or ccache: packages are downloaded from
# DEBIAN_MIRROR (default deb.debian.org) and everything is compiled. The mounts live in a
# private mount namespace (unshare) and vanish with the script.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
root=$(realpath -m -- "${1:-$repo/build/first-result-root}")
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}

die() { echo "time_first_result.sh: $*" >&2; exit 1; }
[[ $EUID -eq 0 ]] || die "must run as root (debootstrap, mount and chroot need it)"
command -v debootstrap > /dev/null || die "needs debootstrap: apt-get install debootstrap"
if [[ ${NMM_FIRST_RESULT_NAMESPACE:-} != "$$" ]]; then
  NMM_FIRST_RESULT_NAMESPACE=$$ exec unshare --mount --propagation private -- "$BASH" "$0" "$@"
fi

timed() {  # timed LABEL COMMAND...: runs the command, prints its wall time
  local start=$SECONDS status=0
  "${@:2}" || status=$?
  echo "time_first_result.sh: $1: $((SECONDS - start)) s" >&2
  return "$status"
}

if [[ -e $root ]]; then
  [[ -z $(awk -v d="$root" 'index($5, d) == 1' /proc/self/mountinfo) ]] ||
    die "something is mounted under $root; unmount it first"
  rm -rf --one-file-system "$root"
fi
make_root() { debootstrap --variant=minbase bookworm "$root" "$mirror" > "$root.debootstrap.log" 2>&1; }
timed "debootstrap (not counted)" make_root || die "debootstrap failed; see $root.debootstrap.log"
cat > "$root/etc/apt/sources.list" << EOF
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb http://deb.debian.org/debian-security bookworm-security main
EOF
printf '#!/bin/sh\nexit 101\n' > "$root/usr/sbin/policy-rc.d"  # start no services
chmod +x "$root/usr/sbin/policy-rc.d"
mount -t proc proc "$root/proc"
mount -t sysfs sysfs "$root/sys"
mount --rbind /dev "$root/dev"

in_root() { chroot "$root" env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 "$@"; }
total=$SECONDS
timed "apt-get install git" in_root sh -c \
  'apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq git ca-certificates > /dev/null'
# Cloned by the host's git (a worktree's .git points outside it), as from a server: no
# hard links, no build tree, only the committed files.
timed "git clone" git clone -q --no-hardlinks "file://$repo" "$root/root/nmm"
timed "bash scripts/run.sh (packages, build, the example)" in_root sh -c 'cd /root/nmm && bash scripts/run.sh'
echo "time_first_result.sh: from a fresh Debian 12 to the example's result: $((SECONDS - total)) s" >&2
