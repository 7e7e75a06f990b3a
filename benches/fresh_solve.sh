#!/bin/bash
# A fresh `riplab solve` of one level, after a chosen idle time: wall, CPU, peak memory, the
# fresh memory it faulted in (transparent huge pages, /proc/vmstat thp_fault_alloc) and the
# solve's own stage timings (BENCHMARKS.md, "Fresh memory").
#
# On a virtual machine whose balloon reports free pages to the host (virtio-balloon
# F_REPORTING, as on the machine of BENCHMARKS.md), memory a process freed more than ~2 s ago
# is returned to the host, and the next process to touch it waits for the host to fault it in
# again: a run after IDLE ≥ 5 s pays that ("cold"), a run right after another does not ("warm").
#
# usage: benches/fresh_solve.sh LEVEL IDLE RUNS [riplab solve options...]
#   e.g. benches/fresh_solve.sh 7 6 3      (three cold level-7 solves)
#        benches/fresh_solve.sh 8 0 2 --threads 1
set -euo pipefail
level=$1; idle=$2; runs=$3; shift 3
bin=${RIPLAB:-target/release/riplab}
out=$(mktemp); times=$(mktemp)
trap 'rm -f "$out" "$times"' EXIT
thp() { awk '/^thp_fault_alloc /{print $2}' /proc/vmstat; }
for _ in $(seq "$runs"); do
  sleep "$idle"
  before=$(thp)
  /usr/bin/time -f "%e %U %S %M" -o "$times" "$bin" solve --level "$level" --format json "$@" > "$out"
  after=$(thp)
  read -r wall user sys peak < "$times"
  stages=$(python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['timing_ms']; print(' '.join(f'{k} {v:.0f}' for k,v in t.items()))" "$out")
  echo "level $level, idle ${idle} s: wall ${wall} s, user ${user} s, sys ${sys} s, peak $((peak / 1024)) MiB, fresh $(( (after - before) * 2 )) MiB | ms: $stages"
done
