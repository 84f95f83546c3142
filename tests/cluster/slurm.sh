#!/usr/bin/env bash
# A real Slurm for the `cluster` tests: one node on localhost, munged, slurmctld and slurmd
# started with a private configuration, key, state, logs and ports, and stopped by PID.
# Nothing is installed here (scripts/install-packages.sh installs slurm-wlm and munge) and
# nothing of the machine's own Slurm or munge is touched.
#
#   slurm.sh start ENV_FILE   start it; ENV_FILE gets the lines a test sources (SLURM_CONF)
#   slurm.sh stop ENV_FILE    stop what start started, and remove its folder
#
# The daemons live in a folder under /tmp: munged refuses a socket below a folder that not
# everyone may search (a build tree under /root is one).
set -euo pipefail
usage() { echo "usage: slurm.sh start|stop ENV_FILE" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1 env_file=$2

stop() {
  [ -f "$env_file" ] || return 0
  local home
  home=$(sed -n 's/^ACETATE_SLURM_HOME=//p' "$env_file")
  [ -n "$home" ] && [ -d "$home" ] || { rm -f "$env_file"; return 0; }
  for daemon in slurmd slurmctld munged; do
    local pid
    pid=$(cat "$home/$daemon.pid" 2>/dev/null || true)
    [ -n "$pid" ] || continue
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  done
  rm -rf "$home" "$env_file"
}

free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

start() {
  for tool in munged mungekey slurmctld slurmd sbatch sinfo python3; do
    command -v "$tool" >/dev/null ||
      { echo "slurm.sh: $tool is not installed (scripts/install-packages.sh installs it)" >&2; exit 1; }
  done
  stop
  local home
  home=$(mktemp -d /tmp/acetate-slurm-XXXXXX)
  chmod 711 "$home"
  mkdir -p "$home/state" "$home/spool"
  mungekey --create --keyfile="$home/munge.key"
  chmod 600 "$home/munge.key"
  # The origin is given: a root without /etc/hosts cannot look up its own name.
  munged --key-file="$home/munge.key" --socket="$home/munge.socket" --origin=127.0.0.1 \
    --pid-file="$home/munged.pid" --log-file="$home/munged.log" --seed-file="$home/munged.seed"
  local controller_port node_port cpus
  controller_port=$(free_port)
  node_port=$(free_port)
  cpus=$(nproc)
  # Processes are tracked by their parent ids and bound to no cgroup: the root this runs in
  # may have no systemd, and the tests need no isolation between their own tasks.
  cat > "$home/slurm.conf" <<CONF
ClusterName=acetate
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$controller_port
SlurmdPort=$node_port
SlurmUser=$(id -un)
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$home/munge.socket
CredType=cred/munge
StateSaveLocation=$home/state
SlurmdSpoolDir=$home/spool
SlurmctldPidFile=$home/slurmctld.pid
SlurmdPidFile=$home/slurmd.pid
SlurmctldLogFile=$home/slurmctld.log
SlurmdLogFile=$home/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MinJobAge=3600
NodeName=acetate-node NodeHostname=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=acetate Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  printf 'ACETATE_SLURM_HOME=%s\nSLURM_CONF=%s\n' "$home" "$home/slurm.conf" > "$env_file"
  export SLURM_CONF=$home/slurm.conf
  # A daemon that does not start is one line naming it, then the end of its log.
  local daemon
  for daemon in slurmctld slurmd; do
    local args=(-f "$SLURM_CONF")
    [ "$daemon" = slurmd ] && args+=(-N acetate-node)
    "$daemon" "${args[@]}" || {
      echo "slurm.sh: $daemon did not start; the end of $home/$daemon.log:" >&2
      tail -n 5 "$home/$daemon.log" >&2 || true
      [ -d /sys/fs/cgroup ] || echo "slurm.sh: (slurmd needs the cgroup file system at /sys/fs/cgroup)" >&2
      stop
      exit 1
    }
  done
  for _ in $(seq 300); do
    [ "$(sinfo -h -o %t 2>/dev/null)" = idle ] && { echo "slurm.sh: one node, $cpus CPUs, up ($home)"; return 0; }
    sleep 0.1
  done
  echo "slurm.sh: the node did not come up in 30 s; the logs:" >&2
  tail -n 5 "$home"/*.log >&2 || true
  stop
  exit 1
}

case $action in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
