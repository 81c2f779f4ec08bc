#!/usr/bin/env bash
# Run a study as a Slurm job array on a real (one-node, loopback-only) Slurm and
# check the merged file against a single-process run, bit for bit.
#
# - installs Debian's slurmctld, slurmd and munge if missing (apt-get; idempotent; needs root
#   or sudo);
# - writes a private munge key and a minimal slurm.conf into a temporary folder (state, spool,
#   logs, sockets all there; nothing in /etc is changed) for one node `localhost` at 127.0.0.1
#   with this machine's CPU count, no accounting, proctrack/linuxproc, task/none;
# - starts munged, slurmctld and slurmd (listening on 127.0.0.1 only: NoInAddrAny);
# - `batstudy slurm studies/smoke.yaml --shards 4`, then the generated submit.sh with one
#   task that cannot finish: the merge must run after the array and refuse; then
#   `batstudy slurm --resubmit` submits that shard alone and the merge again;
# - waits (bounded) for the jobs, runs the study in one process, compares every dataset with
#   scripts/compare_results.py;
# - always stops its daemons (trap), and prints one PASS/FAIL line.
#
# Environment: BATSTUDY_BIN (default: cargo build, target/debug/batstudy),
# SLURM_TEST_TIMEOUT (seconds to wait for the jobs, default 240), SLURM_TEST_KEEP=1 keeps the
# temporary folder, SLURM_TEST_PORT (slurmctld port, default 16817; slurmd uses +1).
set -uo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
timeout_s=${SLURM_TEST_TIMEOUT:-240}
port=${SLURM_TEST_PORT:-16817}
t0=$(date +%s)

say() { echo "slurm-local-test: $*"; }
fail() {
  say "$*"
  echo "FAIL: slurm-local-test: $*"
  exit 1
}
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

