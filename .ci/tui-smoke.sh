#!/usr/bin/env bash
# Real-terminal smoke test of the terminal app: start the release binary in a 120×40 tmux pane,
# press keys, check that the panels and changing numbers appear, export an SVG (x), that Esc
# closes the graph and the settings form without quitting, that the form applies a change, quit
# with q, and check the process exited 0 and left the terminal in cooked mode on the main screen.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v tmux >/dev/null || { echo "tui-smoke: tmux is required" >&2; exit 1; }
cargo build --release --quiet
bin="$PWD/target/release/tumble"
work="$(mktemp -d)"
session="tumble-smoke-$$"
cleanup() { tmux kill-session -t "$session" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT

fail() {
  echo "tui-smoke: FAIL: $1" >&2
  echo "--- last screen ---" >&2
  tmux capture-pane -p -t "$session" >&2 || true
  exit 1
}
screen() { tmux capture-pane -p -t "$session"; }
# Waits until the screen contains $1 (up to 10 s).
wait_for() {
  for _ in $(seq 1 100); do
    screen | grep -qF -- "$1" && return 0
    sleep 0.1
  done
  fail "never saw \`$1\`"
}

# After the app exits, the pane's shell records the exit code and the tty mode, then waits.
tmux new-session -d -s "$session" -x 120 -y 40 \
  "bash -c 'cd \"$work\"; \"$bin\" --ascii; echo EXIT=\$? > \"$work/exit\"; stty -a > \"$work/stty\"; echo SHELL-AFTER-APP; sleep 60'"

wait_for "the loop"
for part in "state" "inertia tensor" "angular velocity" "angular momentum" "energy" \
            "derive" "collide" "? help" "t 0.000000 s" "step 0"; do
  screen | grep -qF -- "$part" || fail "panel or label \`$part\` missing"
done

# One phase, then one frame.
tmux send-keys -t "$session" n
wait_for "after derive"
tmux send-keys -t "$session" Right
wait_for "step 1 "
before="$(screen)"

# Run: the run pauses by itself at the next page of the lesson; time and numbers change.
tmux send-keys -t "$session" Space
wait_for "paused: page"
after="$(screen)"
t_before="$(grep -o 't [0-9.]* s' <<<"$before" | head -1)"
t_after="$(grep -o 't [0-9.]* s' <<<"$after" | head -1)"
[[ -n "$t_after" && "$t_before" != "$t_after" ]] || fail "time did not advance ($t_before → $t_after)"
x_before="$(grep -o ' x  .*  m' <<<"$before" | head -1)"
x_after="$(grep -o ' x  .*  m' <<<"$after" | head -1)"
[[ -n "$x_after" && "$x_before" != "$x_after" ]] || fail "position did not change"

# Step back, help overlay, views, integrator switch.
tmux send-keys -t "$session" Left
tmux send-keys -t "$session" '?'
wait_for "help — ? or Esc closes"
tmux send-keys -t "$session" '?'
tmux send-keys -t "$session" v
wait_for "side z–y"
tmux send-keys -t "$session" i
wait_for "integrator rk4"

# Export the screen as SVG (key x): written in the current folder, named in the status line.
tmux send-keys -t "$session" x
wait_for "wrote tumble-"
svg="$(ls "$work"/tumble-*.svg 2>/dev/null | head -1)"
[[ -n "$svg" ]] || fail "x wrote no SVG in the current folder"
grep -q "<svg" "$svg" && grep -qF "inertia tensor" "$svg" || fail "the SVG lacks the screen's text"

# Esc closes the graph and never quits.
tmux send-keys -t "$session" g
wait_for "energy, J"
tmux send-keys -t "$session" Escape
wait_for "inertia tensor"
screen | grep -qF "energy, J" && fail "Esc did not close the energy graph"
tmux send-keys -t "$session" Escape
wait_for "nothing to close: q quits"
[[ -s "$work/exit" ]] && fail "Esc quit the app"

# The settings form (of the body the panels show): change the third field (the box's size y), apply (the scene restarts), then Esc closes a reopened form.
tmux send-keys -t "$session" e
wait_for "— Esc closes, nothing applied"
for _ in 1 2; do tmux send-keys -t "$session" Down; done
tmux send-keys -t "$session" 3 Enter
wait_for "settings applied ("
wait_for "step 0 "
tmux send-keys -t "$session" e
wait_for "— Esc closes, nothing applied"
tmux send-keys -t "$session" Escape
wait_for "settings closed: nothing applied"
[[ -s "$work/exit" ]] && fail "Esc quit the app from the form"

# Quit: exit code 0, cooked mode, main screen back.
tmux send-keys -t "$session" q
for _ in $(seq 1 100); do [[ -s "$work/stty" ]] && break; sleep 0.1; done
[[ -s "$work/exit" ]] || fail "the app did not exit"
[[ "$(cat "$work/exit")" == "EXIT=0" ]] || fail "exit code: $(cat "$work/exit")"
grep -qw icanon "$work/stty" && grep -qw echo "$work/stty" || fail "terminal left in raw mode: $(cat "$work/stty")"
wait_for "SHELL-AFTER-APP"
screen | grep -qF "inertia tensor" && fail "the app's screen is still shown (alternate screen not left)"
echo "tui-smoke: ok ($t_before → $t_after)"
