#!/usr/bin/env bash
# Headless demo of the `unidist` command on a few primitive pairs: human-readable and JSON answers, a model
# description, and what bad input looks like. Usage: demos/main_demo.sh [path/to/unidist]
# (A Bullet scene replaces this demo in a later issue.)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
UNIDIST="${1:-$ROOT/build/demos/unidist}"
if [[ ! -x "$UNIDIST" ]]; then
  echo "main_demo: $UNIDIST not found; build first (demos/run.sh does)" >&2
  exit 1
fi

show() {  # show "title" args...
  local title="$1"
  shift
  printf '\n=== %s\n$ unidist' "$title"
  local a
  for a in "$@"; do
    if [[ "$a" == *" "* ]]; then printf ' "%s"' "$a"; else printf ' %s' "$a"; fi
  done
  printf '\n'
  "$UNIDIST" "$@"
}

"$UNIDIST" --version
show "sphere and box, apart (distance 1, normal -x)" \
  distance sphere:r=1 box:hx=1,hy=1,hz=1 --pose-a "3 0 0 1 0 0 0"
show "the same pair as JSON" \
  distance sphere:r=1 box:hx=1,hy=1,hz=1 --pose-a "3 0 0 1 0 0 0" --json
show "a unit ball inside a 2x2x2 box: -(minimum translation to separate) = -2" \
  distance sphere:r=1 box:hx=1,hy=1,hz=1 --json
show "a box and a smaller box turned 45 degrees about z: its edge is 0.1929 from A's +x face" \
  distance box:hx=1,hy=1,hz=1 box:hx=0.5,hy=0.5,hz=0.5 --pose-b "1.9 0.2 0.1 0.9238795325112867 0 0 0.3826834323650898"
show "a capsule and a tilted cylinder, with a requested tolerance" \
  distance capsule:r=0.25,h=1 cylinder:r=0.5,h=0.75 \
  --pose-a "0 0 0 1 0 0 0" --pose-b "1.5 0 0.5 0.9659258262890683 0.2588190451025207 0 0" --tol 1e-12 --json
show "a cone standing 0.25 above the half-space z <= 0" \
  distance plane:nx=0,ny=0,nz=1,d=0 cone:r=0.5,h=0.5 --pose-b "0.3 -0.2 0.75 1 0 0 0"
show "a ball in the hole of a torus: 0.25 from the tube" \
  distance torus:R=1,r=0.25 sphere:r=0.5 --json
show "two spheres 3.5 apart, grown by --inflate-a 0.25 and --inflate-b 0.1: 3.15" \
  distance sphere:r=1 sphere:r=0.5 --pose-b "3 4 0 1 0 0 0" --inflate-a 0.25 --inflate-b 0.1 --json
show "what a model is" info torus:R=1,r=0.25
show "the same as JSON" info box:hx=1,hy=2,hz=3 --json

printf '\n=== bad input: exit code 2, one line on stderr, nothing on stdout\n'
for args in "distance pyramid:r=1 sphere:r=1" "distance sphere:r=-1 sphere:r=1" \
            "distance sphere:r=1 sphere:r=1 --tol -1"; do
  printf '$ unidist %s\n' "$args"
  rc=0
  # shellcheck disable=SC2086  # word splitting wanted: args are plain words
  "$UNIDIST" $args 2>&1 || rc=$?
  printf '(exit code %d)\n' "$rc"
done
