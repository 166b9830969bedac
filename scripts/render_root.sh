#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Run scripts/render.py (ParaView's pvbatch) inside a private Debian 12 root.
#
# Why: render.py needs pvbatch, packaged in Debian 12 as python3-paraview, which conflicts
# with python3-vtk9; the project's build needs libvtk9-dev, which pulls in python3-vtk9. One
# system cannot hold both, so ParaView lives in a debootstrap'ed bookworm root under
# build/paraview-root (git-ignored) and this script runs render.py there, under xvfb-run.
#
# Usage (as root: debootstrap, mount and chroot need it):
#   scripts/render_root.sh RENDER.PY-ARGUMENTS...   render (see scripts/render.py --help)
#   scripts/render_root.sh --setup                  only create the root
#   scripts/render_root.sh --help
# e.g.
#   scripts/render_root.sh /tmp/out/case.pvd docs/pictures/beam.png --field stress --component 0
#
# The first call creates the root (a few minutes, about 2.4 GB; debootstrap is installed on
# the host when missing); later calls reuse it. A render takes about 10 s. Every argument
# ending in .pvd, .vtu, .vtp or .png is a path: absolute or relative to the current
# directory. The repository is seen in the root as /repo; the directory of any other path
# is bind-mounted for the run (a .pvd's step files must sit in its directory or below).
# The folder of a .png is created when missing. Paths in render.py's messages are shown as
# on the host.
#
# Everything is mounted in a private mount namespace (unshare): the mounts are invisible
# outside this script and its children and vanish with them, even when it is killed. So a
# bind mount of the repository is never left in build/paraview-root, where a recursive
# delete of build/ would go through it into the repository. One render (or setup) at a time:
# a lock on the directory that holds the root.
# Environment: NMM_RENDER_ROOT (the root's directory), DEBIAN_MIRROR.
#
# ParaView is Debian's own, unchanged: nmm's files are well-formed XML with their data inline
# (base64 in each DataArray), which its VTK 9.1 readers parse with Debian 12's current
# libexpat. (Files with an AppendedData element, raw as nmm wrote them before 2026-12-01 or
# base64, fail there since libexpat's security update for CVE-2023-52425: "Error parsing XML
# ... not well-formed (invalid token)".)
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
root=${NMM_RENDER_ROOT:-$repo/build/paraview-root}
root=$(realpath -m -- "$root")
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
# pvbatch, an X server for it, and Mesa's software OpenGL (llvmpipe) that draws into it.
packages=(paraview python3-paraview xvfb xauth libgl1-mesa-dri fonts-dejavu-core)

die() { echo "render_root.sh: $*" >&2; exit 1; }
note() { echo "render_root.sh: $*" >&2; }

case ${1:-} in
  -h | --help) sed -n '3,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
  "") die "no arguments; usage: $0 INPUT OUTPUT.png [render.py options] (or --help)" ;;
esac
[[ $EUID -eq 0 ]] || die "must run as root (debootstrap, mount and chroot need it): sudo $0 $*"

# Start again in a mount namespace of our own (unshare execs: the process id stays).
if [[ ${NMM_RENDER_NAMESPACE:-} != "$$" ]]; then
  NMM_RENDER_NAMESPACE=$$ exec unshare --mount --propagation private -- "$BASH" "$0" "$@"
fi

mkdir -p "$(dirname "$root")"
exec 9< "$(dirname "$root")"
flock 9  # one render (or setup) at a time

