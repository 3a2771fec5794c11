#!/usr/bin/env bash
# Sets up everything and runs the main job: `tessera demo`, writing out/report.html.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
build/bin/tessera demo -o out
echo "Open out/report.html in a browser."