# ---- packages
need=()
for pkg in slurmctld slurmd munge; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || need+=("$pkg")
done
if ((${#need[@]})); then
  say "installing Debian packages: ${need[*]}"
  as_root apt-get update -qq || fail "apt-get update failed"
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null ||
    fail "apt-get install ${need[*]} failed"
fi
[ "$(id -u)" = 0 ] || fail "must run as root (slurmd runs jobs as their user and needs root)"

# ---- batstudy
if [ -z "${BATSTUDY_BIN:-}" ]; then
  cargo build -q || fail "cargo build failed"
  BATSTUDY_BIN=$repo/target/debug/batstudy
fi
bin=$(readlink -f "$BATSTUDY_BIN")
[ -x "$bin" ] || fail "no batstudy binary at $BATSTUDY_BIN"
py=python3
[ -x "$repo/.venv/bin/python" ] && py=$repo/.venv/bin/python
"$py" -c "import h5py" 2>/dev/null || fail "$py has no h5py (run scripts/setup.sh)"

say "packages and binary ready in $(($(date +%s) - t0)) s"

# ---- private cluster
work=$(mktemp -d /tmp/batstudy-slurm.XXXXXX)
chmod 755 "$work"
mkdir -p "$work"/{munge,ctld,spool,log,run,jobs}
pids=()
cleanup() {
  local rc=$?
  if [ -n "${SLURM_CONF:-}" ] && [ -f "$SLURM_CONF" ]; then
    scancel --quiet --user=root >/dev/null 2>&1 || true
    sleep 1
  fi
  # stop the daemons this script started, by pid, newest first
  for ((k = ${#pids[@]} - 1; k >= 0; k--)); do
    kill "${pids[k]}" 2>/dev/null || true
  done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$p" 2>/dev/null || true
  done
  wait 2>/dev/null
  if [ "${SLURM_TEST_KEEP:-0}" = 1 ] || [ "$rc" != 0 ]; then
    say "logs and files kept in $work"
  else
    rm -rf "$work"
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

cpus=$(nproc)
# munge: a private key, socket, pid and log
dd if=/dev/urandom of="$work/munge/munge.key" bs=1 count=1024 status=none
chmod 700 "$work/munge"
chmod 400 "$work/munge/munge.key"
sock=$work/munge/munge.socket
munged -F --force --socket="$sock" --key-file="$work/munge/munge.key" \
  --log-file="$work/log/munged.log" --pid-file="$work/run/munged.pid" \
  --seed-file="$work/munge/munged.seed" --origin=127.0.0.1 >"$work/log/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$sock" ] && break; sleep 0.1; done
[ -S "$sock" ] || fail "munged did not start: $(tail -3 "$work/log/munged.log" 2>/dev/null)"

export SLURM_CONF=$work/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=batstudytest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
CommunicationParameters=NoCtldInAddrAny,NoInAddrAny
StateSaveLocation=$work/ctld
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=$cpus State=UNKNOWN
PartitionName=batstudy Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
: >"$work/cgroup.conf"

slurmctld -D -c -f "$SLURM_CONF" >"$work/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" >"$work/log/slurmd.out" 2>&1 &
pids+=($!)

# wait until the node is idle
state=""
for _ in $(seq 60); do
  state=$(sinfo -h -n localhost -o %T 2>/dev/null | head -1)
  [ "$state" = idle ] && break
  sleep 0.5
done
if [ "$state" != idle ]; then
  tail -5 "$work/log/slurmctld.log" "$work/log/slurmd.log" 2>/dev/null
  fail "the node did not become idle (state '$state'); logs in $work/log"
fi
say "one-node Slurm up on 127.0.0.1:$port ($cpus CPUs) in $(($(date +%s) - t0)) s"
if command -v ss >/dev/null; then
  ss -ltn 2>/dev/null | awk -v a="$port" -v b="$((port + 1))" \
    '$4 ~ ":"a"$" || $4 ~ ":"b"$" {print "slurm-local-test: listening " $4}'
fi

# ---- the array and the merge, with one task that cannot finish: a folder where
# shard 3's lock file goes makes its run fail (exit 3); the merge must run after the array
# anyway (afterany) and refuse the incomplete set; `batstudy slurm --resubmit` must then
# submit shard 3 alone, and the merge again.
study=$repo/studies/smoke.yaml
"$bin" slurm "$study" --shards 4 --cpus-per-task 1 --time 00:10:00 \
  --dir "$work/jobs" -o "$work/merged.h5" >"$work/log/slurm-cmd.out" ||
  fail "batstudy slurm failed: $(cat "$work/log/slurm-cmd.out")"
mkdir -p "$work/jobs/smoke.shard-3-of-4.h5.lock"
bash "$work/jobs/submit.sh" >"$work/log/submit-1.out" || fail "submit.sh failed"
# shellcheck disable=SC1091
. "$work/jobs/jobs.env"
say "array job $ARRAY_JOB_ID, merge job $MERGE_JOB_ID (shard 3 cannot finish)"

job_state() { scontrol show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 | sort -u | tr '\n' ' '; }
# wait_ended JOB: until the job has ended; prints its states
wait_ended() {
  local deadline=$(($(date +%s) + timeout_s)) st
  while :; do
    st=$(job_state "$1")
    case "$st" in
      *PENDING* | *RUNNING* | *CONFIGURING* | *COMPLETING* | "") ;;
      *) echo "$st"; return 0 ;;
    esac
    if [ "$(date +%s)" -ge "$deadline" ]; then
      squeue 2>/dev/null
      fail "timeout after ${timeout_s}s waiting for job $1 ($st)"
    fi
    sleep 1
  done
}
ms=$(wait_ended "$MERGE_JOB_ID")
[ "$ms" = "FAILED " ] || fail "the first merge ended '$ms', expected FAILED (an incomplete set)"
grep -q "shards 3" "$work/jobs/logs/merge.out" && grep -q -- "--resubmit" "$work/jobs/logs/merge.out" ||
  fail "the merge did not name the unfinished shard and the command: $(cat "$work/jobs/logs/merge.out")"
[ ! -e "$work/merged.h5" ] || fail "an incomplete set was merged"
say "first submission: shard 3 failed, the merge ran after the array and refused ($(($(date +%s) - t0)) s)"

rmdir "$work/jobs/smoke.shard-3-of-4.h5.lock"
"$bin" slurm --resubmit "$work/jobs" >"$work/log/submit-2.out" || fail "slurm --resubmit failed: $(cat "$work/log/submit-2.out")"
grep -q "shards 3 of 4" "$work/log/submit-2.out" || fail "--resubmit did not submit shard 3 alone: $(cat "$work/log/submit-2.out")"
# shellcheck disable=SC1091
. "$work/jobs/jobs.env"
ms=$(wait_ended "$MERGE_JOB_ID")
[ "$ms" = "COMPLETED " ] || { tail -20 "$work/jobs/logs/"*.out; fail "the second merge ended '$ms'"; }
as=$(wait_ended "$ARRAY_JOB_ID")
[ "$as" = "COMPLETED " ] || fail "the resubmitted task ended $as"
say "resubmission: shard 3 resubmitted alone, merged in $(($(date +%s) - t0)) s"
for i in 1 2 3 4; do
  [ -f "$work/jobs/smoke.shard-$i-of-4.h5" ] || fail "shard file $i missing"
done

# ---- single-process reference and comparison
"$bin" run "$study" -o "$work/single.h5" --jobs "$cpus" --quiet || fail "single-process run failed"
"$py" "$repo/scripts/compare_results.py" "$work/single.h5" "$work/merged.h5" ||
  fail "merged file differs from the single-process run"
echo "PASS: slurm-local-test: 4-shard Slurm array, a failed task resubmitted, merge == single-process run, bit for bit ($(($(date +%s) - t0)) s)"
