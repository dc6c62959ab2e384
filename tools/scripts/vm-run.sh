#!/usr/bin/env bash
# Runs COMMAND where vcan0 and vcan1 exist: natively in a private network namespace when the
# host kernel can create vcan interfaces, otherwise in a throwaway VM (qemu-system-x86_64 with
# Debian's kernel) that sees the host's files. Both give COMMAND a loopback with a multicast
# route (LCM udpm with ttl=0) and the same working directory and environment.
# See tools/scripts/vm/README.md for how it works and what it costs.
set -euo pipefail

readonly exit_timeout=124   # COMMAND did not finish within --timeout
readonly exit_vm_failure=125 # the VM did not boot, set up or power off as expected

usage() {
  cat <<'EOF'
usage: vm-run.sh [--systemd] [--timeout SEC] [--mem MB] [--cpus N] [--env NAME=VALUE]... [--rw DIR]... -- COMMAND [ARGS...]

Runs COMMAND with vcan0, vcan1 and a multicast-capable lo, in the host's working directory and
environment (the whole environment passes through; --env adds or overrides one variable).
  --systemd       always the VM, with systemd as PID 1: COMMAND runs as a unit once the basic
                  system is up (journald, sysusers, tmpfiles), so it can use systemctl,
                  journalctl, systemd-run, systemd-analyze and dpkg -i with real maintainer
                  scripts; see tools/scripts/vm/README.md, "--systemd"
  --timeout SEC   kill COMMAND (and the VM) after SEC seconds; exit status 124 (default 600)
  --mem MB        guest memory (default 1024)
  --cpus N        guest CPUs (default 1: a second one costs ~1-2 s of boot without KVM)
  --env NAME=VAL  set NAME=VAL for COMMAND
  --rw DIR        make host directory DIR writable from the VM (its writes reach the host);
                  everything else is the host's root, read-only, under a throwaway tmpfs layer
Environment:
  HEADINGD_VM=force|native|auto   force the VM / refuse the VM / native when possible (default)
  HEADINGD_VM_CACHE=DIR           kernel, modules, initramfs, console logs
                                  (default ${XDG_CACHE_HOME:-~/.cache}/headingd-vm)
  HEADINGD_VM_ACCEL=tcg|kvm       accelerator (default tcg, plain emulation)
  HEADINGD_VM_KERNEL_DEB=FILE     use this linux-image .deb instead of downloading one
Exit status: COMMAND's; 124 on timeout; 125 when the VM fails to boot or set up (the console
log's tail is printed).
EOF
}

die_usage() { echo "vm-run: $*" >&2; usage >&2; exit 2; }
say() { echo "vm-run: $*" >&2; }

timeout_s=600
mem_mb=1024
cpus=1
extra_env=()
rw_dirs=()
with_systemd=0
while (($#)); do
  case "$1" in
    --systemd) with_systemd=1; shift ;;
    --timeout) [[ "${2:-}" =~ ^[0-9]+$ ]] || die_usage "--timeout needs seconds"; timeout_s=$2; shift 2 ;;
    --mem) [[ "${2:-}" =~ ^[0-9]+$ ]] || die_usage "--mem needs megabytes"; mem_mb=$2; shift 2 ;;
    --cpus) [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || die_usage "--cpus needs a count"; cpus=$2; shift 2 ;;
    --env) [[ "${2:-}" =~ ^[A-Za-z_][A-Za-z0-9_]*= ]] || die_usage "--env needs NAME=VALUE"; extra_env+=("$2"); shift 2 ;;
    --rw) [[ -d "${2:-}" ]] || die_usage "--rw needs an existing directory"; rw_dirs+=("$(cd "$2" && pwd -P)"); shift 2 ;;
    -h|--help) usage; exit 0 ;;
    --) shift; break ;;
    *) die_usage "unknown option '$1' (COMMAND goes after --)" ;;
  esac
