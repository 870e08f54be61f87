#!/usr/bin/env bash
# scripts/slurm/ on a real single-node Slurm cluster: Debian's munge and slurm-wlm, configured for
# this host under a temporary folder (munge key, slurm.conf, state, spool, logs, free localhost
# ports), the daemons started as root and detached (setsid, output to files), submit.sh's 4-task
# array of `glintlab verify --budget quick` on six claims and its merge job, then the merged
# claims.{json,csv,md} byte-compared with one unsharded run apart from the timing fields; then a
# 3-task array of `glintlab figure --budget quick` on three cheap figures and its merge, the merged
# folders byte-compared with one run (these figures have no timing field).
# Negative controls: the same comparisons must tell the first shard's files alone from the single
# run, and a broken run (an unknown budget) must fail its tasks and never run its merge.
#
# Usage: single_node_cluster_test.sh GLINTLAB. Exit 0 pass, 1 fail, 77 skip (ctest
# SKIP_RETURN_CODE) when the cluster cannot run here: not root, a package missing, or a daemon
# that does not start or become ready (the reason and the daemons' last log lines are printed).
# Every daemon started is stopped by its pid on exit, whatever happens; the test gives up on its
# own after DEADLINE seconds, well inside ctest's TIMEOUT, so that its trap always runs.
set -uo pipefail

GLINTLAB=${1:?usage: single_node_cluster_test.sh GLINTLAB}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SUBMIT=$HERE/../../scripts/slurm/submit.sh
DEADLINE=${DEADLINE:-240}   # seconds for the whole test (ctest's TIMEOUT is 290)
READY_SECONDS=60            # for the daemons to answer
# The six quick claims of tests/cli/shard_merge_test.cpp, three of them with p-values, so that
# the suite's adjustment spans shards.
CLAIMS="kemppinen.furnace,kemppinen.roulette,kneiphof.subdivision,eto.backfacing-stable-pdf,kneiphof.cap-probability,podee.brightest-vector"
SHARDS=4
# Three quick figures of tests/cli/figure_shard_test.cpp, about 0.1 s of CPU each: one per shard.
FIGURES="kneiphof2024-fig6,kemppinen2025-fig6,kemppinen2025-fig14"
FIGURE_SHARDS=3
start=$SECONDS

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
left() { echo $((DEADLINE - (SECONDS - start))); }

[ "$(id -u)" -eq 0 ] || skip "the daemons must run as root (uid $(id -u))"
for tool in munged slurmctld slurmd sbatch squeue scontrol sinfo scancel; do
  command -v "$tool" > /dev/null || skip "$tool not installed (scripts/setup.sh installs munge and slurm-wlm)"
done
[ -x "$GLINTLAB" ] || fail "no glintlab executable at '$GLINTLAB'"
GLINTLAB=$(cd "$(dirname "$GLINTLAB")" && pwd)/$(basename "$GLINTLAB")

