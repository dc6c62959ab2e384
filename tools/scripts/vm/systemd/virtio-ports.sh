# Sourced by guest-init.sh and run-job.sh (POSIX sh, busybox or the host's): sets $out and
# $err to the virtio-serial ports vm-run.sh named "stdout" and "stderr" (sysfs gives the
# names), /dev/null for a port that is not there.
find_job_ports() {
  out=/dev/null
  err=/dev/null
  for port in /sys/class/virtio-ports/*; do
    [ -e "$port/name" ] || continue
    case "$(cat "$port/name")" in
      stdout) out=/dev/${port##*/} ;;
      stderr) err=/dev/${port##*/} ;;
    esac
  done
}
