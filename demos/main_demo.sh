#!/usr/bin/env bash
# The main headless demo: the mixed scene demos/scenes/mixed.json (a NURBS ball, the shared FCL "piano" mesh,
# a point-cloud blob, a torus and a box primitive, dropped on a floor and on each other, in millimetres) run with
# the unidist plugin in Bullet and in ODE. Prints each engine's summary (final poses, contacts, deepest
# penetration, steps per second), the two side by side, and writes a trajectory CSV and PNG frames (shaded
# bodies, contact points and normals; docs/pictures.md) per engine.
# Then two single queries. Usage: demos/main_demo.sh [path/to/unidist] [output directory]
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
UNIDIST="${1:-$ROOT/build/demos/unidist}"
OUT="${2:-$(dirname "$(dirname "$UNIDIST")")/demo}"
SCENE="$ROOT/demos/scenes/mixed.json"
if [[ ! -x "$UNIDIST" ]]; then
  echo "main_demo: $UNIDIST not found; build first (demos/run.sh does)" >&2
  exit 1
fi
mkdir -p "$OUT"
"$UNIDIST" --version

# Frames need the renderer (OSMesa, qhull and libpng at build time); a build without it still runs the demo.
RENDER=()
if "$UNIDIST" sim "$SCENE" --steps 0 --render "$OUT/frames_probe" --render-size 8x8 >/dev/null 2>&1; then
  RENDER=(--render-size 480x360 --render-every 40)  # 31 frames of the 1200 steps
else
  echo "(no frames: this unidist was built without the renderer; install libosmesa6-dev libqhull-dev libpng-dev)"
fi
rm -rf "$OUT/frames_probe"

for engine in bullet ode; do
  printf '\n=== %s: unidist sim demos/scenes/mixed.json --engine %s\n' "$engine" "$engine"
  if ((${#RENDER[@]})); then
    rm -rf "$OUT/frames_$engine"
    "$UNIDIST" sim "$SCENE" --engine "$engine" --trajectory "$OUT/trajectory_$engine.csv" \
      --render "$OUT/frames_$engine" "${RENDER[@]}"
  else
    "$UNIDIST" sim "$SCENE" --engine "$engine" --trajectory "$OUT/trajectory_$engine.csv"
  fi
  "$UNIDIST" sim "$SCENE" --engine "$engine" --json > "$OUT/final_$engine.json"
  echo "(trajectory: $OUT/trajectory_$engine.csv)"
done

printf '\n=== the two engines side by side (final centre heights in mm)\n'
python3 - "$OUT/final_bullet.json" "$OUT/final_ode.json" <<'PY'
import json, sys
b, o = (json.load(open(p)) for p in sys.argv[1:3])
print(f"{'body':12} {'bullet z':>10} {'ode z':>10}")
for x, y in zip(b["bodies"], o["bodies"]):
    print(f"{x['name']:12} {x['pose'][2]:10.2f} {y['pose'][2]:10.2f}")
for key in ("contacts", "max_penetration", "steps_per_second"):
    print(f"{key:17} {b[key]:10.4g} {o[key]:10.4g}")
PY

show() {  # show "title" args...
  local title="$1"
  shift
  printf '\n=== %s\n$ unidist %s\n' "$title" "$*"
  "$UNIDIST" "$@"
}
show "a box and the NURBS ball of the scene: certified distance with bounds" \
  distance box:hx=100,hy=100,hz=100 "$ROOT/demos/scenes/ball_r150.unurbs.json" --pose-b "30 -20 400 1 0 0 0"
show "the contact points of a box resting on a box" \
  contacts box:hx=1,hy=1,hz=1 box:hx=0.5,hy=0.5,hz=0.5 --pose-b "0.2 0 1.5 1 0 0 0"
