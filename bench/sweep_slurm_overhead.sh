#!/usr/bin/env bash
# What a shard costs on Slurm beyond its trials: one sweep of SHARDS one-trial shards (the planar
# arm's shelf pick, a few milliseconds a trial) run on the local backend with one worker per core,
# then through sbatch on the one-node cluster of scripts/slurm_local.sh (one task per core), both
# waited for; the difference per shard and core is the per-shard overhead (scheduling, starting
# mjarm, reading the plan, writing the shard file).
#   bench/sweep_slurm_overhead.sh [MJARM] [SHARDS]   (defaults: build-demo/mjarm, 48)
set -euo pipefail
mjarm=$(realpath "${1:-build-demo/mjarm}")
shards="${2:-48}"
source_dir=$(cd "$(dirname "$0")/.." && pwd)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cores=$(nproc)
cat > "$work/sweep.yaml" <<YAML
scenario: shelf-pick
parameters: {robot: planar2, controller: ct}
seeds: $shards
YAML
cat > "$work/session.sh" <<SESSION
#!/usr/bin/env bash
set -euo pipefail
cd "$work"
t0=\$(date +%s.%N)
"$mjarm" sweep run sweep.yaml --out local --shard-size 1 --jobs $cores > /dev/null
t1=\$(date +%s.%N)
"$mjarm" sweep run sweep.yaml --out slurm --shard-size 1 --backend slurm --wait > /dev/null
t2=\$(date +%s.%N)
cmp -s <("$mjarm" sweep export local --csv) <("$mjarm" sweep export slurm --csv)
python3 - <<PY
local, slurm = \$t1 - \$t0, \$t2 - \$t1
print(f"{$shards} one-trial shards on {$cores} cores: local {local:.2f} s, Slurm {slurm:.2f} s")
print(f"per-shard overhead on Slurm: {(slurm - local) * $cores / $shards:.3f} s (same rows: yes)")
PY
SESSION
chmod +x "$work/session.sh"
bash "$source_dir/scripts/slurm_local.sh" "$work/cluster" "$work/session.sh"
