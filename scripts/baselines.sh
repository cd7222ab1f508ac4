#!/usr/bin/env bash
# The physics baselines a change meant to leave the numbers alone must keep, one line each:
# final-state md5s of the contact scenes (impulse and soft-step), the joint chains' CSV md5s
# and the cloth cases' bit checksums. Run it before and after a change and diff the output.
#
#   scripts/baselines.sh > before.txt   # ... change ...   scripts/baselines.sh | diff before.txt -
#
# Release build of the three examples; a few minutes on two cores. Not part of CI.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q --example contact_steps --example chain_steps --example cloth_steps
bin=target/release/examples

contact() { # SCENE STEPS RESPONSE: md5 of the final states (timings dropped)
  local sum
  sum=$(CONTACT_STEPS_STATES=1 "$bin/contact_steps" "$1" "$2" "$3" 2>/dev/null | grep -v µs | md5sum)
  echo "contact $3 $1 $2 ${sum:0:8}"
}
for run in "stack-10 2000" "pyramid-10 600" "dominoes 3000" "stack-1 20000" "dominoes16 1500" \
  "wall-ball 200" "bonded-wall-ball 100" "knife-wall-ball 100" "wall 600" "cradle 3000"; do
  contact $run impulse
done
for run in "stack-10 600" "pyramid-10 300" "dominoes 1000"; do
  contact $run soft-step
done

for chain in ball hinge landing; do # the CSV every 100 steps over 1000
  sum=$(CHAIN_STEPS_CSV=100 "$bin/chain_steps" "$chain" 1000 2>/dev/null | md5sum)
  echo "chain $chain 1000 ${sum:0:8}"
done

for case in world-implicit world-symplectic sheet-symplectic sheet-implicit-1e-3 sheet-implicit-5e-3; do
  bits=$("$bin/cloth_steps" "$case" 2000 2>/dev/null | grep -o 'bits=[0-9a-f]*')
  echo "cloth $case 2000 ${bits#bits=}"
done
