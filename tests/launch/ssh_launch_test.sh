#!/usr/bin/env bash
# scripts/launch-ssh.sh against an sshd of our own on a loopback port: a
# throwaway host key, a throwaway client key, its own config, all in a
# temporary folder that is removed at the end (the machine's ssh setup is not
# touched). Checks that
#   - two workers started from a hosts file render frames equal, bit for bit,
#     to the single-process render, and both take part;
#   - the master and the remote workers end when the launcher is killed (-9);
#   - --viewer-keys opens the master's viewer port and prints how to connect igi-view;
#   - an unreachable host gives exit status 4 and names the host, no
#     reachable host at all gives 3, and a bad hosts file 2 with its line.
#   tests/launch/ssh_launch_test.sh BUILD-DIR
# Skips (exit 77, with the reason) where there is no sshd.
set -uo pipefail
BUILD=$(cd "${1:?usage: ssh_launch_test.sh BUILD-DIR}" && pwd)
source "$(dirname "$0")/test-lib.sh"

for program in /usr/sbin/sshd ssh ssh-keygen idiff python3; do
  command -v "$program" >/dev/null || skip "$program is missing (scripts/setup.sh installs openssh-server, openssh-client, openimageio-tools)"
done

login_shell=$(getent passwd "$(id -un)" | cut -d: -f7)
case "$login_shell" in */nologin | */false) skip "user $(id -un) cannot log in over ssh (login shell $login_shell)" ;; esac

