# Shared by scripts/launch-ssh.sh and scripts/launch-srun.sh (sourced, never
# run): the run folder and its keys, the master, the wait, and the summary.
#
# Both launchers start igi-master here and workers elsewhere that dial back to
# it (as ParaView's reverse connection does): the workers need to reach the
# master's port, the master needs no way in to them.
#
# Exit status of both launchers (what went wrong):
#   0  the master wrote every frame and every worker left cleanly
#   1  the master failed or was interrupted (the end of its log is shown)
#   2  bad options or hosts file: nothing was started
#   3  every worker ended before the master finished (the master was stopped)
#   4  the master finished, but some workers did not end cleanly (each named)
#
# The caller sets LAUNCH_NAME, fills the variables below through
# launch_parse_common, starts its workers (worker_pids: one process per
# channel, an ssh or an srun), and defines launch_stop_workers (how they are
# told to go) and launch_channel_explain (what that channel's exit statuses
# mean) before calling launch_wait.

LAUNCH_REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

launch_build="$LAUNCH_REPO/build"  # where igi-master, igi-keys and igi-worker were built
launch_dir=""                      # the run folder: keys/, master.log, workers/
launch_master_host=""              # the address workers dial back to
launch_port=5555
launch_listen=""                   # what the master binds [tcp://0.0.0.0:PORT]
launch_worker_args=()              # extra igi-worker options, for every worker
launch_grace=10                    # seconds workers get to leave after the master ends
launch_gather=30                   # seconds the master waits for every worker before the first frame
launch_viewer_keys=""              # --viewer-keys: the window goes to igi-view (the master's --viewer-listen)
launch_viewer_port=5600
master_args=()                     # after --: igi-master's own options
worker_pids=() worker_names=() worker_logs=()  # the launcher's channel to each worker (ssh, srun)
worker_status=()                   # their exit statuses, as they end
stopped=()                         # indices of those still running when the launcher stopped them
alive=0
master_pid="" master_status="" interrupted=0

launch_fail() { echo "$LAUNCH_NAME: $*" >&2; echo "($LAUNCH_NAME --help lists the options)" >&2; exit 2; }
launch_say() { echo "$LAUNCH_NAME: $*" >&2; }

# Options both launchers share. Sets `shift_by` to what it used of "$@" (0: not ours).
launch_parse_common() {
  shift_by=2
  case "$1" in
    --build | --dir | --master-host | --port | --listen | --worker-args | --grace | --min-workers-wait | \
      --viewer-keys | --viewer-port)
      [ $# -ge 2 ] || launch_fail "$1: missing value" ;;
    --wait-workers) launch_fail "--wait-workers is now --min-workers-wait, as igi-master calls it" ;;
    *) shift_by=0; return ;;
  esac
  case "$1" in
    --build) launch_build=$2 ;;
    --dir) launch_dir=$2 ;;
    --master-host) launch_master_host=$2 ;;
    --port) launch_port=$2 ;;
    --listen) launch_listen=$2 ;;
    --worker-args) read -ra launch_worker_args <<<"$2" ;;
    --grace) launch_grace=$2 ;;
    --min-workers-wait) launch_gather=$2 ;;
    --viewer-keys) launch_viewer_keys=$2 ;;
    --viewer-port) launch_viewer_port=$2 ;;
  esac
}

