#!/usr/bin/env bash
# A one-node Slurm cluster on this host, for examples/slurm/tolerance.sbatch and its test.
#
#   sudo bash tools/slurm-one-node.sh
#
# Installs Debian's slurm-wlm and munge when they are missing (apt-get update, then
# apt-get install -y --no-install-recommends), generates a munge key if there is none, starts
# munged, writes /etc/slurm/slurm.conf for ONE node (this host, with the CPUs and memory that
# `slurmd -C` reads; both daemons on 127.0.0.1; process tracking by /proc, no cgroups, no
# accounting), starts slurmctld and slurmd directly (no systemd needed) and waits until `sinfo`
# shows the node idle.
#
# Idempotent: what is installed, configured and running is left as it is, so a second run
# changes nothing and succeeds. A slurm.conf that this script did not write is never replaced:
# if it already gives a cluster with a node up, the script succeeds without touching anything,
# otherwise it stops (exit 1) saying so.
#
# Exit codes: 0 the node is idle (or a cluster already answers); 77 the cluster cannot be set up
# here (slurm or munge missing, and not root or no apt-get), one line saying why; 1 any other
# failure, with the daemons' last log lines.
set -euo pipefail

readonly UNAVAILABLE=77
readonly MARKER="# Written by cycloid's tools/slurm-one-node.sh; it rewrites this file."
readonly CONF_DIR=/etc/slurm
readonly CONF=$CONF_DIR/slurm.conf
readonly STATE_DIR=/var/lib/slurm/slurmctld
readonly SPOOL_DIR=/var/lib/slurm/slurmd
readonly LOG_DIR=/var/log/slurm
readonly CTLD_PID=/run/slurmctld.pid
readonly SLURMD_PID=/run/slurmd.pid
readonly MUNGE_KEY=/etc/munge/munge.key
readonly WAIT_S=${SLURM_ONE_NODE_WAIT_S:-60}
# Every program the cluster needs; a missing one means an install.
readonly NEEDED=(munged munge unmunge slurmctld slurmd sinfo sbatch scontrol)

say() { echo "slurm-one-node: $*" >&2; }
unavailable() {
    echo "slurm-one-node: unavailable: $*"
    exit "$UNAVAILABLE"
}
fail() {
    say "error: $*"
    for log in "$LOG_DIR/slurmctld.log" "$LOG_DIR/slurmd.log"; do
        [[ -r $log ]] && { say "last lines of $log:"; tail -n 15 "$log" >&2; }
    done
    exit 1
}

# Programs of NEEDED that are not on PATH (sbin included: a user's PATH may lack it).
missing_programs() {
    local p missing=()
    for p in "${NEEDED[@]}"; do
        PATH=$PATH:/usr/sbin:/sbin command -v "$p" >/dev/null 2>&1 || missing+=("$p")
    done
    echo "${missing[*]}"
}

# True when a cluster answers and has a node idle (or partly or wholly allocated).
node_up() {
    local states
    states=$(sinfo --noheader --Node --format=%t 2>/dev/null) || return 1
    grep -Eq '^(idle|mix|alloc)$' <<<"$states"
}

# The process whose pid a pid file holds is alive and runs the named program.
running() {
    local pidfile=$1 name=$2 pid
    [[ -r $pidfile ]] || return 1
    pid=$(<"$pidfile")
    [[ $pid =~ ^[0-9]+$ ]] && [[ -r /proc/$pid/comm ]] && [[ $(</proc/$pid/comm) == "$name" ]]
}

# Ends the daemon of a pid file (by its pid) and waits until it is gone.
stop() {
    local pidfile=$1 name=$2 pid i
    running "$pidfile" "$name" || return 0
    pid=$(<"$pidfile")
    say "stopping $name ($pid) to load the new slurm.conf"
    kill "$pid"
    for ((i = 0; i < 50; i++)); do
        [[ -d /proc/$pid ]] || return 0
        sleep 0.2
    done
    fail "$name ($pid) did not stop"
}

install_packages() {
    local missing
    missing=$(missing_programs)
    [[ -z $missing ]] && return 0
    ((EUID == 0)) || unavailable "not root, and slurm-wlm/munge are not installed (missing: $missing)"
    command -v apt-get >/dev/null 2>&1 ||
        unavailable "apt-get is unavailable, and slurm-wlm/munge are not installed (missing: $missing)"
    say "installing slurm-wlm and munge (missing: $missing)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q >&2
    apt-get install -y -q --no-install-recommends slurm-wlm munge >&2
    missing=$(missing_programs)
    [[ -z $missing ]] || fail "still missing after apt-get install: $missing"
}

# munged runs as the munge user with a key only that user reads; a key is generated if none.
start_munge() {
    if [[ ! -s $MUNGE_KEY ]]; then
        say "generating a munge key in $MUNGE_KEY"
        install -d -o munge -g munge -m 0700 /etc/munge
        (umask 077 && dd if=/dev/urandom of="$MUNGE_KEY.tmp" bs=1024 count=1 status=none)
        chown munge:munge "$MUNGE_KEY.tmp"
        chmod 0400 "$MUNGE_KEY.tmp"
        mv "$MUNGE_KEY.tmp" "$MUNGE_KEY"
    fi
    if munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
        return 0
    fi
    say "starting munged"
    install -d -o munge -g munge -m 0755 /run/munge
    install -d -o munge -g munge -m 0700 /var/lib/munge /var/log/munge
    runuser -u munge -- /usr/sbin/munged 9>&-
    munge -n </dev/null | unmunge >/dev/null || fail "munged started but a credential does not round-trip"
}

