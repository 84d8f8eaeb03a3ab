#!/usr/bin/env bash
# A real Slurm test of scripts/slurm-render.sh on this machine: starts munge and a one-node
# Slurm cluster (slurmctld + slurmd, Debian's slurm-wlm and munge) configured in a temporary
# folder, as root or not, submits graphs/underwater.json at a small size in 4 chunks, waits for
# the final check job, compares every frame with a local render of the same range (they must
# match: a frame does not depend on how the range was cut), and stops the daemons it started.
#
#   scripts/slurm-test.sh            (after scripts/build.sh; exit 0 when everything matched)
#
# Nothing outside the temporary folder is touched: its own munge key and socket, its own
# ports, its own state and spool folders. KEEP=1 keeps the folder for reading the logs.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"
aquarelle="${AQUARELLE:-$repo/build/app/aquarelle}"
frames="1-8" chunk=2 size="96x54"

fail() {
  echo "slurm-test: FAIL: $*" >&2
  exit 1
}
for tool in munged slurmctld slurmd sbatch scontrol iinfo idiff; do
  command -v "$tool" >/dev/null || PATH="$PATH:/usr/sbin" command -v "$tool" >/dev/null ||
    fail "$tool not found: apt-get install slurm-wlm munge openimageio-tools"
done
export PATH="$PATH:/usr/sbin"
[ -x "$aquarelle" ] || fail "no $aquarelle: build first (scripts/build.sh)"

work="$(mktemp -d /tmp/aq-slurm-test.XXXXXX)"
chmod 755 "$work"
pids=()
cleanup() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ "${KEEP:-0}" = 1 ] || [ $status -ne 0 ]; then
    echo "slurm-test: logs kept in $work" >&2
  else
    rm -rf "$work"
  fi
  exit $status
}
trap cleanup EXIT INT TERM

# Free TCP ports for slurmctld and slurmd, so concurrent runs do not collide.
free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'
}
ctld_port=$(free_port)
slurmd_port=$(free_port)
user="$(id -un)"
node="$(hostname -s)"
cpus="$(nproc)"
mkdir -p "$work"/{munge,state,spool,log,out,local}
chmod 700 "$work/munge"

# munge: a fresh key, its own socket.
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --foreground --force --socket="$work/munge/munge.socket" \
  --key-file="$work/munge/munge.key" --pid-file="$work/munge/munged.pid" \
  --log-file="$work/log/munged.log" --seed-file="$work/munge/munged.seed" \
  >"$work/log/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$work/munge/munge.socket" ] && break; sleep 0.1; done
[ -S "$work/munge/munge.socket" ] || fail "munged did not start (see $work/log/munged.log)"

cat >"$work/slurm.conf" <<EOF
ClusterName=aqtest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=60
InactiveLimit=0
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
EOF
export SLURM_CONF="$work/slurm.conf"

slurmctld -D -i -f "$SLURM_CONF" >"$work/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" >"$work/log/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  state=$(sinfo -h -N -o '%t' 2>/dev/null | head -1 || true)
  [[ "$state" == idle* ]] && break
  sleep 0.2
done
[[ "${state:-}" == idle* ]] || fail "the node did not come up (state '${state:-none}'; see $work/log)"
echo "slurm-test: cluster up ($node, $cpus CPUs, ports $ctld_port/$slurmd_port)"

job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1; }
# Submits the range and waits for its check job; sets render_job, check_job and state.
submit_and_wait() {
  AQUARELLE="$aquarelle" scripts/slurm-render.sh graphs/underwater.json "$work/out/####.exr" \
    --frames "$frames" --chunk "$chunk" -- --size "$size" --float
  read -r render_job check_job <"$work/out/slurm-logs/last-submission"
  for _ in $(seq 900); do
    state="$(job_state "$check_job")"
    case "$state" in COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL) break ;; esac
    sleep 0.2
  done
}

start=$SECONDS
# The local render of the same range runs while the cluster works.
"$aquarelle" render graphs/underwater.json -o "$work/local/####.exr" --frames "$frames" \
  --size "$size" --float -q &
local_render=$!
submit_and_wait
wait "$local_render" || fail "the local render failed"
echo "slurm-test: check job $check_job $state after $((SECONDS - start)) s"
cat "$work/out/slurm-logs/check-$check_job.log"
[ "$state" = COMPLETED ] || fail "the check job ended $state (logs in $work/out/slurm-logs)"
tasks=$(ls "$work/out/slurm-logs/render-${render_job}_"*.log | wc -l)
[ "$tasks" -eq 4 ] || fail "expected 4 task logs, found $tasks"

first="${frames%-*}" last="${frames#*-}"
for ((frame = first; frame <= last; ++frame)); do
  name=$(printf '%04d.exr' "$frame")
  idiff -fail 0 -failpercent 0 "$work/local/$name" "$work/out/$name" >/dev/null ||
    fail "frame $frame rendered by Slurm differs from the local render"
done
echo "slurm-test: $tasks tasks rendered frames $frames, each identical to the local render"

# A lost frame: the check names it, and the same submission again renders only that frame.
rm "$work/out/0005.exr"
before=$(stat -c %Y.%N "$work/out/0001.exr" "$work/out/0008.exr")
check_script=$(ls "$work/out/slurm-logs/"check-*.sbatch | head -1)
if report=$("$check_script"); then fail "the check passed with frame 5 missing"; fi
grep -q "^  5 (no file .*0005.exr)" <<<"$report" || fail "the check did not name frame 5: $report"
sleep 1  # a re-rendered frame would get a later modification time
submit_and_wait
[ "$state" = COMPLETED ] || fail "the re-submission's check ended $state"
[ -s "$work/out/0005.exr" ] || fail "the re-submission did not render frame 5"
[ "$before" = "$(stat -c %Y.%N "$work/out/0001.exr" "$work/out/0008.exr")" ] ||
  fail "the re-submission rendered frames that were already there"
idiff -fail 0 -failpercent 0 "$work/local/0005.exr" "$work/out/0005.exr" >/dev/null ||
  fail "the re-rendered frame 5 differs from the local render"
echo "slurm-test: PASS in $((SECONDS - start)) s: 4 chunks match the local render; a lost frame is named by the check and re-rendered alone"
