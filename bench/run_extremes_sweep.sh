#!/usr/bin/env bash
# The extremes sweep of the material point (issue #3): runs the full matrix and writes docs/extremes.md.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc)" --target driver > /dev/null
build/bin/driver -input input/point/extremes.yaml -output_dir out/sweep/extremes
python3 post/sweep_table.py out/sweep/extremes/sweep.csv --out docs/extremes.md > /dev/null
echo "written: docs/extremes.md"