# The node's line of slurm.conf: NodeName, CPUs, Boards, Sockets, Cores, Threads, RealMemory
# as slurmd -C reads them from this host (its first line; the second is the uptime).
node_hardware() {
    local line
    line=$(slurmd -C 2>/dev/null | head -n 1) || true
    if [[ $line != NodeName=* ]]; then
        # Without slurmd -C: the CPUs and the memory (MiB) from the kernel.
        line="NodeName=$HOST CPUs=$(nproc) RealMemory=$(($(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024))"
    fi
    sed -E "s/^NodeName=[^ ]+//" <<<"$line"
}

slurm_conf() {
    local slurm_user=root
    id slurm >/dev/null 2>&1 && slurm_user=slurm
    cat <<EOF
$MARKER
# One node on this host; both daemons on loopback (127.0.0.1).
ClusterName=cycloid
SlurmctldHost=$HOST(127.0.0.1)
SlurmUser=$slurm_user
AuthType=auth/munge
CredType=cred/munge
MpiDefault=none
# No cgroups (none may be writable here): processes tracked through /proc, tasks not bound.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
# Cores are the consumable resource; memory is not, so jobs that ask none still share the node.
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
# No accounting: no slurmdbd, no database.
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
# The node comes back by itself after a restart of the daemons.
ReturnToService=2
StateSaveLocation=$STATE_DIR
SlurmdSpoolDir=$SPOOL_DIR
SlurmctldPidFile=$CTLD_PID
SlurmdPidFile=$SLURMD_PID
SlurmctldLogFile=$LOG_DIR/slurmctld.log
SlurmdLogFile=$LOG_DIR/slurmd.log
NodeName=$HOST NodeAddr=127.0.0.1$(node_hardware) State=UNKNOWN
PartitionName=main Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
}

# Writes slurm.conf when it differs from what it should be; prints "changed" when it did.
write_conf() {
    local wanted
    wanted=$(slurm_conf)
    if [[ -e $CONF ]]; then
        if ! grep -qxF "$MARKER" "$CONF"; then
            fail "$CONF was not written by this script and no node is up: fix that cluster, or move $CONF away and run again"
        fi
        [[ $(<"$CONF") == "$wanted" ]] && return 0
    fi
    say "writing $CONF"
    install -d -m 0755 "$CONF_DIR"
    printf '%s\n' "$wanted" >"$CONF.tmp"
    chmod 0644 "$CONF.tmp"
    mv "$CONF.tmp" "$CONF"
    echo changed
}

start_daemons() {
    local changed=$1 owner
    owner=$(sed -n 's/^SlurmUser=//p' "$CONF")
    install -d -o "$owner" -m 0755 "$STATE_DIR" "$LOG_DIR"
    install -d -m 0755 "$SPOOL_DIR"
    if [[ -n $changed ]]; then
        stop "$SLURMD_PID" slurmd
        stop "$CTLD_PID" slurmctld
    fi
    if ! running "$CTLD_PID" slurmctld; then
        say "starting slurmctld"
        slurmctld 9>&- || fail "slurmctld did not start"
    fi
    if ! running "$SLURMD_PID" slurmd; then
        say "starting slurmd"
        slurmd 9>&- || fail "slurmd did not start"
    fi
}

# Waits for the node to be idle; a node left down or drained by an earlier run is resumed once.
wait_idle() {
    local state resumed="" i
    for ((i = 0; i < WAIT_S * 5; i++)); do
        state=$(sinfo --noheader --Node --nodes="$HOST" --format=%t 2>/dev/null | head -n 1) || state=""
        case $state in
            idle | mix | alloc) return 0 ;;
            down* | drain* | drng*)
                if [[ -z $resumed ]]; then
                    say "node $HOST is $state: resuming it"
                    scontrol update NodeName="$HOST" State=RESUME >/dev/null 2>&1 || true
                    resumed=yes
                fi
                ;;
        esac
        sleep 0.2
    done
    fail "node $HOST is not idle after ${WAIT_S} s (sinfo: ${state:-no answer})"
}

main() {
    HOST=$(hostname -s)
    readonly HOST
    export PATH=$PATH:/usr/sbin:/sbin
    # Two runs at once (two test processes) take turns: the second finds the node up. The
    # daemons are started without this descriptor (9>&-), or they would hold the lock for ever.
    if ((EUID == 0)) && command -v flock >/dev/null 2>&1; then
        exec 9>/run/cycloid-slurm-one-node.lock
        flock --wait "$((WAIT_S * 5))" 9 || fail "another run of this script holds /run/cycloid-slurm-one-node.lock"
    fi
    install_packages
    # A cluster that already answers with a node up (this script's or the user's) is used as is.
    if ! grep -qxsF "$MARKER" "$CONF" && node_up; then
        say "a Slurm cluster already answers with a node up; nothing to do"
        exit 0
    fi
    ((EUID == 0)) || {
        node_up && { say "a Slurm node is up; nothing to do"; exit 0; }
        unavailable "not root, and no Slurm node is up to use (run this script as root to start one)"
    }
    start_munge
    local changed
    changed=$(write_conf)
    start_daemons "$changed"
    wait_idle
    say "node $HOST is idle: $(sinfo --noheader --Node --nodes="$HOST" --format='%N %c CPUs %m MiB %P')"
}

main "$@"
