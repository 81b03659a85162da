#!/usr/bin/env bash
# setup.apt_untouched: scripts/setup.sh finds the LAMMPS source package through
# a private apt configuration and leaves the machine's apt configuration and
# package lists as they were.
#   1. fingerprints /etc/apt (every file's path and content) and
#      /var/lib/apt/lists (names, sizes, modification times);
#   2. runs `setup.sh --check-source` with a fresh, empty cache: the private
#      deb-src list is derived from the system's deb entries, updated into the
#      cache and searched for the installed liblammps-dev's source version;
#   3. fingerprints again: both must be unchanged, and no apt source file may
#      carry the marker of the entry earlier versions of setup.sh wrote.
# Exit 77 (ctest: skipped) when the Debian archive cannot be reached.
#   check_apt_untouched.sh REPO_ROOT
set -uo pipefail
root=$1
fp() {
  { find /etc/apt -type f -print0 2>/dev/null | sort -z | xargs -0 sha256sum 2>/dev/null
    find /var/lib/apt/lists -maxdepth 1 -type f -printf '%f %s %T@\n' 2>/dev/null | sort; } | sha256sum
}
before=$(fp)
cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT
out=$(TLSPH_CACHE="$cache" bash "$root/scripts/setup.sh" --check-source 2>&1)
rc=$?
echo "$out" | tail -5
after=$(fp)
if [ $rc -ne 0 ]; then
  if grep -qiE "Could not resolve|Failed to fetch|Temporary failure|Unable to connect" <<<"$out"; then
    echo "SKIPPED: the Debian archive cannot be reached"
    [ "$before" = "$after" ] || { echo "FAILED: /etc/apt or /var/lib/apt/lists changed"; exit 1; }
    exit 77
  fi
  echo "FAILED: setup.sh --check-source exited with $rc"
  exit 1
fi
ok=1
[ "$before" = "$after" ] || { echo "FAILED: /etc/apt or /var/lib/apt/lists changed"; ok=0; }
if grep -rqs '^# added by tlsph' /etc/apt; then
  echo "FAILED: an apt source entry written by tlsph is in /etc/apt"; ok=0
fi
[ -s "$cache/apt/sources.list" ] || ls "$cache"/apt/sources.list.d/*.sources >/dev/null 2>&1 ||
  { echo "FAILED: no private source list in the cache"; ok=0; }
[ $ok = 1 ] && echo "PASSED: source found through $cache/apt; /etc/apt and /var/lib/apt/lists unchanged"
[ $ok = 1 ]
