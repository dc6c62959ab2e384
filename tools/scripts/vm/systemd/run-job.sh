#!/bin/sh
# vm-run.sh --systemd: started by headingd-vm-job.service (the host's /bin/sh, under systemd).
# Runs the job vm-run.sh wrote (/run/headingd-vm/run.sh: environment, working directory,
# COMMAND) with its stdout and stderr on the two virtio-serial ports, as guest-init.sh does
# in the default mode, and writes COMMAND's exit status into the job share. The unit powers
# the guest off when this script ends.
. /run/headingd-vm-init/virtio-ports.sh
find_job_ports
if [ "$out" = /dev/null ]; then
  echo "vm-job: SETUP FAILED: no virtio-serial port named stdout" >&2
  exit 1
fi
read -r up _ </proc/uptime
echo "vm-job: [$up s] running the job under systemd"
/bin/bash /run/headingd-vm/run.sh </dev/null >"$out" 2>"$err"
status=$?
echo "$status" >/run/headingd-vm/status.tmp && mv /run/headingd-vm/status.tmp /run/headingd-vm/status
read -r up _ </proc/uptime
echo "vm-job: [$up s] job exited with status $status; powering off"
