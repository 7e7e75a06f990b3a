#!/usr/bin/env bash
# Per-level cost of a fresh solve of the default scenario (the table in BENCHMARKS.md):
# dofs, Newton iterations, assembly, symbolic and numeric factorisation, total, peak memory.
# Usage: bash benches/levels.sh [max_level]   (after `cargo build --release`)
set -euo pipefail
cd "$(dirname "$0")/.."
max=${1:-7}
bin=target/release/riplab
printf "| scheme | level | dofs | Newton | assembly ms | symbolic ms | factorisations ms | total ms | peak MiB |\n|---|---|---|---|---|---|---|---|---|\n"
for scheme in M1 M3; do
  for level in $(seq 0 "$max"); do
    out=$( { /usr/bin/time -f "%M" "$bin" solve --scheme "$scheme" --level "$level" --format json > /tmp/riplab-bench.json; } 2>&1 )
    python3 - "$scheme" "$level" "$out" <<'PY'
import json, sys
scheme, level, peak_kib = sys.argv[1], sys.argv[2], int(sys.argv[3].split()[-1])
r = json.load(open('/tmp/riplab-bench.json'))
t = r['timing_ms']
print(f"| {scheme} | {level} | {r['n_dofs']} | {r['newton_iterations']} | {t['assembly']:.1f} | {t['symbolic']:.1f} | {t['factorization']:.1f} | {t['total']:.1f} | {peak_kib/1024:.0f} |")
PY
  done
done
