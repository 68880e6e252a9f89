#!/usr/bin/env bash
# scripts/launch-srun.sh and scripts/slurm/igi-hetjob.sbatch against a Slurm
# of our own on this machine: munged, slurmctld and two slurmd (nodes igi-a
# and igi-b, both 127.0.0.1 on ports of their own), configured and kept in a
# temporary folder (SLURM_CONF points there; /etc is not touched), without
# cgroups (proctrack/linuxproc, task/none), and torn down at the end. Checks
# that
#   - launch-srun.sh, making its own allocation of two nodes, runs two workers
#     whose frames equal, bit for bit, the single-process render;
#   - the heterogeneous-job example (master in component 0, workers in
#     component 1 dialling back) does the same through sbatch --wait.
#   tests/launch/slurm_launch_test.sh BUILD-DIR
# Skips (exit 77, with the reason) where Slurm cannot run: not root, packages
# missing, or daemons that do not come up (e.g. in a container that forbids them).
set -uo pipefail
BUILD=$(cd "${1:?usage: slurm_launch_test.sh BUILD-DIR}" && pwd)
source "$(dirname "$0")/test-lib.sh"

[ "$(id -u)" = 0 ] || skip "needs root: slurmd starts jobs as their users"
for program in munged munge unmunge slurmctld slurmd srun sbatch sinfo scancel squeue idiff python3; do
  command -v "$program" >/dev/null ||
    skip "$program is missing (scripts/setup.sh installs slurm-wlm, munge, openimageio-tools)"
done

