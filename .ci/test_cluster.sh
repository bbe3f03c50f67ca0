#!/usr/bin/env bash
# make test-cluster: the tiny workflow three times, compared bit for bit.
#   local    snakemake --cores 2 (the reference; its BEM seeds the other two)
#   route 1  snakemake --workflow-profile workflow/profiles/slurm (every heavy rule a SLURM job)
#   route 2  a dask-jobqueue cluster (workflow/profiles/slurm/dask_jobqueue_example.py), then
#            snakemake --cores 2 with DASK_SCHEDULER_ADDRESS: the simulations run on its workers
# Route 1 and route 2 start from the local run's results/hydro/platform.nc (copied, then
# touched: the BEM is the slowest rule, and snakemake must not rerun it). Needs a SLURM
# cluster: if none answers, .ci/slurm.sh starts the one-node cluster and stops it at exit.
# Usage: .ci/test_cluster.sh [BIN]   (BIN: the venv's bin folder, default .venv/bin)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BIN=$(cd "${1:-.venv/bin}" && pwd)
WORK=${MOORLIFE_CLUSTER_WORK:-$ROOT/.test-cluster}
CONFIG=(--configfile config/quick.yaml tests/data/tiny.yaml)
t0=$(date +%s)
say() { echo "== test-cluster [$(($(date +%s) - t0)) s] $*"; }

started=0
cleanup() {
    if [[ -f $WORK/route2/dask-cluster.pid ]]; then
        kill "$(cat "$WORK/route2/dask-cluster.pid")" 2>/dev/null || true
    fi
    if ((started)); then bash "$ROOT/.ci/slurm.sh" down || true; fi
}
trap cleanup EXIT
if ! scontrol ping 2>/dev/null | grep -q UP; then
    bash "$ROOT/.ci/slurm.sh" up
    started=1
fi
sinfo

rm -rf "$WORK"
for run in local route1 route2; do
    mkdir -p "$WORK/$run/tests"
    cp -r Snakefile workflow config envs "$WORK/$run/"
    cp -r tests/data "$WORK/$run/tests/"
done
export PATH=$BIN:$PATH PYTHONWARNINGS=ignore
unset DASK_SCHEDULER_ADDRESS

say "local run (snakemake --cores 2)"
(cd "$WORK/local" && snakemake --cores 2 "${CONFIG[@]}" >snakemake.log 2>&1) ||
    { tail -n 60 "$WORK/local/snakemake.log"; exit 1; }

seed() { # the local BEM, so that hydro does not rerun
    mkdir -p "$WORK/$1/results/hydro"
    cp "$WORK/local/results/hydro/platform.nc" "$WORK/$1/results/hydro/platform.nc"
    touch "$WORK/$1/results/hydro/platform.nc"
}

say "route 1: snakemake --workflow-profile workflow/profiles/slurm --max-threads 2"
seed route1
(cd "$WORK/route1" && snakemake --workflow-profile workflow/profiles/slurm --max-threads 2 \
    "${CONFIG[@]}" >snakemake.log 2>&1) || { tail -n 80 "$WORK/route1/snakemake.log"; exit 1; }
ids=$(grep -oE "SLURM jobid [0-9]+|external jobid '?[0-9]+" "$WORK/route1/snakemake.log" | grep -oE "[0-9]+$" | tr '\n' ' ' || true)
n=$(wc -w <<<"$ids")
((n > 0)) || { echo "route 1 submitted no SLURM job"; tail -n 40 "$WORK/route1/snakemake.log"; exit 1; }
say "route 1: $n sbatch jobs: $ids"
grep -E "^(rule|localrule) " "$WORK/route1/snakemake.log" | sort | uniq -c

say "route 2: dask-jobqueue cluster (1 SLURM job, 2 workers), then snakemake --cores 2"
seed route2
cd "$WORK/route2"
DASK_SCHEDULER_ADDRESS=$(python "$ROOT/workflow/profiles/slurm/dask_jobqueue_example.py" \
    --jobs 1 --cores 2 --memory 4GB --walltime 00:30:00 --timeout 300 --detach)
export DASK_SCHEDULER_ADDRESS
cat dask-cluster.log
squeue
(snakemake --cores 2 "${CONFIG[@]}" >snakemake.log 2>&1) || { tail -n 80 snakemake.log; exit 1; }
joined=$(grep -l "joining the Dask scheduler at $DASK_SCHEDULER_ADDRESS" logs/*/simulate_*.log logs/sensitivity/*.log 2>/dev/null | wc -l)
((joined > 0)) || { echo "route 2: no simulate rule joined the dask-jobqueue scheduler"; exit 1; }
say "route 2: $joined simulate jobs ran on the dask-jobqueue workers (SLURM job $(squeue -h -n dask-worker -o %i | tr '\n' ' '))"
kill "$(cat dask-cluster.pid)"
for _ in $(seq 50); do [[ -f dask-cluster.pid ]] || break; sleep 0.2; done
unset DASK_SCHEDULER_ADDRESS
cd "$ROOT"

say "compare every output with the local run"
rc=0
python .ci/compare_runs.py "$WORK/local" "$WORK/route1" || rc=1
python .ci/compare_runs.py "$WORK/local" "$WORK/route2" || rc=1
((rc == 0)) || { echo "test-cluster: outputs differ from the local run"; exit 1; }
say "passed: routes 1 and 2 identical to the local run"
