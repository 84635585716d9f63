#!/usr/bin/env bash
# `mjarm sweep --backend slurm` on a real one-node cluster (scripts/slurm_local.sh): the rows
# through sbatch equal the local backend's; a dry run writes the scripts and submits nothing; a
# shard that fails names its exit status and log line to the user and a resume runs only it; a
# sweep cancelled mid-run leaves no partial shard file and a resume runs only what is missing.
# Usage: sweep_slurm_check.sh SOURCE_DIR WORK_DIR MJARM
set -euo pipefail
source_dir=$1
work=$2
mjarm=$(realpath "$3")
rm -rf "$work"
mkdir -p "$work"

cat > "$work/shelf.yaml" <<'YAML'
scenario: shelf-pick
parameters: {robot: planar2}
axes:
  controller: [ct, osc, task-pd]
seeds: 2
YAML
# a long hold: each trial runs for seconds, long enough to be cancelled in the middle
cat > "$work/docking.yaml" <<'YAML'
scenario: docking
parameters: {motion.hold-time: 60}
axes:
  offset.dx: [0.0, 0.002, 0.004]
YAML

cat > "$work/session.sh" <<SESSION
#!/usr/bin/env bash
set -u
cd "$work"
passed=0
failed=0
expect() {  # expect WHAT COMMAND...
  local what=\$1
  shift
  if "\$@"; then passed=\$((passed + 1)); else failed=\$((failed + 1)); echo "FAILED: \$what"; fi
}
sweep() { "$mjarm" sweep "\$@"; }

# 1. the same trials through sbatch as on the local backend, and as two arrays: the cluster takes
#    at most 4 tasks in one (MaxArraySize=4 below), the sweep has 6 shards of one trial
sweep run shelf.yaml --out local --shard-size 2 --json > local.json
sweep run shelf.yaml --out slurm --shard-size 1 --backend slurm --wait --json > slurm.json
expect "the Slurm sweep ends well (exit \$?)" [ \$? -eq 0 ]
expect "six shards in two arrays (4 + 2)" grep -qx '#SBATCH --array=0-1' slurm/slurm/array-1.sbatch
sweep export local --csv > local.csv
sweep export slurm --csv > slurm.csv
expect "the trials rows through Slurm equal the local ones" cmp -s local.csv slurm.csv
expect "six rows" [ "\$(wc -l < slurm.csv)" -eq 7 ]
expect "the merge job ran" ls slurm/slurm/logs/merge-*.out
expect "the tasks' exit statuses were kept" [ "\$(cat slurm/slurm/exit/shard-*.txt | tr -d '\n')" = 000000 ]

# 2. a dry run: the scripts with the throttle and the pass-through options, nothing submitted
sweep run shelf.yaml --out dry --shard-size 2 --backend slurm --dry-run --throttle 1 \
  --sbatch-arg=--nice=10 > dry.txt
expect "a dry run exits 0" [ \$? -eq 0 ]
expect "the array line has the throttle" grep -qx '#SBATCH --array=0-2%1' dry/slurm/array-0.sbatch
expect "a dry run submits nothing" [ -z "\$(squeue -h -o %i)" ]
expect "a dry run writes no job list" [ ! -e dry/slurm/jobs.json ]

# 3. a shard that cannot be written: its exit status and message reach the user; resume runs it
sweep run shelf.yaml --out broken --shard-size 2 --backend slurm --dry-run > /dev/null
mkdir broken/shards/shard-000001.json  # a folder where the shard's file goes
sweep resume broken --backend slurm --wait > broken.txt 2> broken.err
status=\$?
expect "a failed shard fails the sweep (exit 1), got \$status" [ \$status -eq 1 ]
expect "the user is told which shard failed, its exit status and why" \
  grep -q "1 of 3 shards did not finish: shard 1 exited with 1: mjarm: error: .*shard" broken.err
rmdir broken/shards/shard-000001.json
sweep resume broken --backend slurm --wait > resumed.txt
expect "the resume ends well" [ \$? -eq 0 ]
expect "the resume submitted only the failed shard" grep -q "^submitted 1 shards" resumed.txt
sweep export broken --csv > broken.csv
expect "after the resume, the rows equal the local ones" cmp -s local.csv broken.csv

# 4. cancelled mid-run: no partial shard file; resume runs only what is missing
sweep run docking.yaml --out cancelled --shard-size 1 --backend slurm --throttle 1 > cancel.txt
for _ in \$(seq 600); do
  [ -n "\$(squeue -h -t RUNNING -o %i)" ] && [ -e cancelled/slurm/logs/shard-0.log ] && break
  sleep 0.1
done
sleep 0.5  # the first shard's trial is under way (a docking trial takes seconds)
sweep cancel cancelled > /dev/null
for _ in \$(seq 300); do
  [ -z "\$(squeue -h -o %i)" ] && break
  sleep 0.1
done
expect "no job is left after the cancel" [ -z "\$(squeue -h -o %i)" ]
expect "no shard file, whole or partial, was left by the cancelled shards" \
  [ -z "\$(ls -A cancelled/shards)" ]
sweep status cancelled --json > status.json
expect "status: three shards missing, none damaged" python3 -c "
import json; s = json.load(open('status.json'))
assert s['missing'] == [0, 1, 2] and s['damaged'] == [] and s['done'] == 0, s"
sweep resume cancelled --backend slurm --wait --json > cancelled.json
expect "the resume ran the three shards" python3 -c "
import json; s = json.load(open('cancelled.json'))
assert s['slurm']['shards'] == 3 and s['merge']['trials'] == 3, s"

echo "\$passed passed, \$failed failed"
[ "\$failed" -eq 0 ]
SESSION
chmod +x "$work/session.sh"
SLURM_LOCAL_EXTRA_CONF="MaxArraySize=4" \
  exec bash "$source_dir/scripts/slurm_local.sh" "$work/cluster" "$work/session.sh"
