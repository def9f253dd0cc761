#!/usr/bin/env bash
# Install missing Debian packages (as root), build Release in build/, run the main demo (demos/main_demo.sh:
# the mixed scene in Bullet and ODE).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/.ci/setup.sh"
exec "$ROOT/demos/main_demo.sh" "${UNIDIST_BUILD_DIR:-$ROOT/build}/demos/unidist"