launch_common_usage() {
  cat <<EOF
  --master-host HOST   the address the workers dial back to [$(launch_default_host)]
  --port N             the master's port; workers must be able to reach it [5555]
  --listen ENDPOINT    what the master binds [tcp://0.0.0.0:PORT]
  --dir DIR            the run folder: keys/, master.log, workers/*.log [igi-run-DATE-TIME]
  --build DIR          where igi-master, igi-keys and igi-worker were built [$LAUNCH_REPO/build]
  --worker-args "ARGS" more igi-worker options for every worker, e.g.
                       "--scene-dir /shared/scenes --cache /scratch/igi --give-up 30"
  --min-workers-wait S the first frame waits until every worker has joined, at most S seconds,
                       then starts with those present (igi-master's option of that name) [30]
  --grace S            seconds workers get to leave after the master ends [10]
  --viewer-keys PATH   leave the window to igi-view on your own machine: the viewers' .pub files
                       (igi-keys new NAME); the master listens for one on 127.0.0.1:VIEWER-PORT,
                       and the launcher prints the ssh tunnel and igi-view commands
  --viewer-port N      that port [5600]
  -- OPTIONS           igi-master's options (scene, method, --frames, -o, ...); the launcher adds
                       --workers 0 --listen --key --authorized-keys
Exit status: 0 all went well; 1 the master failed or was interrupted; 2 bad options (nothing
started); 3 every worker ended before the master finished; 4 the master finished but some
workers did not end cleanly. Logs: DIR/master.log and DIR/workers/.
EOF
}

launch_default_host() { hostname -f 2>/dev/null || hostname; }

# Checks what both need and fills the defaults.
launch_check_common() {
  [[ "$launch_port" =~ ^[0-9]+$ ]] && [ "$launch_port" -ge 1 ] && [ "$launch_port" -le 65535 ] ||
    launch_fail "--port: expected a number from 1 to 65535, got '$launch_port'"
  [[ "$launch_grace" =~ ^[0-9]+$ ]] || launch_fail "--grace: expected whole seconds, got '$launch_grace'"
  [[ "$launch_gather" =~ ^[0-9]+$ ]] || launch_fail "--min-workers-wait: expected whole seconds, got '$launch_gather'"
  [[ "$launch_viewer_port" =~ ^[0-9]+$ ]] && [ "$launch_viewer_port" -ge 1 ] && [ "$launch_viewer_port" -le 65535 ] ||
    launch_fail "--viewer-port: expected a number from 1 to 65535, got '$launch_viewer_port'"
  [ -z "$launch_viewer_keys" ] || [ -e "$launch_viewer_keys" ] || launch_fail "--viewer-keys $launch_viewer_keys: not found"
  [ -n "$launch_master_host" ] || launch_master_host=$(launch_default_host)
  [ -n "$launch_listen" ] || launch_listen="tcp://0.0.0.0:$launch_port"
  [ -n "$launch_dir" ] || launch_dir="igi-run-$(date +%Y%m%d-%H%M%S)"
  for program in master/igi-master master/igi-keys worker/igi-worker; do
    [ -x "$launch_build/$program" ] || launch_fail "$launch_build/$program: not found (build with scripts/build.sh, or give --build DIR)"
  done
  launch_build=$(cd "$launch_build" && pwd)
  [ ${#master_args[@]} -gt 0 ] || launch_fail "no igi-master options after --: which scene, how many frames, where to write them?"
  if [ -e "$launch_dir/keys" ]; then launch_fail "$launch_dir holds an earlier run: give another --dir, or remove it"; fi
  mkdir -p "$launch_dir/workers" || launch_fail "$launch_dir: cannot create the run folder"
  launch_dir=$(cd "$launch_dir" && pwd)
}

# Fresh CURVE keys for this run, in DIR/keys (mode 0700): the master's pair,
# and one pair for each worker NAME given, whose .pub goes to keys/workers/,
# the master's --authorized-keys. Secret keys never leave this machine except
# through the launcher's channel to the worker (ssh or srun standard input).
launch_make_keys() {
  (umask 077 && mkdir -p "$launch_dir/keys/workers") || exit 1
  local name
  for name in master "$@"; do
    (cd "$launch_dir/keys" && "$launch_build/master/igi-keys" new "$name" >/dev/null) || exit 1
    [ "$name" = master ] || mv "$launch_dir/keys/$name.pub" "$launch_dir/keys/workers/"
  done
}

# FIELD's Z85 value in a key file (public-key or secret-key).
launch_key_value() {
  sed -n "s/^[[:space:]]*$2[[:space:]]*=[[:space:]]*\"\([^\"]*\)\".*/\1/p" "$1"
}

# What a worker reads through --curve-fd: the master's public key and its own secret.
launch_worker_keys() {
  printf 'server-key = "%s"\nsecret-key = "%s"\n' "$(launch_key_value "$launch_dir/keys/master.pub" public-key)" \
    "$(launch_key_value "$launch_dir/keys/$1.key" secret-key)"
}

# Starts the master here for WORKERS workers and waits until it listens (or
# fails). It gets SIGTERM if the launcher dies, even by SIGKILL (setpriv
# --pdeathsig), and then says goodbye to its workers.
launch_start_master() {
  local workers=$1 guard=() viewer=()
  command -v setpriv >/dev/null && guard=(setpriv --pdeathsig TERM --)
  [ -z "$launch_viewer_keys" ] ||
    viewer=(--viewer-listen "tcp://127.0.0.1:$launch_viewer_port" --viewer-keys "$launch_viewer_keys")
  "${guard[@]}" "$launch_build/master/igi-master" --workers 0 --listen "$launch_listen" \
    --key "$launch_dir/keys/master.key" --authorized-keys "$launch_dir/keys/workers" \
    --min-workers "$workers" --min-workers-wait "$launch_gather" "${viewer[@]}" "${master_args[@]}" \
    >"$launch_dir/master.log" 2>&1 &
  master_pid=$!
  local tries
  for ((tries = 0; tries < 200; ++tries)); do  # 20 s: loading a large scene comes first
    grep -qs "listening on" "$launch_dir/master.log" && { launch_say_viewer; return 0; }
    if ! kill -0 "$master_pid" 2>/dev/null; then
      wait "$master_pid"
      launch_say "the master did not start (exit $?):"
      tail -n 5 "$launch_dir/master.log" | sed 's/^/  /' >&2
      exit 1
    fi
    sleep 0.1
  done
}

# With --viewer-keys: how the user's own machine connects a window (the master's key is this run's).
launch_say_viewer() {
  [ -n "$launch_viewer_keys" ] || return 0
  local here port=$launch_viewer_port
  here="$(id -un)@$(launch_default_host)"
  launch_say "the window: on your machine, with your viewer key (its .pub in $launch_viewer_keys):"
  launch_say "  scp $here:$launch_dir/keys/master.pub igi-master.pub"
  launch_say "  ssh -N -L $port:127.0.0.1:$port $here &"
  launch_say "  igi-view --connect tcp://127.0.0.1:$port --key YOUR.key --master-key igi-master.pub"
}

# Records the exit status of every worker that has ended (once: bash hands
# it out once) and counts in `alive` those still running.
launch_collect() {
  local i
  alive=0
  for i in "${!worker_pids[@]}"; do
    [ -n "${worker_status[$i]:-}" ] && continue
    if kill -0 "${worker_pids[$i]}" 2>/dev/null; then
      alive=$((alive + 1))
    else
      wait "${worker_pids[$i]}" 2>/dev/null
      worker_status[$i]=$?
    fi
  done
}

# Whether a worker ended cleanly: only the master's goodbye ends one so.
launch_any_clean() { [[ " ${worker_status[*]} " == *" 0 "* ]]; }

# Waits for the master. When every worker is gone first, either one left
# cleanly (the master said goodbye: it is writing its last frames) and the
# master is waited for, or none did and the master is stopped. Then the
# workers get --grace seconds to leave, and launch_stop_workers stops the rest.
launch_wait() {
  trap 'interrupted=1; kill -TERM "$master_pid" 2>/dev/null' INT TERM
  local orphaned=0 waited i
  while kill -0 "$master_pid" 2>/dev/null; do
    launch_collect
    if [ $alive = 0 ] && [ $interrupted = 0 ] && ! launch_any_clean; then
      orphaned=1
      launch_say "every worker ended before the master finished: stopping the master"
      kill -TERM "$master_pid" 2>/dev/null
      break
    fi
    sleep 0.2
  done
  wait "$master_pid" 2>/dev/null  # (no "Killed" line from bash: the summary says it)
  master_status=$?
  for ((waited = 0; waited < launch_grace * 5; ++waited)); do
    launch_collect
    [ $alive = 0 ] && break
    sleep 0.2
  done
  for i in "${!worker_pids[@]}"; do [ -z "${worker_status[$i]:-}" ] && stopped+=("$i"); done
  launch_stop_workers
  for ((waited = 0; waited < 25; ++waited)); do
    launch_collect
    [ $alive = 0 ] && break
    sleep 0.2
  done
  for i in "${stopped[@]}"; do kill -KILL "${worker_pids[$i]}" 2>/dev/null; done
  launch_collect
  launch_summary $orphaned
}

# What a worker's exit status says. igi-worker: 0 goodbye, 2 options or keys,
# 3 refused, 4 gave up; launch_channel_explain (each launcher's own) says what
# the rest mean for ssh or srun.
launch_explain() {
  case $1 in
    0) echo "left cleanly" ;;
    2) echo "bad worker options or key files" ;;
    3) echo "refused by the master (another build or protocol version, or a key it does not know)" ;;
    4) echo "gave up: no master at tcp://$launch_master_host:$launch_port (wrong --master-host, port closed by a firewall?)" ;;
    126 | 127) echo "igi-worker not found or not executable there (the same path on every host?)" ;;
    *) launch_channel_explain "$1" ;;
  esac
}