mounted=()   # mount points to undo, in order of mounting
cleanup() {  # the namespace drops the mounts anyway; this also removes the mount points
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount -R "${mounted[i]}" 2>/dev/null || umount -R -l "${mounted[i]}" 2>/dev/null ||
      note "could not unmount ${mounted[i]}"
  done
  mounted=()
  # rmdir, never rm -r: a mount that did not come off must not lose its files.
  if [[ -n ${run_dir:-} ]]; then rmdir "$run_dir"/* "$run_dir" 2>/dev/null || true; fi
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

bind() {  # bind SOURCE TARGET: bind-mount a host directory into the root
  mkdir -p "$2"
  mount --bind "$1" "$2" || die "cannot bind-mount $1 on $2"
  mounted+=("$2")
}

enter() {  # enter ROOT: mount /proc, /sys, /dev and a fresh /tmp in ROOT (for chroot)
  mount -t proc proc "$1/proc" || die "cannot mount /proc in $1"
  mounted+=("$1/proc")
  mount -t sysfs sysfs "$1/sys" || die "cannot mount /sys in $1"
  mounted+=("$1/sys")
  mount --rbind /dev "$1/dev" || die "cannot bind-mount /dev in $1"
  mounted+=("$1/dev")
  mount -t tmpfs -o mode=1777 tmpfs "$1/tmp" || die "cannot mount a tmpfs on $1/tmp"
  mounted+=("$1/tmp")
}

mounts_under() { awk -v d="$1" '$5 == d || index($5, d "/") == 1' /proc/self/mountinfo; }

setup() {
  local stage=$root.partial start=$SECONDS
  if [[ -e $stage ]]; then
    # Mounts of this script cannot outlive it, but make sure: rm -r would go through them.
    [[ -z $(mounts_under "$stage") ]] || die "something is mounted under $stage; unmount it first"
    note "removing $stage, left by an unfinished setup"
    rm -rf --one-file-system "$stage"
  fi
  if ! command -v debootstrap > /dev/null; then
    note "installing debootstrap on the host"
    apt-get install -y debootstrap > /dev/null ||
      { apt-get update > /dev/null && apt-get install -y debootstrap > /dev/null; } ||
      die "cannot install debootstrap (apt-get install debootstrap failed)"
  fi
  note "creating a Debian 12 root in $root (once; a few minutes)"
  debootstrap --variant=minbase bookworm "$stage" "$mirror" > "$root.debootstrap.log" 2>&1 ||
    die "debootstrap failed; see $root.debootstrap.log (the mirror $mirror reachable?)"
  cat > "$stage/etc/apt/sources.list" << EOF
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb http://deb.debian.org/debian-security bookworm-security main
EOF
  printf '#!/bin/sh\nexit 101\n' > "$stage/usr/sbin/policy-rc.d"  # start no services
  chmod +x "$stage/usr/sbin/policy-rc.d"
  # Start from the host's downloaded packages: apt uses those whose checksum matches.
  cp -l /var/cache/apt/archives/*.deb "$stage/var/cache/apt/archives/" 2>/dev/null || true
  enter "$stage"
  note "installing ${packages[*]}"
  {
    chroot "$stage" apt-get update &&
      chroot "$stage" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y --no-install-recommends "${packages[@]}" &&
      chroot "$stage" apt-get clean
  } > "$root.apt.log" 2>&1 || die "installing ParaView in the root failed; see $root.apt.log"
  cleanup
  mv "$stage" "$root"
  note "root ready in $((SECONDS - start)) s, $(du -sh --one-file-system "$root" | cut -f1)"
}

inside=""  # set by translate: the path of $1 seen from inside the root
run_dir=""
declare -A dirs=()  # host directory -> its mount point inside the root
translate() {
  local path dir
  path=$(realpath -m -- "$1")
  case $path in
    *.png | *.PNG) mkdir -p "$(dirname "$path")" ;;
    *) [[ -f $path ]] || die "no such file: $1" ;;
  esac
  if [[ $path == "$repo"/* ]]; then
    inside=/repo${path#"$repo"}
    return
  fi
  dir=$(dirname "$path")
  if [[ -z ${dirs[$dir]:-} ]]; then
    dirs[$dir]=/mnt/nmm-render.$$/${#dirs[@]}
    bind "$dir" "$root${dirs[$dir]}"
  fi
  inside=${dirs[$dir]}/$(basename "$path")
}

free_display() {  # an X display number that no X server uses, on the host or in the root
  local n
  for ((n = 99; n < 200; n++)); do
    # Xvfb also listens on the abstract socket @/tmp/.X11-unix/Xn, shared with the host.
    [[ -e /tmp/.X$n-lock ]] || grep -q "/tmp/.X11-unix/X$n\$" /proc/net/unix || {
      echo "$n"
      return
    }
  done
  die "no free X display number in 99-199"
}

[[ -e $root ]] || setup
[[ -x $root/usr/bin/pvbatch ]] ||
  die "$root is not a root made by this script (no pvbatch); remove it"
[[ ${1:-} == --setup ]] && exit 0

run_dir=$root/mnt/nmm-render.$$
mkdir -p "$run_dir"
bind "$repo" "$root/repo"
args=()
for arg in "$@"; do
  case $arg in
    --*=*.pvd | --*=*.vtu | --*=*.vtp | --*=*.png)
      translate "${arg#*=}"; args+=("${arg%%=*}=$inside") ;;
    -*) args+=("$arg") ;;
    *.pvd | *.vtu | *.vtp | *.png | *.PNG) translate "$arg"; args+=("$inside") ;;
    *) args+=("$arg") ;;
  esac
done
# render.py's messages name the paths it was given: show the host's paths instead.
host_paths=(-e "s#/repo/#$repo/#g")
for dir in "${!dirs[@]}"; do host_paths+=(-e "s#${dirs[$dir]}/#$dir/#g"); done
enter "$root"
# pvbatch under a virtual X server. -noreset: without it Xvfb resets when pvbatch closes its
# first connection (the OpenGL check), and pvbatch's next one can fail: "bad X server
# connection ... Aborting".
status=0
chroot "$root" env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 \
  xvfb-run -n "$(free_display)" -e /dev/stderr -s "-screen 0 1920x1200x24 -noreset" \
  pvbatch /repo/scripts/render.py "${args[@]}" 2>&1 |
  sed "${host_paths[@]}" || status=$?
if [[ -n ${SUDO_UID:-} ]]; then  # give the pictures to whoever ran sudo
  for arg in "$@"; do
    case $arg in
      *.png | *.PNG) chown "$SUDO_UID:${SUDO_GID:-$SUDO_UID}" -- "${arg#--*=}" 2>/dev/null || true ;;
    esac
  done
fi
exit "$status"
