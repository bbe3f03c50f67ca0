#!/usr/bin/env bash
# A one-node SLURM cluster on this host, for `make test-cluster` (CI runs as root on Debian 12).
#   .ci/slurm.sh up     install slurm-wlm and munge if absent, write slurm.conf, start munged,
#                       slurmctld and slurmd, wait until the node is idle
#   .ci/slurm.sh down   stop the three daemons by the PIDs that `up` recorded
#   .ci/slurm.sh status sinfo and squeue
# The configuration: one node (this host's name, 2 CPUs), one partition `debug` (the default),
# no accounting (no slurmdbd: the profile polls with squeue, and slurmctld keeps finished jobs
# for MinJobAge=600 s). It writes /etc/slurm/slurm.conf only if that file is absent or was
# written by this script, and refuses to touch a real site configuration.
set -euo pipefail

STATE=${MOORLIFE_SLURM_STATE:-/var/lib/moorlife-slurm}
CONF=/etc/slurm/slurm.conf
MARK="# written by moorlife .ci/slurm.sh"
CPUS=${MOORLIFE_SLURM_CPUS:-2}

log() { echo "slurm.sh: $*" >&2; }

install_packages() {
    local missing=()
    command -v slurmctld >/dev/null || missing+=(slurm-wlm)
    command -v munged >/dev/null || missing+=(munge)
    if ((${#missing[@]})); then
        log "installing ${missing[*]} with apt"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq
        apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    fi
}

write_conf() {
    if [[ -f $CONF ]] && ! grep -qF "$MARK" "$CONF"; then
        log "$CONF exists and is not ours: refusing to overwrite a site configuration"
        exit 1
    fi
    local host mem
    host=$(hostname -s)
    # 90 % of the host's memory, in MB: the simulate jobs ask mem_mb_per_cpu x CPUs
    mem=$(awk '/MemTotal/ {printf "%d", $2 / 1024 * 0.9}' /proc/meminfo)
    mkdir -p /etc/slurm "$STATE/ctld" "$STATE/d" "$STATE/log"
    cat >"$CONF" <<EOF
$MARK
ClusterName=moorlife-ci
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/d
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
MinJobAge=600
SlurmctldTimeout=60
SlurmdTimeout=60
InactiveLimit=0
KillWait=10
NodeName=$host CPUs=$CPUS RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
    log "wrote $CONF (node $host, $CPUS CPUs, ${mem} MB, partition debug)"
}

start_munge() {
    if munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
        log "munged already answers"  # not ours: `down` leaves it running
        return
    fi
    if [[ ! -s /etc/munge/munge.key ]]; then
        mkdir -p /etc/munge
        if command -v mungekey >/dev/null; then mungekey --create --force; else
            dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none; fi
    fi
    chown munge:munge /etc/munge /etc/munge/munge.key 2>/dev/null || true
    chmod 0700 /etc/munge
    chmod 0400 /etc/munge/munge.key
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge 2>/dev/null || true
    chmod 0755 /run/munge
    # setpriv execs (runuser would fork), so $! is the PID of munged itself
    setpriv --reuid munge --regid munge --init-groups /usr/sbin/munged --foreground \
        >>"$STATE/log/munged.out" 2>&1 &
    echo $! >"$STATE/munged.pid"
    for _ in $(seq 50); do
        munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1 && return
        sleep 0.2
    done
    log "munged did not start"
    exit 1
}

alive() { # pidfile name: the recorded process is still that daemon
    [[ -f $1 ]] && [[ $(cat "/proc/$(cat "$1")/comm" 2>/dev/null) == "$2" ]]
}

up() {
    install_packages
    mkdir -p "$STATE"
    if alive "$STATE/slurmctld.pid.own" slurmctld && alive "$STATE/slurmd.pid.own" slurmd; then
        log "already up (slurmctld $(cat "$STATE/slurmctld.pid.own"), slurmd $(cat "$STATE/slurmd.pid.own"))"
        sinfo
        return
    fi
    # PIDs recorded by an earlier session whose daemons are gone: never kill a reused PID
    for f in slurmctld.pid.own:slurmctld slurmd.pid.own:slurmd munged.pid:munged; do
        alive "$STATE/${f%%:*}" "${f##*:}" || rm -f "$STATE/${f%%:*}"
    done
    write_conf
    start_munge
    # -D: stay in the foreground, so that $! is the daemon's PID; -i: ignore stale state
    slurmctld -D -i >>"$STATE/log/slurmctld.out" 2>&1 &
    echo $! >"$STATE/slurmctld.pid.own"
    for _ in $(seq 100); do scontrol ping 2>/dev/null | grep -q UP && break; sleep 0.2; done
    slurmd -D >>"$STATE/log/slurmd.out" 2>&1 &
    echo $! >"$STATE/slurmd.pid.own"
    local host state=""
    host=$(hostname -s)
    for _ in $(seq 150); do
        state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
        [[ $state == idle ]] && break
        [[ $state == down* || $state == drain* ]] && scontrol update nodename="$host" state=resume 2>/dev/null || true
        sleep 0.2
    done
    if [[ $state != idle ]]; then
        log "node $host is '$state', not idle; logs in $STATE/log"
        tail -n 20 "$STATE"/log/*.log >&2 || true
        exit 1
    fi
    log "up: munged $(cat "$STATE/munged.pid" 2>/dev/null || echo '(already running)')," \
        "slurmctld $(cat "$STATE/slurmctld.pid.own"), slurmd $(cat "$STATE/slurmd.pid.own")"
    sinfo
}

stop_pid() { # name pidfile
    local f=$2 pid
    [[ -f $f ]] || return 0
    pid=$(cat "$f")
    if alive "$f" "$1"; then
        kill "$pid"
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
        kill -0 "$pid" 2>/dev/null && kill -9 "$pid"
        log "stopped $1 ($pid)"
    fi
    rm -f "$f"
}

down() {
    # every daemon this script started, by the PID it recorded (jobs die with slurmd)
    stop_pid slurmd "$STATE/slurmd.pid.own"
    stop_pid slurmctld "$STATE/slurmctld.pid.own"
    stop_pid munged "$STATE/munged.pid"
}

case ${1:-} in
up) up ;;
down) down ;;
status) sinfo && squeue ;;
*) echo "usage: $0 up|down|status" >&2; exit 2 ;;
esac