done
(($#)) || die_usage "no COMMAND"

mode=${HEADINGD_VM:-auto}
[[ "$mode" =~ ^(auto|force|native)$ ]] || die_usage "HEADINGD_VM must be auto, force or native"
if ((with_systemd)); then
  # systemd as PID 1 needs a machine of its own: a network namespace is not one.
  [[ "$mode" != native ]] || die_usage "--systemd needs the VM, but HEADINGD_VM=native"
  mode=force
fi

# ---------------------------------------------------------------------------------------------
# Native: a private network namespace (root: unshare -n; otherwise a user namespace too).
net_setup='ip link set lo up && ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo &&
  for i in vcan0 vcan1; do ip link add dev "$i" type vcan && ip link set "$i" up || exit 1; done'
unshare_cmd=(unshare -n)
[[ $(id -u) -eq 0 ]] || unshare_cmd=(unshare -r -n)

native_possible() {
  command -v unshare >/dev/null && command -v ip >/dev/null &&
    "${unshare_cmd[@]}" sh -c "$net_setup" >/dev/null 2>&1
}

if [[ "$mode" != force ]] && native_possible; then
  status=0
  timeout --kill-after=5 "$timeout_s" "${unshare_cmd[@]}" bash -c \
    "$net_setup >&2 || { echo 'vm-run: network namespace setup failed' >&2; exit $exit_vm_failure; }
     exec env -- \"\$@\"" vm-run "${extra_env[@]}" "$@" || status=$?
  # timeout(1) says 124 (137 after --kill-after); COMMAND might say 124 too, so check the clock.
  if ((status == 124 || status == 137)) && ((SECONDS >= timeout_s)); then
    say "timeout: COMMAND did not finish within ${timeout_s} s (native, private network namespace)"
    exit "$exit_timeout"
  fi
  exit "$status"
fi
if [[ "$mode" == native ]]; then
  say "HEADINGD_VM=native, but this host cannot create vcan interfaces in a network namespace"
  exit "$exit_vm_failure"
fi

# ---------------------------------------------------------------------------------------------
# VM.
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cache=${HEADINGD_VM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/headingd-vm}
command -v qemu-system-x86_64 >/dev/null || { say "qemu-system-x86_64 missing (apt-get install qemu-system-x86)"; exit "$exit_vm_failure"; }
read -r kernel initramfs < <("$here/vm/prepare.sh" "$cache") || true
[[ -f "${kernel:-}" && -f "${initramfs:-}" ]] || { say "preparing the VM cache in $cache failed"; exit "$exit_vm_failure"; }

mkdir -p "$cache/logs"
console_log="$cache/logs/console-$(date +%Y%m%d-%H%M%S)-$$.log"
# Keep the 20 newest console logs.
{ ls -1t "$cache"/logs/console-*.log 2>/dev/null || true; } | tail -n +21 | xargs -r rm -f

job=$(mktemp -d "${TMPDIR:-/tmp}/headingd-vm.XXXXXX")
chmod 755 "$job"
qemu_pid=
readers=()
cleanup() { # shellcheck disable=SC2317 # (called by the EXIT trap)
  if [[ -n "$qemu_pid" ]]; then kill "$qemu_pid" 2>/dev/null || true; fi
  rm -rf "$job"
}
trap cleanup EXIT
trap 'say "interrupted"; exit 130' INT
trap 'say "terminated"; exit 143' TERM

# The job: environment, working directory and COMMAND, run by the host's bash inside the guest.
{
  echo "# written by vm-run.sh; run in the guest by /init with the host's root as /"
  export -p | grep -vE '^declare -x (PWD|OLDPWD|SHLVL|HOSTNAME|_)=' || true
  for assignment in "${extra_env[@]}"; do
    printf 'export %q=%q\n' "${assignment%%=*}" "${assignment#*=}"
  done
  printf 'cd -- %q || exit %d\n' "$PWD" "$exit_vm_failure"
  printf 'exec'; printf ' %q' "$@"; printf '\n'
} >"$job/run.sh"

# The guest mounts fresh tmpfs on /tmp and /run, which would hide a checkout or build tree
# there (a CI job may clone under /tmp): share the top directory of each such path.
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd -P)
for path in "$(pwd -P)" "$repo_root"; do
  case "$path" in
    /tmp/?*|/run/?*)
      top=$(printf '%s' "$path" | cut -d/ -f1-3)
      already=0
      for d in "${rw_dirs[@]}"; do [[ "$d" == "$top" ]] && already=1; done
      ((already)) || rw_dirs+=("$top")
      ;;
  esac
done

rw_args=()
: >"$job/rw-mounts"
for i in "${!rw_dirs[@]}"; do
  rw_args+=(-virtfs "local,path=${rw_dirs[$i]},mount_tag=rw$i,security_model=none,multidevs=remap")
  echo "rw$i ${rw_dirs[$i]}" >>"$job/rw-mounts"
done

# COMMAND's stdout/stderr arrive through FIFOs; readers first, so QEMU's open does not block.
mkfifo "$job/stdout" "$job/stderr"
cat "$job/stdout" &
readers+=($!)
cat "$job/stderr" >&2 &
readers+=($!)

