#!/bin/sh
# /init of the VM runner's initramfs (busybox sh, PID 1 in the guest).
# Loads the modules, mounts the host's root (9p, read-only) under a tmpfs overlay so the guest
# sees the host's binaries, libraries and paths but its writes stay in the guest, brings up lo
# (with a multicast route, for LCM udpm ttl=0), vcan0 and vcan1, runs the job that vm-run.sh
# wrote into the "job" share with its stdout/stderr on two virtio-serial ports, writes the
# exit status back into the job share, and powers off. With headingd_vm.init=systemd on the
# kernel command line (vm-run.sh --systemd) it hands the root to systemd instead, which runs
# the job as a unit (boot_systemd).
# Everything here goes to the console (ttyS0), which the host keeps as a log file.
export PATH=/bin

say() { read -r up _ </proc/uptime; echo "vm-init: [$up s] $*"; }
fail() {
  # vm-run.sh finds no status file, prints the console's tail and exits with its boot-failure status.
  say "SETUP FAILED: $*"
  dmesg | tail -n 25
  sync
  poweroff -f
  sleep 60
}

# vm-run.sh --systemd: the overlay root, network and shares are set up as for a job, then
# systemd becomes PID 1 on that root and runs the job as a unit (/systemd: the units, the
# mask list and the job wrapper, from tools/scripts/vm/systemd/).
boot_systemd() {
  say "installing the job's units, masking the VM's useless units"
  etc_units=$r/etc/systemd/system
  mkdir -p $etc_units $r/etc/systemd/system-generators $r/run/headingd-vm-init
  cp /systemd/headingd-vm.target /systemd/headingd-vm-job.service $etc_units/ || fail "copy of the job's units"
  cp /systemd/run-job.sh /systemd/virtio-ports.sh $r/run/headingd-vm-init/ || fail "copy of run-job.sh"
  sed 's/#.*//' /systemd/masked-units | while read -r unit; do
    [ -n "$unit" ] && ln -sf /dev/null "$etc_units/$unit"
  done
  # Generators read the host's fstab, disks, SysV scripts and consoles: none of it applies.
  # The debug generator stays (systemd.mask= and systemd.wants= on the kernel command line).
  for generator in $r/lib/systemd/system-generators/* $r/usr/lib/systemd/system-generators/*; do
    name=${generator##*/}
    [ -e "$generator" ] && [ "$name" != systemd-debug-generator ] \
      && ln -sf /dev/null "$r/etc/systemd/system-generators/$name"
  done
  : >$r/etc/fstab
  # A host that is a container (docker leaves /.dockerenv) would make systemd believe it runs
  # in one: it would then ignore the kernel command line (systemd.unit=) and skip the
  # machine's setup. The guest is a real machine.
  rm -f $r/.dockerenv $r/run/.containerenv
  echo headingd-vm >$r/etc/hostname
  [ -x $r/lib/systemd/systemd ] || fail "no /lib/systemd/systemd on the host root (systemd not installed)"
  say "switching to systemd as PID 1"
  umount /proc /sys
  umount -l /dev
  exec switch_root $r /lib/systemd/systemd
  fail "switch_root to /lib/systemd/systemd"
}

mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev

say "loading modules"
while read -r module; do
  insmod "/lib/modules/$module" || fail "insmod $module"
done </lib/modules/load-order

say "mounting the host root"
# msize: large 9p messages make reading binaries and libraries much faster than the default.
p9_opts=trans=virtio,version=9p2000.L,msize=512000
mount -t 9p -o "$p9_opts,cache=none" job /job || fail "mount of the job share"
# cache=loose: the host root is read-only for the guest's lifetime, so caching it is safe.
mount -t 9p -o "$p9_opts,ro,cache=loose" hostroot /mnt || fail "mount of the host root (9p)"

mkdir -p /overlay
mount -t tmpfs -o mode=755 overlay-rw /overlay
mkdir -p /overlay/upper /overlay/work
mount -t overlay overlay -o lowerdir=/mnt,upperdir=/overlay/upper,workdir=/overlay/work /newroot \
  || fail "overlay of tmpfs on the host root"

r=/newroot
mount -t proc proc $r/proc
mount -t sysfs sysfs $r/sys
mount -t devtmpfs devtmpfs $r/dev
mkdir -p $r/dev/pts $r/dev/shm
mount -t devpts -o newinstance,gid=5,mode=620,ptmxmode=666 devpts $r/dev/pts
ln -sf pts/ptmx $r/dev/ptmx
# What udev would add: bash's process substitution needs /dev/fd.
ln -sf /proc/self/fd $r/dev/fd
ln -sf /proc/self/fd/0 $r/dev/stdin
ln -sf /proc/self/fd/1 $r/dev/stdout
ln -sf /proc/self/fd/2 $r/dev/stderr
mount -t tmpfs -o mode=1777 tmpfs $r/dev/shm
mount -t tmpfs -o mode=1777 tmpfs $r/tmp
mount -t tmpfs -o mode=755 tmpfs $r/run
mkdir -p $r/run/headingd-vm
mount -o bind /job $r/run/headingd-vm

# Host directories shared read-write (vm-run.sh --rw DIR): "TAG PATH" lines.
if [ -f /job/rw-mounts ]; then
  while read -r tag path; do
    mkdir -p "$r$path"
    mount -t 9p -o "$p9_opts,cache=none" "$tag" "$r$path" || fail "mount of --rw $path"
  done </job/rw-mounts
fi

say "bringing up lo, vcan0, vcan1"
hostname headingd-vm
# lo with multicast and a route for 224.0.0.0/4, so UDP multicast with ttl=0 (LCM udpm) loops back.
ip link set lo up || fail "lo up"
ip link set lo multicast on || fail "lo multicast on"
ip route add 224.0.0.0/4 dev lo || fail "multicast route on lo"
for can_if in vcan0 vcan1; do
  ip link add dev $can_if type vcan || fail "ip link add $can_if type vcan"
  ip link set $can_if up || fail "ip link set $can_if up"
done

# The job's stdout and stderr: virtio-serial ports named by vm-run.sh.
. /systemd/virtio-ports.sh
find_job_ports
[ "$out" != /dev/null ] || fail "no virtio-serial port named stdout"

if grep -qw 'headingd_vm.init=systemd' /proc/cmdline; then
  boot_systemd # does not return
fi

say "running the job"
chroot $r /bin/bash /run/headingd-vm/run.sh </dev/null >"$out" 2>"$err"
status=$?
echo "$status" >/job/status.tmp && mv /job/status.tmp /job/status
say "job exited with status $status"
sync
say "powering off"
poweroff -f
sleep 60
