#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for testing the job scripts for real.
#
#   cluster/slurm/local-cluster.sh start    # install (apt), configure and start munged, slurmctld, slurmd
#   cluster/slurm/local-cluster.sh status   # is it up?
#   cluster/slurm/local-cluster.sh stop     # stop the three daemons (by the ids in their pid files)
#
# Meant for a fresh Debian/Ubuntu machine or container run as root, without systemd: the daemons
# are started directly. This host is the controller and the only compute node, with the CPUs and
# memory `slurmd -C` finds; processes are tracked by /proc (proctrack/linuxproc, task/none), so no
# cgroups are needed. `start` is idempotent: what is installed, configured or running is kept.
#
# Exit status: 0 done; 2 this machine cannot run it (not root, not Debian, apt unreachable): the
# caller reports the Slurm test as skipped; anything else is a real failure.
set -euo pipefail

readonly CONF=/etc/slurm/slurm.conf
readonly MARK="# Written by nullpath cluster/slurm/local-cluster.sh: a single-node test cluster."
readonly STATE=/var/spool/nullpath-slurm
readonly RUN=/run/nullpath-slurm
readonly LOGS=/var/log/nullpath-slurm

say() { echo "local-cluster: $*" >&2; }
unavailable() {
    say "cannot run here: $*"
    exit 2
}

# Installs munge and Slurm unless they are there.
install_packages() {
    if command -v munged >/dev/null && command -v slurmctld >/dev/null && command -v slurmd >/dev/null &&
        command -v sbatch >/dev/null; then
        return
    fi
    command -v apt-get >/dev/null || unavailable "no apt-get to install slurm-wlm and munge"
    say "installing slurm-wlm and munge (apt-get)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq || unavailable "apt-get update failed (no network?)"
    apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null ||
        unavailable "apt-get install slurm-wlm munge failed"
}

# Is the process whose id is in pid file $1 running?
running() {
    [[ -s $1 ]] && kill -0 "$(cat "$1")" 2>/dev/null
}

start_munge() {
    install -d -o munge -g munge -m 0700 /etc/munge /var/lib/munge /var/log/munge
    install -d -o munge -g munge -m 0755 /run/munge
    if [[ ! -s /etc/munge/munge.key ]]; then
        # A random key, readable by munge only: the cluster's one shared secret.
        dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
        chown munge:munge /etc/munge/munge.key
        chmod 0400 /etc/munge/munge.key
    fi
    if ! running /run/munge/munged.pid; then
        say "starting munged"
        runuser -u munge -- /usr/sbin/munged
    fi
    munge -n | unmunge >/dev/null || {
        say "munge does not work: a credential made here is not accepted here"
        exit 1
    }
}

# The configuration: this host controls itself and is the one node of partition `local`.
write_conf() {
    local node hardware
    node=$(hostname -s)
    # `slurmd -C` prints this machine as a node line: NodeName=… CPUs=… RealMemory=… (and a
    # second line, UpTime=…, left out). Its address is the loopback, so no name service is needed.
    hardware=$(slurmd -C | grep '^NodeName=' | sed "s/^NodeName=[^ ]*/NodeName=$node NodeAddr=127.0.0.1/")
    install -d -m 0755 /etc/slurm "$STATE/ctld" "$STATE/d" "$RUN" "$LOGS"
    local new
    new=$(
        cat <<EOF
$MARK
ClusterName=nullpath-local
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MailProg=/bin/true
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/d
SlurmctldPidFile=$RUN/slurmctld.pid
SlurmdPidFile=$RUN/slurmd.pid
SlurmctldLogFile=$LOGS/slurmctld.log
SlurmdLogFile=$LOGS/slurmd.log
$hardware State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
    )
    if [[ -e $CONF ]] && ! grep -qxF "$MARK" "$CONF"; then
        say "$CONF exists and was not written by this script: not touching a real cluster's configuration"
        exit 1
    fi
    if [[ ! -e $CONF ]] || [[ $(cat "$CONF") != "$new" ]]; then
        say "writing $CONF"
        printf '%s\n' "$new" >"$CONF"
        stop_slurm # Daemons running with another configuration start again with this one.
    fi
}

start_slurm() {
    local node
    node=$(hostname -s)
    if ! running "$RUN/slurmctld.pid"; then
        say "starting slurmctld"
        slurmctld
    fi
    if ! running "$RUN/slurmd.pid"; then
        say "starting slurmd"
        slurmd -N "$node"
    fi
    # Wait (at most a minute) until the node takes jobs.
    local state=""
    for _ in $(seq 60); do
        state=$(sinfo -h -n "$node" -o %T 2>/dev/null || true)
        case $state in
        idle* | mixed* | allocated*) break ;;
        down* | drain*) scontrol update NodeName="$node" State=RESUME 2>/dev/null || true ;;
        esac
        sleep 1
    done
    case $state in
    idle* | mixed* | allocated*) say "up: node $node is $state (logs in $LOGS)" ;;
    *)
        say "node $node is '${state:-unknown}' after 60 s; see $LOGS"
        tail -n 20 "$LOGS"/*.log >&2 || true
        exit 1
        ;;
    esac
}

# Stops slurmd and slurmctld by the ids in their pid files, waiting until they have exited.
stop_slurm() {
    local pidfile pid
    for pidfile in "$RUN/slurmd.pid" "$RUN/slurmctld.pid"; do
        if running "$pidfile"; then
            pid=$(cat "$pidfile")
            say "stopping $(basename "$pidfile" .pid) ($pid)"
            kill "$pid"
            for _ in $(seq 50); do
                kill -0 "$pid" 2>/dev/null || break
                sleep 0.2
            done
        fi
    done
}

stop_munge() {
    if running /run/munge/munged.pid; then
        say "stopping munged"
        kill "$(cat /run/munge/munged.pid)"
    fi
}

main() {
    case ${1:-start} in
    start)
        [[ $(id -u) == 0 ]] || unavailable "needs root (to install packages and start daemons)"
        install_packages
        start_munge
        write_conf
        start_slurm
        ;;
    stop)
        stop_slurm
        stop_munge
        ;;
    status)
        running "$RUN/slurmctld.pid" && running "$RUN/slurmd.pid" && sinfo
        ;;
    *)
        echo "usage: $0 [start|stop|status]" >&2
        exit 64
        ;;
    esac
}

main "$@"
