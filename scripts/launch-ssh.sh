#!/usr/bin/env bash
# Renders on machines reached by ssh: starts igi-master here and one igi-worker
# per line of a hosts file, which dials back to the master (see
# scripts/lib/launch-common.sh for the exit statuses).
#   scripts/launch-ssh.sh --hosts hosts.txt --master-host HEAD [options] -- IGI-MASTER-OPTIONS
#
# Keys: a fresh CURVE key pair for the master and for each worker, made in
# DIR/keys; a worker's secret key and the master's public key reach it through
# ssh's standard input (never its command line or disk). What is left of that
# standard input is the worker's lifeline: when the launcher ends (however: a
# normal end, Ctrl-C, kill -9) or the ssh connection drops, the remote side
# sees end of file and stops the worker.
set -uo pipefail
LAUNCH_NAME=launch-ssh.sh
source "$(dirname "$0")/lib/launch-common.sh"

usage() {
  cat <<EOF
usage: scripts/launch-ssh.sh --hosts FILE [options] -- IGI-MASTER-OPTIONS
Starts igi-master here and an igi-worker on every host of FILE through ssh; the
workers connect back to the master, CURVE-authenticated with keys made for the run.
  --hosts FILE         one worker a line: HOST [THREADS] (THREADS 0 or absent: all cores);
                       HOST is anything ssh takes (user@host, an alias of ~/.ssh/config);
                       a host listed twice runs two workers; # starts a comment
  --ssh "COMMAND"      how to reach a host, split at spaces [ssh]; the launcher adds
                       -T -o BatchMode=yes -o ConnectTimeout=10 -o ServerAliveInterval=10
  --remote-worker PATH igi-worker on the hosts [the one in --build: a shared file system]
$(launch_common_usage)
Example:
  scripts/launch-ssh.sh --hosts hosts.txt --master-host head.cluster -- \\
      --scene scene.glb --method igi --frames 100 --camera-path orbit -o frames.exr
EOF
}

hosts_file="" ssh_command=ssh remote_worker=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --) shift; master_args=("$@"); break ;;
    --hosts | --ssh | --remote-worker)
      [ $# -ge 2 ] || launch_fail "$1: missing value"
      case "$1" in
        --hosts) hosts_file=$2 ;;
        --ssh) ssh_command=$2 ;;
        --remote-worker) remote_worker=$2 ;;
      esac
      shift 2 ;;
    *)
      launch_parse_common "$@"
      [ "$shift_by" -gt 0 ] || launch_fail "unknown option '$1'"
      shift "$shift_by" ;;
  esac
done

# The hosts file: names and thread counts, checked before anything starts.
hosts=() threads=()
[ -n "$hosts_file" ] || launch_fail "--hosts FILE is required"
[ -r "$hosts_file" ] || launch_fail "--hosts $hosts_file: cannot read it"
line_number=0
while IFS= read -r line || [ -n "$line" ]; do
  line_number=$((line_number + 1))
  line=${line%%#*}
  read -ra words <<<"$line"
  [ ${#words[@]} -eq 0 ] && continue
  if [ ${#words[@]} -gt 2 ] || { [ ${#words[@]} = 2 ] && ! [[ "${words[1]}" =~ ^[0-9]+$ ]]; } ||
    [[ "${words[0]}" == -* ]]; then
    launch_fail "$hosts_file:$line_number: expected 'HOST [THREADS]', got '${line}'"
  fi
  hosts+=("${words[0]}")
  threads+=("${words[1]:-0}")
done <"$hosts_file"
[ ${#hosts[@]} -gt 0 ] || launch_fail "$hosts_file: no hosts (one a line: HOST [THREADS])"
read -ra ssh_words <<<"$ssh_command"
[ ${#ssh_words[@]} -gt 0 ] || launch_fail "--ssh: empty command"
launch_check_common
[ -n "$remote_worker" ] || remote_worker="$launch_build/worker/igi-worker"

# Runs on the host under sh: reads the two key lines, starts the worker with
# them on descriptor 4, and stops it when the rest of standard input ends.
# $0 is igi-worker, "$@" its options.
remote_script='IFS= read -r server_key && IFS= read -r secret_key || { echo "igi-worker launch: no keys from the launcher" >&2; exit 2; }
"$0" --curve-fd 4 "$@" 4<<IGI_KEYS &
$server_key
$secret_key
IGI_KEYS
worker=$!
server_key= secret_key=
exec 3<&0
(cat <&3 >/dev/null 2>&1; kill -TERM $worker 2>/dev/null) >/dev/null 2>&1 &
watcher=$!
exec 3<&- 0</dev/null
wait $worker
status=$?
kill $watcher 2>/dev/null
exit $status'

# One word for the remote shell: single quotes, with ' written as '\''.
quote() { printf "'%s'" "${1//\'/\'\\\'\'}"; }

names=()
for i in "${!hosts[@]}"; do names+=("$(printf 'w%02d-%s' $((i + 1)) "${hosts[$i]//[^A-Za-z0-9._-]/_}")"); done
launch_make_keys "${names[@]}"
launch_start_master ${#hosts[@]}
endpoint="tcp://$launch_master_host:$launch_port"
launch_say "master on $launch_listen (pid $master_pid); workers dial $endpoint; logs in $launch_dir"

# Every ssh is started before any lifeline is opened, so none inherits
# another's: each lifeline's write end is held by this shell alone.
mkdir -p "$launch_dir/run"
for i in "${!hosts[@]}"; do
  remote="sh -c $(quote "$remote_script") $(quote "$remote_worker") --connect $(quote "$endpoint") --threads ${threads[$i]}"
  for arg in "${launch_worker_args[@]}"; do remote+=" $(quote "$arg")"; done
  fifo="$launch_dir/run/${names[$i]}.in"
  mkfifo "$fifo"
  "${ssh_words[@]}" -T -o BatchMode=yes -o ConnectTimeout=10 -o ServerAliveInterval=10 -o ServerAliveCountMax=3 \
    "${hosts[$i]}" "$remote" <"$fifo" >"$launch_dir/workers/${names[$i]}.log" 2>&1 &
  worker_pids+=($!)
  worker_names+=("${names[$i]} (${hosts[$i]})")
  worker_logs+=("$launch_dir/workers/${names[$i]}.log")
done
lifelines=()
for i in "${!hosts[@]}"; do
  exec {fd}>"$launch_dir/run/${names[$i]}.in"
  lifelines+=("$fd")
  (trap '' PIPE; launch_worker_keys "${names[$i]}" >&"$fd") 2>/dev/null  # an ssh already gone is reported later
done
rm -rf "$launch_dir/run"

launch_channel_explain() {
  case $1 in
    255) echo "ssh failed: host unreachable, login refused, or an unknown host key" ;;
    143) echo "stopped: its ssh connection or the launcher went away" ;;
    *) echo "exit $1" ;;
  esac
}
launch_stop_workers() {
  local fd
  for fd in "${lifelines[@]}"; do exec {fd}>&-; done
  lifelines=()
}
launch_wait