launch_summary() {
  local orphaned=$1 i status bad=0
  for i in "${!worker_pids[@]}"; do
    status=${worker_status[$i]:-137}
    [ "$status" = 0 ] && continue
    bad=$((bad + 1))
    [ $interrupted = 1 ] && continue
    local why
    why=$(launch_explain "$status")
    if [[ " ${stopped[*]} " == *" $i "* ]]; then
      [ "$master_status" = 0 ] || continue  # the master failed: stopping its workers is expected
      why="still running $launch_grace s after the master had ended, so stopped (did it ever reach the master?)"
    fi
    launch_say "worker ${worker_names[$i]}: $why; log ${worker_logs[$i]}:"
    tail -n 3 "${worker_logs[$i]}" 2>/dev/null | sed 's/^/  /' >&2
  done
  if [ "$orphaned" = 1 ]; then
    launch_say "no worker left (run folder $launch_dir)"
    exit 3
  fi
  if [ "$master_status" != 0 ] || [ $interrupted = 1 ]; then
    launch_say "the master $([ $interrupted = 1 ] && echo "was interrupted" || echo "failed") (exit $master_status); end of $launch_dir/master.log:"
    tail -n 5 "$launch_dir/master.log" | sed 's/^/  /' >&2
    exit 1
  fi
  if [ $bad -gt 0 ]; then
    launch_say "the master finished, but not every worker ended cleanly (above)"
    exit 4
  fi
  launch_say "done: the workers left cleanly; logs in $launch_dir"
  exit 0
}