# TCG by default: it works everywhere. KVM is opt-in because a /dev/kvm that opens is no proof
# that it boots a guest (on nested hosts it can hang in the firmware or abort on MSRs).
accel=${HEADINGD_VM_ACCEL:-tcg}
case "$accel" in
  kvm) accel_args=(-accel kvm -cpu host) ;;
  tcg) accel_args=(-accel tcg -cpu max) ;;
  *) die_usage "HEADINGD_VM_ACCEL must be kvm or tcg" ;;
esac

# Quiet console (loglevel=3: errors only); panic=-1 with -no-reboot turns a guest panic
# (e.g. /init dying) into QEMU exiting instead of hanging until the timeout. no_timer_check:
# on a loaded host the emulated timer can miss the kernel's early IO-APIC check, which then
# panics ("IO-APIC + timer doesn't work!"); the timer works, the check is skipped.
cmdline="console=ttyS0 loglevel=3 panic=-1 edd=off no_timer_check rdinit=/init"
# --systemd: /init hands the root to systemd, which boots to the job's target; its unit
# status lines go to the console log (where the boot's time went).
((with_systemd)) && cmdline+=" headingd_vm.init=systemd systemd.unit=headingd-vm.target systemd.show_status=true"
# shellcheck disable=SC2054 # commas separate QEMU's sub-options, not array elements
qemu=(
  qemu-system-x86_64 "${accel_args[@]}"
  -M pc -m "$mem_mb" -smp "$cpus"
  -nodefaults -no-user-config -display none -no-reboot
  -kernel "$kernel" -initrd "$initramfs" -append "$cmdline"
  -chardev "file,id=console,path=$console_log" -serial chardev:console
  -virtfs "local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap"
  -virtfs "local,path=$job,mount_tag=job,security_model=none,multidevs=remap"
  "${rw_args[@]}"
  -device virtio-serial-pci
  -chardev "file,id=stdout,path=$job/stdout" -device virtserialport,chardev=stdout,name=stdout
  -chardev "file,id=stderr,path=$job/stderr" -device virtserialport,chardev=stderr,name=stderr
)

start_ns=$(date +%s%N)
# timeout(1) stops QEMU at the deadline (QEMU itself never exits 124). Waiting with the `wait`
# builtin keeps the INT/TERM traps responsive; cleanup() then stops QEMU through timeout(1).
timeout "$timeout_s" "${qemu[@]}" </dev/null &
qemu_pid=$!
qemu_status=0
wait "$qemu_pid" || qemu_status=$?
qemu_pid=
timed_out=0
((qemu_status == 124)) && timed_out=1
elapsed_ms=$((($(date +%s%N) - start_ns) / 1000000))

# Release readers still blocked in open() (QEMU died before opening the FIFO), then drain them.
for fifo in "$job/stdout" "$job/stderr"; do
  exec {fd}<>"$fifo"
  exec {fd}>&-
done
wait "${readers[@]}" 2>/dev/null || true

show_console_tail() {
  if [[ ! -s "$console_log" ]]; then
    say "the console log $console_log is empty: the kernel never started (see QEMU's messages above)"
    return
  fi
  if (($(wc -l <"$console_log") <= 30)); then
    say "console log: $console_log:"
    sed 's/^/vm-console: /' "$console_log" >&2
    return
  fi
  say "console log: $console_log; its key lines, then its last 20 lines:"
  grep -aE 'vm-init:|Kernel panic|Out of memory|BUG:|Oops|segfault|Killed process' "$console_log" \
    | tail -n 15 | sed 's/^/vm-console: /' >&2 || true
  echo "vm-console: ..." >&2
  tail -n 20 "$console_log" | sed 's/^/vm-console: /' >&2
}

if ((timed_out)); then
  say "timeout: COMMAND did not finish within ${timeout_s} s; VM killed"
  show_console_tail
  exit "$exit_timeout"
fi
if [[ ! -f "$job/status" ]]; then
  say "the VM stopped without a job status (QEMU exit status $qemu_status): boot or setup failed"
  show_console_tail
  exit "$exit_vm_failure"
fi
status=$(cat "$job/status")
[[ -n "${HEADINGD_VM_VERBOSE:-}" ]] && say "VM run took ${elapsed_ms} ms (${accel}$( ((with_systemd)) && echo ", systemd")), COMMAND exit status $status"
exit "$status"
