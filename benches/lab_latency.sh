#!/bin/bash
# Key-to-frame latency of a level step in the lab, measured in tmux: send the key, poll the
# pane until the header shows the new level and the status line a converged solve.
# usage: benches/lab_latency.sh FROM TO WAIT [back|after|stress]
#   steps up from level 1 to FROM, waits WAIT s idle, steps to TO; with `back`, steps back to
#   FROM as soon as the status line shows TO being built, and times that step instead; with
#   `after`, steps back as soon as TO is shown solved (its displacement still under way); with
#   `stress`, opens the stress scene at FROM and steps to TO while the stresses are computed;
#   with `burst`, presses `+` (TO − FROM + 1 times, 30 ms apart) at FROM instead of stepping and
#   times the last key to the deformed view (its displacement computed).
#   METHOD=alm|nitsche|exact: the lab's method (pressing `m` until the header names it) first.
from=$1; to=$2; wait=$3; back=${4:-}
# Wait until the pane shows level $1 solved.
shown() {
  until tmux capture-pane -p -t lat | grep -q "level $1 " && tmux capture-pane -p -t lat | grep -q 'converged'; do sleep 0.002; done
}
# Send key $1 and print the ms until level $2 is shown solved.
timed() {
  local t0 t1
  t0=$(date +%s%N)
  tmux send-keys -t lat "$1"
  shown "$2"
  t1=$(date +%s%N)
  echo $(( (t1-t0)/1000000 ))
}
tmux kill-session -t lat 2>/dev/null
tmux new -d -s lat -x 100 -y 30 "NO_COLOR=1 ${RIPLAB:-target/release/riplab}"
sleep 2
if [ -n "${METHOD:-}" ]; then
  until tmux capture-pane -p -t lat | sed -n 2p | grep -q "$METHOD"; do tmux send-keys -t lat m; sleep 0.3; done
fi
cur=$(tmux capture-pane -p -t lat | grep -o 'level [0-9]' | head -1 | cut -d' ' -f2)
while [ "$cur" -lt "$from" ]; do tmux send-keys -t lat ']'; cur=$((cur+1)); 
  until tmux capture-pane -p -t lat | grep -q "level $cur .*" && tmux capture-pane -p -t lat | grep -q 'converged'; do sleep 0.05; done; done
sleep "$wait"
key=']'; [ "$to" -lt "$from" ] && key='['
rkey='['; [ "$key" = '[' ] && rkey=']'
if [ "$back" = burst ]; then
  for i in $(seq $((to - from + 1))); do tmux send-keys -t lat '+'; sleep 0.03; done
  t0=$(date +%s%N)
  until ! tmux capture-pane -p -t lat | grep -q "computing the displacement" && tmux capture-pane -p -t lat | grep -q 'converged'; do sleep 0.005; done
  t1=$(date +%s%N)
  echo "level $from, $((to - from + 1)) × + 30 ms apart: last key + 30 ms to the deformed view $(( (t1-t0)/1000000 )) ms"
elif [ "$back" = stress ]; then
  for i in 1 2 3 4; do tmux send-keys -t lat Tab; done
  until tmux capture-pane -p -t lat | grep -q "computing the stresses"; do sleep 0.002; done
  echo "level $from -> $to while the stresses of $from are computed: $(timed "$key" "$to") ms"
elif [ "$back" = after ]; then
  tmux send-keys -t lat "$key"
  shown "$to"
  echo "level $from -> $to -> $from, back as soon as $to is shown: $(timed "$rkey" "$from") ms"
elif [ "$back" = back ]; then
  tmux send-keys -t lat "$key"
  until tmux capture-pane -p -t lat | grep -q "building level $to"; do sleep 0.002; done
  echo "level $from -> $to -> $from, back while $to is built: $(timed "$rkey" "$from") ms"
else
  echo "level $from -> $to after ${wait}s idle: $(timed "$key" "$to") ms"
fi
tmux capture-pane -p -t lat | sed -n "2p;$p"; sleep 1; tmux capture-pane -p -t lat | tail -3
tmux kill-session -t lat
