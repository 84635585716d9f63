#!/usr/bin/env bash
# Every task's figures as JSON, one file per command, into OUT: the shelf pick (100 seeds per
# robot and controller), pick and place (200 trials per robot, grasp and mode, seeds 1-200), the
# docking grids and tracking gates (sensor / sensorless, with and without joint friction) and the
# bimanual lift (position and motor mode). Used to put two builds side by side (an engine
# upgrade): bench/compare_task_figures.py OLD NEW prints the tables of docs/mujoco.md.
#
# usage: bench/task_figures.sh OUT [MJARM]     (MJARM: the CLI to run, default build/mjarm)
set -uo pipefail
[ $# -ge 1 ] && [ "$1" != "--help" ] || { sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
out=$1
bin=${2:-build/mjarm}
[ -x "$bin" ] || { echo "task_figures: no mjarm CLI at $bin" >&2; exit 2; }
mkdir -p "$out"
: > "$out/exit_codes.txt"

run() {
  local name=$1
  shift
  [ -t 2 ] && echo "task_figures: $name" >&2
  /usr/bin/time -f "%e s wall, %U s user" -o "$out/$name.time" \
    "$bin" "$@" --json > "$out/$name.json" 2> "$out/$name.err"
  # 1 is a task that did not meet its criteria (e.g. the plain CIC jams): its JSON is complete
  echo "$name $?" >> "$out/exit_codes.txt"
}

run shelf_all run shelf-pick --all --seeds 100
for robot in arm6 panda_hand; do
  for grasp in weld friction; do
    for mode in position torque; do
      run "pp_${robot}_${grasp}_${mode}" run pick-place --robot "$robot" --grasp "$grasp" \
        --mode "$mode" --trials 200 --seed 1
    done
  done
done
for kind in grid gate; do
  run "dock_${kind}" run docking "--$kind" --controller all
  run "dock_${kind}_sensorless" run docking "--$kind" --controller all --sensorless
  run "dock_${kind}_friction" run docking "--$kind" --controller all --friction
  run "dock_${kind}_friction_sensorless" run docking "--$kind" --controller all --friction \
    --sensorless
done
run bimanual_position bimanual --mode position
run bimanual_torque bimanual --mode torque
# a command that crashed or was refused (exit 2 and above) left no figures
failed=$(awk '$2 >= 2 { print $1 " (exit " $2 ")" }' "$out/exit_codes.txt")
if [ -n "$failed" ]; then
  echo "task_figures: no figures from: $failed" >&2
  exit 1
fi
