#!/bin/bash
# Key-to-frame latency of the lab's two-body scene, measured in tmux at 80×24: send a key,
# poll the pane until it has changed (the key's frame says `solving` until its answer, a
# solve or a refusal, is drawn) and nothing is being solved. A variant of benches/lab_latency.sh (the one-body scene's level step).
# usage: benches/lab_bodies_latency.sh SCENARIO LEVEL WAIT [REPEAT]
#   opens `riplab SCENARIO` (a two-body scenario), steps with → or ← to LEVEL, then times
#   REPEAT (default 3) presses each of `n` (the interface's discretisation), `k` (the element
#   ratio) and `→` (a level finer, each followed by `←` back, timed too), each key sent WAIT s
#   after the frame before it was shown (0: at once, before an idle prefetch has run; 5: after
#   it). RIPLAB: the binary (default target/release/riplab).
scenario=$1; level=$2; wait=$3; repeat=${4:-3}
pane() { tmux capture-pane -p -t blat; }
settled() { ! tmux capture-pane -p -t blat | grep -q 'solving'; }
# Send key $1 and print the ms until the frame shows its settings solved.
timed() {
  local before t0 t1
  before=$(pane)
  t0=$(date +%s%N)
  tmux send-keys -t blat "$1"
  until [ "$(pane)" != "$before" ] && settled; do sleep 0.002; done
  t1=$(date +%s%N)
  echo $(( (t1-t0)/1000000 ))
}
shown_level() { tmux capture-pane -p -t blat | sed -n 1p | grep -o 'level [0-9]*' | cut -d' ' -f2; }
tmux kill-session -t blat 2>/dev/null
tmux new -d -s blat -x 80 -y 24 "NO_COLOR=1 ${RIPLAB:-target/release/riplab} $scenario"
until [ -n "$(shown_level)" ] && settled && tmux capture-pane -p -t blat | sed -n 2p | grep -q ratio; do sleep 0.05; done
while [ "$(shown_level)" -lt "$level" ]; do timed Right > /dev/null; done
while [ "$(shown_level)" -gt "$level" ]; do timed Left > /dev/null; done
for key in n k; do
  out=""
  for i in $(seq "$repeat"); do sleep "$wait"; out="$out $(timed $key)"; done
  echo "$(basename "$scenario") level $level, $key after ${wait}s idle:$out ms"
done
up=""; back=""
for i in $(seq "$repeat"); do
  sleep "$wait"; up="$up $(timed Right)"
  sleep "$wait"; back="$back $(timed Left)"
done
echo "$(basename "$scenario") level $level, → after ${wait}s idle:$up ms; ← back:$back ms"
tmux capture-pane -p -t blat | sed -n '1,2p;23p'
tmux kill-session -t blat