WORK=$(mktemp -d /tmp/glintlab-slurm.XXXXXX)
# munged wants its socket's folders searchable by every user (clients of any user reach it) and
# writable by none but root.
chmod 0755 "$WORK"
pids=()
cleanup() {
  local status=$?
  trap - EXIT INT TERM HUP
  # Jobs first (their steps outlive slurmd), then the daemons, each by the pid recorded at start.
  if [ -f "$WORK/slurm.conf" ] && [ ${#pids[@]} -gt 0 ]; then
    SLURM_CONF=$WORK/slurm.conf timeout 10 scancel --quiet --user=root > /dev/null 2>&1
  fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill -TERM "${pids[i]}" 2> /dev/null; done
  for _ in $(seq 50); do
    local alive=0
    for p in "${pids[@]}"; do kill -0 "$p" 2> /dev/null && alive=1; done
    [ $alive -eq 0 ] && break
    sleep 0.2
  done
  for p in "${pids[@]}"; do kill -KILL "$p" 2> /dev/null; done
  rm -rf "$WORK"
  exit $status
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

# The daemons' last log lines, printed with a skip or failure.
logs() {
  for f in "$WORK"/log/*; do
    [ -s "$f" ] || continue
    echo "--- last lines of $(basename "$f")"
    tail -n 8 "$f"
  done
}
started() {  # NAME PID: still running half a second after the start?
  sleep 0.5
  kill -0 "$2" 2> /dev/null || { logs; skip "$1 did not start"; }
}

# The unsharded run the cluster's merge must reproduce: 1 thread, as each array task.
timeout "$(left)" "$GLINTLAB" verify --claims "$CLAIMS" --budget quick --threads 1 \
  --out "$WORK/one" > "$WORK/one.txt" 2>&1 || { cat "$WORK/one.txt"; fail "the single run failed"; }
timeout "$(left)" "$GLINTLAB" figure "$FIGURES" --budget quick --threads 1 \
  --out "$WORK/figures-one" > "$WORK/figures-one.txt" 2>&1 ||
  { cat "$WORK/figures-one.txt"; fail "the single figure run failed"; }

mkdir -p "$WORK/munge" "$WORK/log" "$WORK/state" "$WORK/spool" "$WORK/run"
chmod 0755 "$WORK/munge"
# A munge key: 1024 random bytes, owned by the daemon's user (root) and readable by it only.
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 0400 "$WORK/munge/munge.key"
MUNGE_SOCKET=$WORK/munge/munge.socket
setsid munged --foreground --socket="$MUNGE_SOCKET" --key-file="$WORK/munge/munge.key" \
  --pid-file="$WORK/munge/munged.pid" --log-file="$WORK/log/munged.log" \
  --seed-file="$WORK/munge/munged.seed" < /dev/null > "$WORK/log/munged.out" 2>&1 &
pids+=($!)
started munged "${pids[-1]}"

# Two free localhost ports (bound and released by the kernel's choice).
read -r CTLD_PORT SLURMD_PORT < <(/usr/bin/python3 -c '
import socket
socks = [socket.socket() for _ in range(2)]
for s in socks: s.bind(("127.0.0.1", 0))
print(*(s.getsockname()[1] for s in socks))')
HOST=$(hostname -s)
# This host's NodeName line as slurmd sees it (CPUs, sockets, cores, memory), on localhost.
NODE=$(slurmd -C 2> /dev/null | grep '^NodeName=')
[ -n "$NODE" ] || skip "slurmd -C reports no NodeName line"
NODE=$(echo "$NODE" | sed "s/^NodeName=[^ ]*/NodeName=$HOST NodeAddr=127.0.0.1/")
cat > "$WORK/slurm.conf" <<EOF
ClusterName=glintlabtest
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCKET
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/run/slurmctld.pid
SlurmdPidFile=$WORK/run/slurmd.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=600
SchedulerParameters=sched_interval=2
$NODE State=UNKNOWN
PartitionName=test Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$WORK/slurm.conf

setsid slurmctld -D -i -f "$SLURM_CONF" < /dev/null > "$WORK/log/slurmctld.out" 2>&1 &
pids+=($!)
started slurmctld "${pids[-1]}"
setsid slurmd -D -f "$SLURM_CONF" < /dev/null > "$WORK/log/slurmd.out" 2>&1 &
pids+=($!)
started slurmd "${pids[-1]}"

# Ready: the controller answers and the node is idle.
ready=0
for _ in $(seq $((READY_SECONDS * 2))); do
  if timeout 5 scontrol ping 2> /dev/null | grep -q 'is UP' &&
     [ "$(timeout 5 sinfo -h -n "$HOST" -o '%t' 2> /dev/null)" = idle ]; then
    ready=1; break
  fi
  for p in "${pids[@]}"; do kill -0 "$p" 2> /dev/null || { logs; skip "a daemon (pid $p) exited"; }; done
  sleep 0.5
done
if [ $ready -ne 1 ]; then
  timeout 5 sinfo 2>&1
  logs
  skip "the cluster was not ready within ${READY_SECONDS} s"
fi
echo "cluster ready after $((SECONDS - start)) s (controller port $CTLD_PORT, slurmd port $SLURMD_PORT)"

ids=$(GLINTLAB=$GLINTLAB CLAIMS=$CLAIMS BUDGET=quick SHARDS=$SHARDS THREADS=1 OUT=$WORK/run1 \
        PARTITION=test timeout 30 "$SUBMIT") || { echo "$ids"; logs; fail "submit.sh failed"; }
echo "$ids"
array_id=$(echo "$ids" | sed -n 's/^array \([0-9][0-9]*\)$/\1/p')
merge_id=$(echo "$ids" | sed -n 's/^merge \([0-9][0-9]*\)$/\1/p')
[ -n "$array_id" ] && [ -n "$merge_id" ] || fail "submit.sh printed no 'array ID' and 'merge ID' lines"

# Wait until no job of the two is pending or running; MinJobAge keeps the ended ones in view.
while [ -n "$(timeout 5 squeue -h -j "$array_id,$merge_id" -t PENDING,RUNNING,CONFIGURING,COMPLETING -o %i 2>&1)" ]; do
  [ "$(left)" -gt 15 ] || { timeout 5 squeue; logs; fail "the jobs did not end within the test's ${DEADLINE} s"; }
  sleep 1
done
# Every array task and the merge completed (exit 0:0).
states=$(timeout 5 squeue -h -j "$array_id,$merge_id" -t all -o '%i %T' 2>&1)
echo "$states"
tasks=$(echo "$states" | grep -c "^${array_id}_[0-9]* COMPLETED$")
[ "$tasks" -eq $SHARDS ] || { cat "$WORK"/run1/logs/* 2> /dev/null; logs; fail "$tasks of $SHARDS array tasks completed"; }
echo "$states" | grep -q "^$merge_id COMPLETED$" ||
  { timeout 5 scontrol show job "$merge_id"; cat "$WORK"/run1/logs/* 2> /dev/null; fail "the merge job did not complete"; }
echo "jobs ended after $((SECONDS - start)) s"

# The timing fields blanked as in tests/cli/shard_merge_test.cpp (without_timing).
. "$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")/../scale_out/claims_without_timing.sh"
same_as_one() {  # FOLDER: its claims.{json,csv,md} are the single run's apart from timing?
  for f in claims.json claims.csv claims.md; do
    [ -f "$1/$f" ] || return 1
    cmp -s <(without_timing "$1/$f") <(without_timing "$WORK/one/$f") || return 1
  done
}
for f in claims.json claims.csv claims.md; do
  [ -f "$WORK/run1/verify/$f" ] || fail "the merge wrote no $f"
  if ! cmp -s <(without_timing "$WORK/run1/verify/$f") <(without_timing "$WORK/one/$f"); then
    diff <(without_timing "$WORK/one/$f") <(without_timing "$WORK/run1/verify/$f") | head -n 20
    fail "merged $f differs from the single run's"
  fi
done
# Negative control: the first shard's own files (a quarter of the rows, adjusted over those
# only) must be told apart by the same comparison.
if same_as_one "$WORK/run1/shards/1"; then
  fail "negative control: shard 1's files pass as the single run's; the comparison is blind"
fi
echo "merged claims.{json,csv,md} are the single run's bytes apart from timing; shard 1 alone is not"

# A broken run: an unknown budget fails every task (verify's exit 2), and the merge, whose
# dependency can no longer be met, is cancelled without running.
ids=$(GLINTLAB=$GLINTLAB CLAIMS=$CLAIMS BUDGET=no-such-budget SHARDS=2 THREADS=1 OUT=$WORK/run2 \
        PARTITION=test timeout 30 "$SUBMIT") || { echo "$ids"; fail "submit.sh failed"; }
array_id=$(echo "$ids" | sed -n 's/^array \([0-9][0-9]*\)$/\1/p')
merge_id=$(echo "$ids" | sed -n 's/^merge \([0-9][0-9]*\)$/\1/p')
while [ -n "$(timeout 5 squeue -h -j "$array_id,$merge_id" -t PENDING,RUNNING,CONFIGURING,COMPLETING -o %i 2>&1)" ]; do
  [ "$(left)" -gt 15 ] || { timeout 5 squeue; fail "the broken run's jobs did not end within the test's ${DEADLINE} s"; }
  sleep 1
done
states=$(timeout 5 squeue -h -j "$array_id,$merge_id" -t all -o '%i %T' 2>&1)
echo "$states"
[ "$(echo "$states" | grep -c "^${array_id}_[0-9]* FAILED$")" -eq 2 ] || fail "the broken run's tasks did not fail"
echo "$states" | grep -q "^$merge_id CANCELLED$" || fail "the broken run's merge was not cancelled"
[ ! -e "$WORK/run2/verify" ] || fail "the broken run's merge wrote $WORK/run2/verify"
echo "a broken run fails its tasks and its merge never runs"

# Figures: submit.sh with SUBCOMMAND=figure, one figure per task; the merge writes
# OUT/figure/<id>/ for each, the single run's folders byte for byte.
ids=$(GLINTLAB=$GLINTLAB SUBCOMMAND=figure FIGURES=$FIGURES BUDGET=quick SHARDS=$FIGURE_SHARDS \
        THREADS=1 OUT=$WORK/run3 PARTITION=test timeout 30 "$SUBMIT") || { echo "$ids"; fail "submit.sh failed"; }
echo "$ids"
array_id=$(echo "$ids" | sed -n 's/^array \([0-9][0-9]*\)$/\1/p')
merge_id=$(echo "$ids" | sed -n 's/^merge \([0-9][0-9]*\)$/\1/p')
[ -n "$array_id" ] || fail "submit.sh printed no 'array ID' line for the figures"
[ -n "$merge_id" ] || fail "submit.sh printed no 'merge ID' line for the figures"
while [ -n "$(timeout 5 squeue -h -j "$array_id,$merge_id" -t PENDING,RUNNING,CONFIGURING,COMPLETING -o %i 2>&1)" ]; do
  [ "$(left)" -gt 15 ] || { timeout 5 squeue; logs; fail "the figure jobs did not end within the test's ${DEADLINE} s"; }
  sleep 1
done
states=$(timeout 5 squeue -h -j "$array_id,$merge_id" -t all -o '%i %T' 2>&1)
echo "$states"
tasks=$(echo "$states" | grep -c "^${array_id}_[0-9]* COMPLETED$")
[ "$tasks" -eq $FIGURE_SHARDS ] || { cat "$WORK"/run3/logs/* 2> /dev/null; fail "$tasks of $FIGURE_SHARDS figure tasks completed"; }
echo "$states" | grep -q "^$merge_id COMPLETED$" ||
  { timeout 5 scontrol show job "$merge_id"; cat "$WORK"/run3/logs/* 2> /dev/null; fail "the figure merge job did not complete"; }
[ -d "$WORK/run3/figure" ] || fail "the figure merge wrote no $WORK/run3/figure"
if ! diff -r "$WORK/figures-one" "$WORK/run3/figure" > "$WORK/figures.diff" 2>&1; then
  head -n 20 "$WORK/figures.diff"
  fail "the merged figure folders differ from the single run's"
fi
# Negative control: shard 1 holds one of the three figures (and its manifest).
if diff -r -q "$WORK/figures-one" "$WORK/run3/shards/1" > /dev/null 2>&1; then
  fail "negative control: shard 1's folder passes as the single figure run's; the comparison is blind"
fi
echo "merged figure folders are the single run's bytes; shard 1 alone is not"
echo "PASS in $((SECONDS - start)) s"
