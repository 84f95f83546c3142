#!/usr/bin/env bash
# Tests scripts/fresh-machine.sh without the network and without debootstrapping Debian:
#   1. not root: exit 125 and one line saying so;
#   2. no mirror reachable: exit 125 and one line naming the mirror;
#   3. with a cached root (a tiny one made here from this machine's bash): the command runs in
#      it, sees only the committed files and CI=true and a "/" every user may enter, its exit
#      status comes back unchanged, and nothing stays mounted or on disk.
# Cases 2 and 3 need root (mount, chroot); when not root they are reported as not run and the
# test fails unless ACETATE_ALLOW_NONROOT_SKIP=1, so CI (root) never passes them silently.
#
#   bash tests/hygiene/fresh_machine_test.sh /path/to/scripts/fresh-machine.sh
set -euo pipefail
script=$(realpath "$1")
work=$(mktemp -d /tmp/fresh-machine-test.XXXXXX)
chmod 755 "$work"
trap 'rm -rf --one-file-system "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

# Runs the script, capturing status, stdout and stderr.
run() {
  status=0
  "$@" >"$work/out" 2>"$work/err" || status=$?
}
one_line_error() {  # $1: what the line must contain
  local lines
  lines=$(wc -l <"$work/err")
  [ "$lines" -eq 1 ] && grep -q -- "$1" "$work/err"
}

# A project checkout: one committed file, one untracked file.
repo=$work/repo
mkdir -p "$repo"
git -C "$repo" init -q
echo committed >"$repo/committed.txt"
git -C "$repo" add committed.txt
git -C "$repo" -c user.name=test -c user.email=test@example.invalid commit -q -m init
echo untracked >"$repo/untracked.txt"
cp "$script" "$work/fresh-machine.sh"
chmod 755 "$work/fresh-machine.sh"

# ---- 1. Not root ----
as_nobody=(setpriv --reuid=65534 --regid=65534 --clear-groups)
if [ "$(id -u)" -ne 0 ]; then
  as_nobody=()
elif ! "${as_nobody[@]}" bash -c true 2>/dev/null; then
  # Some roots (a chroot whose / is mode 0700) let no other user load a program at all.
  as_nobody=(none)
fi
if [ "${as_nobody[0]:-}" = none ]; then
  echo "not root: not run: no unprivileged process can start here ($(stat -c '/ is mode %a' /))"
else
  run "${as_nobody[@]}" bash "$work/fresh-machine.sh" true
  if [ "$status" -eq 125 ] && one_line_error "must run as root"; then
    pass "not root: exit 125, one line"
  else
    fail "not root: exit $status, stderr: $(cat "$work/err")"
  fi
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "cases 2 and 3 need root: not run"
  [ "${ACETATE_ALLOW_NONROOT_SKIP:-0}" = 1 ] && exit $((failures > 0))
  exit 1
fi

# ---- 2. No mirror reachable (port 9 on loopback: connection refused at once) ----
status=0
(cd "$repo" && ACETATE_FRESH_CACHE=$work/empty-cache ACETATE_FRESH_MIRROR=http://127.0.0.1:9/debian \
  bash "$work/fresh-machine.sh" true >"$work/out" 2>"$work/err") || status=$?
if [ "$status" -eq 125 ] && one_line_error "http://127.0.0.1:9/debian"; then
  pass "no mirror: exit 125, one line naming the mirror"
else
  fail "no mirror: exit $status, stderr: $(cat "$work/err")"
fi
if ls "$work/empty-cache"/staging.* >/dev/null 2>&1; then
  fail "no mirror: a staging folder was left in the cache"
fi

# ---- 3. A cached root: status passed through, committed files only ----
mini=$work/mini
mkdir -p "$mini"/{proc,sys,dev,etc,tmp}
for binary in /bin/bash /usr/bin/env /usr/bin/stat; do
  cp --parents -L "$binary" "$mini"
  ldd "$binary" | grep -oE '/[^ ]+' | while read -r lib; do cp --parents -L "$lib" "$mini"; done
done
mkdir -p "$work/cache"
# As debootstrap's staging folder from mktemp is: the tarball's "./" says 0700, which must not
# become the fresh root's "/" (no user but root could enter it; munge's postinst failed so).
chmod 700 "$mini"
tar -C "$mini" -cf "$work/cache/bookworm-minbase.tar" .

before=$(ls -d /tmp/acetate-fresh.* 2>/dev/null | sort || true)
status=0
(cd "$repo" && ACETATE_FRESH_CACHE=$work/cache bash "$work/fresh-machine.sh" -- bash -c \
  'test -f committed.txt && test ! -e untracked.txt && test "$CI" = true && test "$PWD" = /root/project && test "$(stat -c %a /)" = 755 && exit 7' \
  >"$work/out" 2>"$work/err") || status=$?
if [ "$status" -eq 7 ]; then
  pass "cached root: the command's exit status 7 came back; it saw only committed files and CI=true"
else
  fail "cached root: expected exit 7, got $status; out: $(cat "$work/out") err: $(cat "$work/err")"
fi
status=0
(cd "$repo" && ACETATE_FRESH_CACHE=$work/cache bash "$work/fresh-machine.sh" true \
  >"$work/out" 2>"$work/err") || status=$?
[ "$status" -eq 0 ] && pass "cached root: a passing command exits 0" \
  || fail "cached root: 'true' exited $status: $(cat "$work/err")"
if grep -q acetate-fresh /proc/mounts; then
  fail "a fresh root is still mounted: $(grep acetate-fresh /proc/mounts)"
else
  pass "nothing left mounted"
fi
after=$(ls -d /tmp/acetate-fresh.* 2>/dev/null | sort || true)
[ "$before" = "$after" ] && pass "no root left in /tmp" || fail "roots left in /tmp: $after"

[ "$failures" -eq 0 ] && echo "fresh_machine_test: passed" || echo "fresh_machine_test: $failures failed"
exit $((failures > 0))
