#!/usr/bin/env bash
# Renders on Slurm nodes: starts igi-master here and N igi-worker tasks with
# one srun, which dial back to the master (see scripts/lib/launch-common.sh
# for the exit statuses). Run it inside an allocation (an sbatch script, for
# one scripts/slurm/igi-hetjob.sbatch, or salloc), or where srun may make its
# own allocation (a login node whose master port the compute nodes reach).
#   scripts/launch-srun.sh --workers N [options] -- IGI-MASTER-OPTIONS
#
# Keys: a fresh CURVE key pair for the master and one shared by the step's
# workers, made in DIR/keys; srun hands the worker's secret key and the
# master's public key to every task on its standard input (--input=all), so
# they are never on a command line or a worker's disk. When the master ends,
# its goodbye ends the workers; a step still running after --grace seconds is
# ended by signalling srun, which ends its tasks on every node.
set -uo pipefail
LAUNCH_NAME=launch-srun.sh
source "$(dirname "$0")/lib/launch-common.sh"

usage() {
  cat <<EOF
usage: scripts/launch-srun.sh --workers N [options] -- IGI-MASTER-OPTIONS
Starts igi-master here and N igi-worker tasks with srun; the workers connect back to
the master, CURVE-authenticated with keys made for the run.
  --workers N          worker tasks (srun --ntasks) [SLURM_NTASKS, inside an allocation]
  --srun-args "ARGS"   more srun options, split at spaces: where and how the workers run, e.g.
                       "--het-group=1", "--nodes=4 --cpus-per-task=32 --time=30 --partition=gpu"
  --worker-threads T   render threads per worker [the task's SLURM_CPUS_PER_TASK, else all cores]
$(launch_common_usage)
Worker logs: DIR/workers/worker-TASK.log; srun's own messages: DIR/srun.log.
Example, inside salloc --nodes=4 --ntasks-per-node=1 --cpus-per-task=32:
  scripts/launch-srun.sh --workers 4 --master-host \$(hostname) -- \\
      --scene scene.glb --method igi --frames 100 --camera-path orbit -o frames.exr
EOF
}

workers=${SLURM_NTASKS:-} srun_args=() threads=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --) shift; master_args=("$@"); break ;;
    --threads) launch_fail "--threads is now --worker-threads, as igi-master calls it" ;;
    --workers | --srun-args | --worker-threads)
      [ $# -ge 2 ] || launch_fail "$1: missing value"
      case "$1" in
        --workers) workers=$2 ;;
        --srun-args) read -ra srun_args <<<"$2" ;;
        --worker-threads) threads=$2 ;;
      esac
      shift 2 ;;
    *)
      launch_parse_common "$@"
      [ "$shift_by" -gt 0 ] || launch_fail "unknown option '$1'"
      shift "$shift_by" ;;
  esac
done
command -v srun >/dev/null || launch_fail "srun not found: run this where Slurm's client commands are installed"
[ -n "$workers" ] || launch_fail "--workers N: how many worker tasks (outside an allocation there is no default)"
[[ "$workers" =~ ^[0-9]+$ ]] && [ "$workers" -ge 1 ] || launch_fail "--workers: expected a positive number, got '$workers'"
[ -z "$threads" ] || [[ "$threads" =~ ^[0-9]+$ ]] || launch_fail "--worker-threads: expected a number, got '$threads'"
launch_check_common
[ -z "$threads" ] || launch_worker_args+=(--threads "$threads")  # after the task's default: the later one counts

launch_make_keys worker
launch_start_master "$workers"
endpoint="tcp://$launch_master_host:$launch_port"
launch_say "master on $launch_listen (pid $master_pid); $workers workers dial $endpoint; logs in $launch_dir"

# Each task: read the keys on descriptor 0, render with the task's CPUs.
task='exec "$0" --curve-fd 0 --threads "${SLURM_CPUS_PER_TASK:-0}" "$@"'
srun --ntasks="$workers" --job-name=igi-workers --kill-on-bad-exit=0 --input=all \
  --output="$launch_dir/workers/worker-%t.log" "${srun_args[@]}" \
  /bin/sh -c "$task" "$launch_build/worker/igi-worker" --connect "$endpoint" "${launch_worker_args[@]}" \
  <<<"$(launch_worker_keys worker)" >"$launch_dir/srun.log" 2>&1 &
worker_pids=($!)
worker_names=("srun step of $workers tasks")
worker_logs=("$launch_dir/srun.log")

launch_channel_explain() {
  case $1 in
    1) echo "srun failed (no allocation, a bad option, a task that could not start: see srun.log)" ;;
    137 | 143) echo "the step was cancelled or killed" ;;
    *) echo "exit $1 (srun gives the highest exit status of its tasks: see DIR/workers/)" ;;
  esac
}
launch_stop_workers() { kill -TERM "${worker_pids[0]}" 2>/dev/null; }
launch_wait