tmp=$(mktemp -d /tmp/igi-slurm-test-XXXXXX)
chmod 0755 "$tmp"  # munged wants its socket's folders open to all (the key folder is not)
export SLURM_CONF="$tmp/slurm.conf"
all_gone() {  # of the pids in $pids
  local pid
  for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && return 1; done
  return 0
}
teardown() {
  local start=$SECONDS pidfile pids=()
  if [ -f "$tmp/slurmctld.pid" ] && [ -n "$(squeue -h 2>/dev/null)" ]; then
    scancel --quiet --full --user=root 2>/dev/null
    wait_until 5 bash -c '[ -z "$(squeue -h 2>/dev/null)" ]'
  fi
  for pidfile in "$tmp"/slurmd-igi-a.pid "$tmp"/slurmd-igi-b.pid "$tmp"/slurmctld.pid "$tmp"/munge/munged.pid; do
    [ -f "$pidfile" ] && pids+=("$(cat "$pidfile")")
  done
  if [ ${#pids[@]} -gt 0 ]; then
    kill -TERM "${pids[@]}" 2>/dev/null
    wait_until 10 all_gone || echo "teardown: daemons still running: $(ps -o pid=,args= -p "$(IFS=,; echo "${pids[*]}")")"
    kill -KILL "${pids[@]}" 2>/dev/null
  fi
  rm -rf "$tmp"
  echo "teardown: $((SECONDS - start)) s"
}
trap teardown EXIT
show_logs() { for log in "$@"; do [ -f "$log" ] && { echo "--- $log"; tail -n 15 "$log"; }; done; }

# --- munge, with a key of its own
mkdir -m 0700 "$tmp/secret" && mkdir -m 0755 "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/log"
head -c 1024 /dev/urandom >"$tmp/secret/munge.key" && chmod 0400 "$tmp/secret/munge.key"
munged --key-file="$tmp/secret/munge.key" --socket="$tmp/munge/munge.socket" --pid-file="$tmp/munge/munged.pid" \
  --log-file="$tmp/secret/munged.log" --seed-file="$tmp/secret/munged.seed" 2>"$tmp/secret/munged.err"
if ! munge -n -S "$tmp/munge/munge.socket" | unmunge -S "$tmp/munge/munge.socket" >/dev/null 2>&1; then
  show_logs "$tmp/secret/munged.err" "$tmp/secret/munged.log"
  skip "munged does not run here (its log above)"
fi

# --- slurmctld and two slurmd on loopback ports
cpus=$(nproc)
cat >"$SLURM_CONF" <<EOF
ClusterName=igitest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$(free_port)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool/%n
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd-%n.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/backfill
SchedulerParameters=bf_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
KillWait=5
MailProg=/bin/true
NodeName=igi-a NodeHostname=localhost NodeAddr=127.0.0.1 Port=$(free_port) CPUs=$cpus State=UNKNOWN
NodeName=igi-b NodeHostname=localhost NodeAddr=127.0.0.1 Port=$(free_port) CPUs=$cpus State=UNKNOWN
PartitionName=igi Nodes=igi-a,igi-b Default=YES MaxTime=5 State=UP
EOF
start=$SECONDS
slurmctld -f "$SLURM_CONF" 2>"$tmp/log/slurmctld.err" &&
  slurmd -f "$SLURM_CONF" -N igi-a 2>"$tmp/log/slurmd-a.err" &&
  slurmd -f "$SLURM_CONF" -N igi-b 2>"$tmp/log/slurmd-b.err"
idle() { [ "$(sinfo -h -N -o %T 2>/dev/null | sort -u)" = idle ]; }
if ! wait_until 20 idle; then
  sinfo -N 2>&1
  show_logs "$tmp"/log/*
  skip "Slurm's daemons do not come up here (their logs above)"
fi
echo "single-node Slurm up in $((SECONDS - start)) s"

reference "$tmp/reference.exr"

# --- launch-srun.sh: srun makes an allocation of both nodes, one worker on each
port=$(free_port)
mkdir -p "$tmp/srun-frames"
start=$SECONDS
(cd "$tmp" && timeout -s KILL 60 "$REPO/scripts/launch-srun.sh" --workers 2 --srun-args "--nodes=2 --time=1" \
  --build "$BUILD" --master-host 127.0.0.1 --port "$port" --listen "tcp://127.0.0.1:$port" --dir "$tmp/run-srun" \
  -- "${RENDER[@]}" --frames $FRAMES -o "$tmp/srun-frames/f.exr") >"$tmp/srun.out" 2>&1
status=$?
cat "$tmp/srun.out"
if [ $status != 0 ]; then
  show_logs "$tmp/run-srun/master.log" "$tmp/run-srun/srun.log" "$tmp"/run-srun/workers/*.log "$tmp/log/slurmctld.log"
  fail "launch-srun.sh exited with $status"
fi
echo "launch-srun.sh with 2 workers and $FRAMES frames: $((SECONDS - start)) s"
check_frames "$tmp/srun-frames/f" "$tmp/reference.exr" launch-srun
for task in 0 1; do
  grep -q ready "$tmp/run-srun/workers/worker-$task.log" || fail "task $task: no sign of a worker that loaded the scene"
done

# --- the heterogeneous-job example, sized for two small nodes on the command line
port=$(free_port)
mkdir -p "$tmp/het-frames"
start=$SECONDS
# (sbatch --wait polls at 2 s doubling to 10 s; scontrol is asked every 0.1 s)
job=$(cd "$tmp" && IGI_HOME="$REPO" IGI_LAUNCH_ARGS="--build $BUILD --master-host 127.0.0.1 --port $port \
  --listen tcp://127.0.0.1:$port --dir $tmp/run-het" \
  sbatch --parsable --output="$tmp/het.out" -N1 -n1 -c1 -t 1 : -N1 -n2 --ntasks-per-node=2 -c1 -t 1 \
  "$REPO/scripts/slurm/igi-hetjob.sbatch" "${RENDER[@]}" --frames $FRAMES -o "$tmp/het-frames/f.exr")
job=${job%%;*}
[ -n "$job" ] || fail "sbatch refused the heterogeneous job"
ended() {
  local state
  state=$(scontrol show job "$job" -o 2>/dev/null) && [ -n "$state" ] &&
    ! grep -Eq "JobState=(PENDING|CONFIGURING|RUNNING|COMPLETING)" <<<"$state"
}
wait_until 90 ended || fail "the heterogeneous job $job did not end in 90 s: $(scontrol show job "$job" -o)"
# The leader's (component 0's) exit code is the batch script's.
status=$(scontrol show job "$job" -o | head -n 1 | sed -n 's/.* ExitCode=\([0-9]*\):.*/\1/p')
cat "$tmp/het.out"
if [ "$status" != 0 ]; then
  show_logs "$tmp/run-het/master.log" "$tmp/run-het/srun.log" "$tmp"/run-het/workers/*.log "$tmp/log/slurmctld.log"
  fail "the heterogeneous job ended with $status"
fi
echo "sbatch igi-hetjob.sbatch with 2 workers and $FRAMES frames: $((SECONDS - start)) s"
check_frames "$tmp/het-frames/f" "$tmp/reference.exr" launch-hetjob
for task in 0 1; do
  grep -q ready "$tmp/run-het/workers/worker-$task.log" || fail "hetjob task $task: no sign of a worker that loaded the scene"
done

# --- a master that dies: the launcher ends the srun step (its workers on every node) and says so
port=$(free_port)
"$REPO/scripts/launch-srun.sh" --workers 2 --srun-args "--nodes=2 --time=1" --grace 1 --build "$BUILD" \
  --master-host 127.0.0.1 --port "$port" --listen "tcp://127.0.0.1:$port" --dir "$tmp/run-crash" \
  -- "${RENDER[@]}" --frames 1000000 --no-write >"$tmp/crash.out" 2>&1 &
launcher=$!
ready() { [ "$(cat "$tmp"/run-crash/workers/*.log 2>/dev/null | grep -c ready)" = 2 ]; }
wait_until 20 ready || { kill -KILL $launcher; cat "$tmp/crash.out"; fail "the workers did not start"; }
master=$(sed -n 's/.*master on .*(pid \([0-9]*\)).*/\1/p' "$tmp/crash.out")
[ -n "$master" ] || { kill -KILL $launcher; fail "the launcher did not name the master's pid"; }
kill -KILL "$master"
wait_until 20 bash -c "! kill -0 $launcher 2>/dev/null" || { kill -KILL $launcher; fail "the launcher outlived its master by 20 s"; }
wait $launcher
status=$?
cat "$tmp/crash.out"
[ $status = 1 ] || fail "a killed master: expected exit status 1, got $status"
grep -q "the master failed (exit 137)" "$tmp/crash.out" || fail "the launcher does not say the master failed"
steps() { [ -z "$(squeue -h 2>/dev/null)" ] && ! pgrep -f -- "--connect tcp://127.0.0.1:$port" >/dev/null; }
wait_until 10 steps || fail "workers or jobs outlived the launcher: $(squeue -h) $(pgrep -f -- "--connect tcp://127.0.0.1:$port" | xargs)"

# --- srun failing at once (a partition that does not exist): exit 3, and srun's reason in its log
port=$(free_port)
timeout -s KILL 60 "$REPO/scripts/launch-srun.sh" --workers 2 --srun-args "--partition=nosuch --time=1" \
  --build "$BUILD" --master-host 127.0.0.1 --port "$port" --listen "tcp://127.0.0.1:$port" --dir "$tmp/run-bad" \
  -- "${RENDER[@]}" --frames 1 -o "$tmp/bad.exr" >"$tmp/bad.out" 2>&1
status=$?
cat "$tmp/bad.out"
[ $status = 3 ] || fail "srun failing: expected exit status 3, got $status"
grep -q "nosuch" "$tmp/bad.out" || fail "srun's reason is not shown"
echo "PASS"
