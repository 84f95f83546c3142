#!/usr/bin/env bash
# Builds the image of deploy/image/Containerfile with buildah, and checks it: the installed
# acetate-harness describes a shipped plugin inside it, on lavapipe with the validation layers.
#
#   deploy/image/build.sh [TAG]        (default localhost/acetate:latest)
#
# The base is debian:bookworm from a registry when one answers; otherwise the minimal Debian
# 12 root scripts/fresh-machine.sh makes with debootstrap, imported as localhost/acetate-base.
# Builds with --isolation chroot and the vfs storage driver, so it also runs inside a
# container or chroot without user namespaces or overlay mounts (as root). Exit status: 0 when
# built and checked, 1 when the build or the check failed, 125 when buildah is not installed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
tag=${1:-localhost/acetate:latest}
command -v buildah >/dev/null || { echo "build.sh: buildah is not installed (apt-get install buildah)" >&2; exit 125; }
b=(buildah --storage-driver vfs)

base=docker.io/library/debian:bookworm
if ! "${b[@]}" pull -q "$base" >/dev/null 2>&1; then
  tarball=${ACETATE_FRESH_CACHE:-/var/cache/acetate-fresh-machine}/bookworm-minbase.tar
  if [ ! -s "$tarball" ]; then
    echo "build.sh: no registry answers for $base; making a Debian 12 root with debootstrap"
    bash "$root/scripts/fresh-machine.sh" -- true
  fi
  echo "build.sh: no registry answers for $base; importing $tarball"
  base=localhost/acetate-base:bookworm
  "${b[@]}" rmi -f "$base" >/dev/null 2>&1 || true
  container=$("${b[@]}" from scratch)
  mount=$("${b[@]}" mount "$container")
  tar -C "$mount" -xf "$tarball"
  "${b[@]}" umount "$container" >/dev/null
  "${b[@]}" commit -q "$container" "$base" >/dev/null
  "${b[@]}" rm "$container" >/dev/null
fi

# Only what git tracks goes into the build (no build trees, no caches).
context=$(mktemp -d /tmp/acetate-image-XXXXXX)
trap 'rm -rf "$context"' EXIT
git -C "$root" archive HEAD | tar -C "$context" -xf -
echo "build.sh: building $tag from $base (the whole project: several minutes)"
"${b[@]}" bud --isolation chroot --network host --layers=false --build-arg "BASE=$base" \
  -f "$context/deploy/image/Containerfile" -t "$tag" "$context"

# The check: the installed harness lists a shipped plugin's cases inside the image.
container=$("${b[@]}" from "$tag")
trap '"${b[@]}" rm "$container" >/dev/null 2>&1 || true; rm -rf "$context"' EXIT
cases=$("${b[@]}" run --isolation chroot "$container" -- sh -c \
  'acetate-harness validate "$(ls /opt/acetate/lib*/acetate/plugins/lighting.so /opt/acetate/lib/*/acetate/plugins/lighting.so 2>/dev/null | head -n 1)" --strictness 1 --list-cases | wc -l')
[ "$cases" -gt 10 ] || { echo "build.sh: the installed harness listed $cases cases in the image" >&2; exit 1; }
"${b[@]}" run --isolation chroot "$container" -- acetate --help >/dev/null
echo "build.sh: $tag built; its acetate-harness plans $cases cases for lighting at strictness 1"
"${b[@]}" images "$tag"