tmp=$(mktemp -d /tmp/igi-ssh-test-XXXXXX)
sshd_pid="" launcher_pid=""
cleanup() {
  [ -n "$launcher_pid" ] && kill -KILL "$launcher_pid" 2>/dev/null
  [ -n "$sshd_pid" ] && kill -TERM "$sshd_pid" 2>/dev/null && wait "$sshd_pid" 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT

# --- an sshd on 127.0.0.1 that lets this user in with the throwaway key
ssh-keygen -q -t ed25519 -N '' -f "$tmp/host_key" -C igi-test-host || fail "ssh-keygen failed"
ssh-keygen -q -t ed25519 -N '' -f "$tmp/client_key" -C igi-test-client || fail "ssh-keygen failed"
cp "$tmp/client_key.pub" "$tmp/authorized_keys"
ssh_port=$(free_port)
user=$(id -un)
cat >"$tmp/sshd_config" <<EOF
ListenAddress 127.0.0.1
Port $ssh_port
HostKey $tmp/host_key
PidFile $tmp/sshd.pid
AuthorizedKeysFile $tmp/authorized_keys
AllowUsers $user
PermitRootLogin prohibit-password
PubkeyAuthentication yes
PasswordAuthentication no
KbdInteractiveAuthentication no
UsePAM no
StrictModes no
PrintMotd no
AcceptEnv ASAN_OPTIONS UBSAN_OPTIONS TSAN_OPTIONS
EOF
# sshd run by root wants its privilege-separation folder (the package's init script makes it).
[ "$(id -u)" = 0 ] && [ ! -d /run/sshd ] && mkdir -m 0755 /run/sshd
/usr/sbin/sshd -D -f "$tmp/sshd_config" -E "$tmp/sshd.log" &
sshd_pid=$!

cat >"$tmp/ssh_config" <<EOF
Host worker-a worker-b
  HostName 127.0.0.1
  Port $ssh_port
Host nohost
  HostName 127.0.0.1
  Port $(free_port)
Host *
  User $user
  IdentityFile $tmp/client_key
  IdentitiesOnly yes
  UserKnownHostsFile $tmp/known_hosts
  GlobalKnownHostsFile /dev/null
  StrictHostKeyChecking yes
  SendEnv ASAN_OPTIONS UBSAN_OPTIONS TSAN_OPTIONS
  LogLevel ERROR
EOF
echo "[127.0.0.1]:$ssh_port $(cat "$tmp/host_key.pub")" >"$tmp/known_hosts"
ssh_command="ssh -F $tmp/ssh_config"
if ! wait_until 10 $ssh_command -o BatchMode=yes worker-a true; then
  echo "--- sshd log:"; cat "$tmp/sshd.log"
  kill -0 "$sshd_pid" 2>/dev/null || skip "sshd did not start here (log above)"
  fail "sshd runs but does not let the test key in (log above)"
fi

# Runs the launcher against PORT with hosts file HOSTS; more launcher options, then --, then the master's.
launch() {
  local port=$1 hosts=$2
  shift 2
  scripts_launch=("$REPO/scripts/launch-ssh.sh" --hosts "$hosts" --ssh "$ssh_command" --build "$BUILD"
    --master-host 127.0.0.1 --port "$port" --listen "tcp://127.0.0.1:$port" "$@")
}
printf '# two workers of one render thread each\nworker-a 1\nworker-b 1\n' >"$tmp/hosts"

# --- two workers, three frames, equal to the single-process render
reference "$tmp/reference.exr"
mkdir -p "$tmp/frames"
port=$(free_port)
launch "$port" "$tmp/hosts" --dir "$tmp/run" -- "${RENDER[@]}" --frames $FRAMES -o "$tmp/frames/f.exr" \
  --stats "$tmp/stats.json"
start=$SECONDS
timeout -s KILL 60 "${scripts_launch[@]}" >"$tmp/launch.log" 2>&1
status=$?
cat "$tmp/launch.log"
[ $status = 0 ] || { tail -n 20 "$tmp/run/master.log" "$tmp"/run/workers/*.log; fail "the launcher exited with $status"; }
echo "launch of 2 workers and $FRAMES frames: $((SECONDS - start)) s"
check_frames "$tmp/frames/f" "$tmp/reference.exr" launch-ssh
workers=$(python3 -c 'import json, sys
frames = [line for line in map(json.loads, open(sys.argv[1])) if "frame" in line]  # JSON Lines
print(len({name for f in frames for name in f["workers"]}))' "$tmp/stats.json")
[ "$workers" = 2 ] || fail "expected both workers to render tiles, the statistics name $workers"
for log in "$tmp"/run/workers/w01-worker-a.log "$tmp"/run/workers/w02-worker-b.log; do
  grep -q "ready" "$log" || fail "$log: no sign of a worker that loaded the scene"
done
[ "$(stat -c %a "$tmp/run/keys")" = 700 ] || fail "the run's key folder is open to others"

# --- killing the launcher (-9) ends the master and the remote workers
port=$(free_port)
launch "$port" "$tmp/hosts" --dir "$tmp/run-killed" -- "${RENDER[@]}" --frames 1000000 --no-write
"${scripts_launch[@]}" >"$tmp/launch-killed.log" 2>&1 &
launcher_pid=$!
ready() { [ "$(cat "$tmp"/run-killed/workers/*.log 2>/dev/null | grep -c ready)" = 2 ]; }
wait_until 20 ready || { cat "$tmp/launch-killed.log" "$tmp"/run-killed/workers/*.log; fail "the workers did not start"; }
ours() { pgrep -f -- "tcp://127.0.0.1:$port"; }  # the master's --listen and the workers' --connect name the port
[ "$(ours | wc -l)" -ge 3 ] || fail "expected a master and two workers running, found: $(ours | xargs)"
# Sanitizer options (scripts/test-sanitizers.sh) reach the workers through ssh (SendEnv, AcceptEnv).
for var in ASAN_OPTIONS UBSAN_OPTIONS TSAN_OPTIONS; do
  [ -n "${!var:-}" ] || continue
  for pid in $(pgrep -f -- "--connect tcp://127.0.0.1:$port"); do
    tr '\0' '\n' <"/proc/$pid/environ" | grep -qxF "$var=${!var}" || fail "$var did not reach worker $pid through ssh"
  done
done
kill -KILL "$launcher_pid"
wait "$launcher_pid" 2>/dev/null
launcher_pid=""
gone() { ! ours >/dev/null; }
if ! wait_until 10 gone; then
  left=$(ours | xargs)
  ps -o pid,args -p "${left// /,}"
  kill -KILL $left 2>/dev/null
  fail "processes outlived the killed launcher: $left"
fi
echo "launcher killed: master and workers ended"

# --- the window left to a viewer (--viewer-keys): the master opens its viewer port on loopback and
# the launcher prints the three commands that connect igi-view from the user's machine
mkdir -p "$tmp/viewers" && (cd "$tmp/viewers" && "$BUILD/master/igi-keys" new laptop >/dev/null && rm laptop.key)
port=$(free_port) viewer_port=$(free_port)
launch "$port" "$tmp/hosts" --dir "$tmp/run-viewer" --viewer-keys "$tmp/viewers" --viewer-port "$viewer_port" -- \
  "${RENDER[@]}"
timeout -s KILL 8 "${scripts_launch[@]}" >"$tmp/launch-viewer.log" 2>&1
grep -q "viewer port tcp://127.0.0.1:$viewer_port" "$tmp/run-viewer/master.log" ||
  { cat "$tmp/launch-viewer.log" "$tmp/run-viewer/master.log"; fail "--viewer-keys: the master opened no viewer port"; }
for line in "scp .*:$tmp/run-viewer/keys/master.pub" "ssh -N -L $viewer_port:127.0.0.1:$viewer_port" \
            "igi-view --connect tcp://127.0.0.1:$viewer_port --key YOUR.key --master-key igi-master.pub"; do
  grep -q -- "$line" "$tmp/launch-viewer.log" || { cat "$tmp/launch-viewer.log"; fail "--viewer-keys: no '$line'"; }
done
viewer_master_gone() { ! pgrep -f -- "tcp://127.0.0.1:$viewer_port" >/dev/null; }
wait_until 10 viewer_master_gone || fail "the master outlived its launcher"
echo "window left to a viewer: port and commands printed"

# --- what the exit status says: one host unreachable (4), none reachable (3)
printf 'worker-a 1\nnohost 1\n' >"$tmp/hosts-one-bad"
port=$(free_port)
launch "$port" "$tmp/hosts-one-bad" --dir "$tmp/run-one-bad" --min-workers-wait 2 -- "${RENDER[@]}" --frames 1 -o "$tmp/one-bad.exr"
timeout -s KILL 60 "${scripts_launch[@]}" >"$tmp/one-bad.log" 2>&1
status=$?
cat "$tmp/one-bad.log"
[ $status = 4 ] || fail "one unreachable host: expected exit status 4, got $status"
grep -q "nohost.*ssh failed" "$tmp/one-bad.log" || fail "the unreachable host is not named with the reason"
printf 'nohost\n' >"$tmp/hosts-bad"
port=$(free_port)
launch "$port" "$tmp/hosts-bad" --dir "$tmp/run-bad" -- "${RENDER[@]}" --frames 1 -o "$tmp/bad.exr"
timeout -s KILL 60 "${scripts_launch[@]}" >"$tmp/bad.log" 2>&1
status=$?
cat "$tmp/bad.log"
[ $status = 3 ] || fail "no reachable host: expected exit status 3, got $status"

# --- a bad hosts file: exit 2, the file and line named, nothing started
printf 'worker-a 1\nworker-b one\n' >"$tmp/hosts-typo"
launch "$(free_port)" "$tmp/hosts-typo" --dir "$tmp/run-typo" -- "${RENDER[@]}" --frames 1 -o "$tmp/typo.exr"
"${scripts_launch[@]}" >"$tmp/typo.log" 2>&1
status=$?
cat "$tmp/typo.log"
[ $status = 2 ] || fail "a bad hosts file: expected exit status 2, got $status"
grep -q "hosts-typo:2: expected 'HOST \[THREADS\]'" "$tmp/typo.log" || fail "the bad line is not named"
[ ! -e "$tmp/run-typo" ] || fail "a run folder was made for a launch that did not start"

# --- an option under igi-master's other name: exit 2, the name to use given
launch "$(free_port)" "$tmp/hosts-typo" --dir "$tmp/run-old" --wait-workers 2 -- "${RENDER[@]}" --frames 1 -o "$tmp/old.exr"
"${scripts_launch[@]}" >"$tmp/old.log" 2>&1
status=$?
[ $status = 2 ] || fail "--wait-workers: expected exit status 2, got $status"
grep -q -- "--min-workers-wait" "$tmp/old.log" || fail "--wait-workers: the error does not name --min-workers-wait"
echo "PASS"
