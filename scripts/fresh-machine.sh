#!/usr/bin/env bash
# fresh-machine.sh: run a command the way a newcomer's machine would, in a new minimal Debian 12
# (bookworm) root that holds only the committed tree. Whatever the command needs must be
# installed by the project's own scripts: nothing installed by hand on this machine is there.
#
#   bash scripts/fresh-machine.sh [--keep] [--] COMMAND...   run COMMAND in a fresh root
#   bash scripts/fresh-machine.sh --check                    can a fresh root be made here?
#
# How: a minimal root is made once with `debootstrap --variant=minbase` and cached as a tarball;
# each run unpacks it into a new folder, puts `git archive HEAD` in /root/project, mounts /proc,
# /dev and /sys, and runs COMMAND there with chroot (as root, with CI=true). The root is removed
# afterwards (--keep leaves it and prints its path). Downloaded .deb files are kept in the cache
# between runs so apt does not fetch them twice; they are still installed from nothing each run.
#
# Exit status: COMMAND's own; 125 when no fresh root can be made here (not root, no Debian
# mirror, debootstrap missing or failing, no git checkout) -- one line on stderr says why, and
# .ci/run then runs the command directly; 2 for a usage error.
#
# Environment:
#   ACETATE_FRESH_CACHE   cache folder (default /var/cache/acetate-fresh-machine)
#   ACETATE_FRESH_MIRROR  Debian mirror (default: the first one in this machine's apt sources)
#   ACETATE_FRESH_SUITE   Debian suite (default bookworm)
set -euo pipefail

unavailable() { echo "fresh-machine: $*" >&2; exit 125; }
usage() { echo "fresh-machine: $*; usage: fresh-machine.sh [--keep] [--check] [--] COMMAND..." >&2; exit 2; }

keep=0
check_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) keep=1; shift ;;
    --check) check_only=1; shift ;;
    --) shift; break ;;
    -*) usage "unknown option $1" ;;
    *) break ;;
  esac
done
[ "$check_only" -eq 1 ] || [ $# -gt 0 ] || usage "no command given"

cache=${ACETATE_FRESH_CACHE:-/var/cache/acetate-fresh-machine}
suite=${ACETATE_FRESH_SUITE:-bookworm}
tarball=$cache/$suite-minbase.tar

[ "$(id -u)" -eq 0 ] || unavailable "must run as root (it uses debootstrap, mount and chroot)"
top=$(git rev-parse --show-toplevel 2>/dev/null) || unavailable "run it inside a git checkout of the project"
git -C "$top" rev-parse --verify -q HEAD >/dev/null || unavailable "$top has no commit to archive"

mirror=${ACETATE_FRESH_MIRROR:-}
if [ -z "$mirror" ]; then
  mirror=$(grep -hoE '^(URIs:|deb) +[^ ]+' /etc/apt/sources.list /etc/apt/sources.list.d/*.sources \
    /etc/apt/sources.list.d/*.list 2>/dev/null | grep -v -e security -e '\[' | awk '{print $2}' \
    | grep -m1 -i debian || true)
fi

# Makes the cached minimal root, once.
make_base_root() {
  [ -n "$mirror" ] || unavailable "found no Debian mirror in this machine's apt sources (set ACETATE_FRESH_MIRROR)"
  if ! command -v debootstrap >/dev/null; then
    echo "fresh-machine: installing debootstrap"
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap; } \
      >/dev/null 2>&1 || unavailable "debootstrap is not installed and apt-get could not install it"
  fi
  mkdir -p "$cache" || unavailable "cannot create the cache folder $cache"
  local staging
  staging=$(mktemp -d "$cache/staging.XXXXXX")
  echo "fresh-machine: making a minimal $suite root from $mirror (once; cached in $tarball)"
  if ! debootstrap --variant=minbase "$suite" "$staging" "$mirror" >"$cache/debootstrap.log" 2>&1; then
    rm -rf "$staging"
    unavailable "debootstrap of $suite from $mirror failed: $(tail -n 1 "$cache/debootstrap.log")"
  fi
  chmod 755 "$staging"  # the root's own mode is stored in the tarball ("./")
  tar -C "$staging" -cf "$tarball.tmp" . && mv "$tarball.tmp" "$tarball"
  rm -rf "$staging"
}

if [ "$check_only" -eq 1 ]; then
  [ -s "$tarball" ] && { echo "fresh-machine: ready (cached root $tarball)"; exit 0; }
  [ -n "$mirror" ] || unavailable "found no Debian mirror in this machine's apt sources (set ACETATE_FRESH_MIRROR)"
  command -v debootstrap >/dev/null || command -v apt-get >/dev/null \
    || unavailable "neither debootstrap nor apt-get to install it is here"
  echo "fresh-machine: ready (will debootstrap $suite from $mirror)"
  exit 0
fi

[ -s "$tarball" ] || make_base_root

root=$(mktemp -d /tmp/acetate-fresh.XXXXXX)
mounts=(proc sys dev/pts dev var/cache/apt/archives)
cleanup() {
  local m
  for m in "${mounts[@]}"; do mountpoint -q "$root/$m" 2>/dev/null && umount -l "$root/$m"; done
  if [ "$keep" -eq 1 ]; then echo "fresh-machine: kept $root"; else rm -rf --one-file-system "$root"; fi
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

tar -C "$root" -xf "$tarball"
# It becomes "/", which every user must be able to enter (a package's postinst runs commands as
# its own user: munge's does). Set after unpacking: the tarball's "./" carries the 0700 of the
# staging folder mktemp made, and tar gives it to the root.
chmod 755 "$root"
cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
mkdir -p "$root/root/project" "$root/var/cache/apt/archives" "$cache/apt-archives"
git -C "$top" archive HEAD | tar -x -C "$root/root/project"
mount -t proc proc "$root/proc"
# Recursive, as on a machine: what is mounted under /sys (the cgroup tree slurmd needs) too.
# The lazy unmount in cleanup() detaches the whole tree.
mount --rbind /sys "$root/sys"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
mount --bind "$cache/apt-archives" "$root/var/cache/apt/archives"

echo "fresh-machine: running '$*' in a fresh $suite root ($(git -C "$top" rev-parse --short HEAD))"
status=0
chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  TERM=dumb CI=true LANG=C.UTF-8 /bin/bash -c 'cd /root/project && "$@"' fresh-machine "$@" || status=$?
echo "fresh-machine: '$*' exited $status"
exit "$status"
