#!/usr/bin/env bash
# Prepares the VM runner's cache once: Debian's kernel (linux-image-amd64, fetched with
# `apt-get download`, unpacked with `dpkg -x`, never installed), the kernel modules the guest
# needs, and a busybox-static initramfs with guest-init.sh as /init.
# Usage: prepare.sh CACHE_DIR. Prints "KERNEL INITRAMFS" (two paths) on stdout, progress on stderr.
# Reruns are cheap: the kernel package is downloaded once and kept; the modules are re-extracted
# from it only when the module list changes, the initramfs is rebuilt only when guest-init.sh or
# the modules change (directory and file names carry a hash of their inputs).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cache=${1:?usage: prepare.sh CACHE_DIR}
say() { echo "vm-prepare: $*" >&2; }

# Modules the guest loads, in any order (dependencies are added from modules.dep):
# virtio PCI transport, 9p over virtio (the host's root), overlayfs (a writable layer on it),
# virtio-serial (COMMAND's stdout/stderr), CAN core, raw and broadcast-manager sockets, vcan.
wanted_modules=(virtio_pci virtio_console 9pnet_virtio 9p overlay can can-raw can-bcm can-gw vcan vxcan)

mkdir -p "$cache"
exec 9>"$cache/.lock"
flock 9 # parallel test runs share one cache; only one prepares it

# --- 1. Kernel package: downloaded once and kept (delete the cache dir to refresh). ---
debs="$cache/debs"
if ! ls "$debs"/linux-image-*.deb >/dev/null 2>&1; then
  for tool in apt-get dpkg-deb; do
    command -v "$tool" >/dev/null || { say "missing '$tool'"; exit 1; }
  done
  rm -rf "$debs.tmp"
  mkdir -p "$debs.tmp"
  if [[ -n "${HEADINGD_VM_KERNEL_DEB:-}" ]]; then
    say "using kernel package $HEADINGD_VM_KERNEL_DEB (HEADINGD_VM_KERNEL_DEB)"
    cp "$HEADINGD_VM_KERNEL_DEB" "$debs.tmp/"
  else
    # linux-image-amd64 is a metapackage; its one Depends is the versioned image package.
    say "downloading Debian package linux-image-amd64 (metapackage, ~2 kB) into $debs"
    (cd "$debs.tmp" && apt-get download -q linux-image-amd64 2>&1 | grep -v unsandboxed >&2) \
      || { say "apt-get download linux-image-amd64 failed (no network, or no apt lists: run apt-get update)"; exit 1; }
    image_pkg=$(dpkg-deb -f "$debs.tmp"/linux-image-amd64_*.deb Depends | tr ',' '\n' \
      | sed -n 's/^ *\(linux-image-[0-9][^ ]*\).*/\1/p' | head -n1)
    [[ -n "$image_pkg" ]] || { say "no kernel image package in linux-image-amd64's Depends"; exit 1; }
    say "downloading Debian package $image_pkg (the kernel and its modules, ~70 MB)"
    (cd "$debs.tmp" && apt-get download -q "$image_pkg" 2>&1 | grep -v unsandboxed >&2) \
      || { say "apt-get download $image_pkg failed"; exit 1; }
    rm -f "$debs.tmp"/linux-image-amd64_*.deb
  fi
  ls "$debs.tmp"/linux-image-*.deb >/dev/null 2>&1 || { say "apt-get download produced no .deb"; exit 1; }
  rm -rf "$debs"
  mv "$debs.tmp" "$debs"
fi
deb=$(ls "$debs"/linux-image-*.deb | head -n1)

# --- 2. Kernel and modules: vmlinuz plus the wanted modules and their dependencies, with ---
# their load order. Redone (from the kept .deb) when the package or the module list changes.
kernel_key=$( { basename "$deb"; printf '%s\n' "${wanted_modules[@]}"; } | sha256sum | cut -c1-16)
kernel_dir="$cache/kernel-$kernel_key"
if [[ ! -f "$kernel_dir/ready" ]]; then
  for tool in dpkg depmod; do
    command -v "$tool" >/dev/null || { say "missing '$tool' (install-deps.sh installs it)"; exit 1; }
  done
  say "unpacking $(basename "$deb") (dpkg -x into the cache, not installed)"
  unpacked="$cache/unpacked"
  rm -rf "$unpacked" "$kernel_dir"
  dpkg -x "$deb" "$unpacked"
  version=$(ls "$unpacked/lib/modules" | head -n1)
  [[ -n "$version" && -f "$unpacked/boot/vmlinuz-$version" ]] || { say "no kernel found in $deb"; exit 1; }
  moddir="$unpacked/lib/modules/$version"
  # Debian generates modules.dep at install time (depmod); we install nothing, so run it here.
  depmod -b "$unpacked" "$version"

  declare -A seen=()
  load_order=()
  add_module() { # $1: a path relative to $moddir, as modules.dep names it; deps first
    local rel=$1 dep
    [[ -n "${seen[$rel]:-}" ]] && return
    seen[$rel]=1
    for dep in $(awk -v m="$rel:" '$1 == m { for (i = 2; i <= NF; i++) print $i }' "$moddir/modules.dep"); do
      add_module "$dep"
    done
    load_order+=("$rel")
  }
  for name in "${wanted_modules[@]}"; do
    pattern="/$(echo "$name" | sed 's/[-_]/[-_]/g')\.ko"  # file names use '-' or '_'
    rel=$(grep -E "$pattern(\.[a-z]+)?:" "$moddir/modules.dep" | head -n1 | cut -d: -f1 || true)
    if [[ -z "$rel" ]]; then
      grep -qE "$pattern" "$moddir/modules.builtin" \
        || { say "module $name is neither in modules.dep nor built into kernel $version"; exit 1; }
      continue # built in: nothing to load
    fi
    add_module "$rel"
  done

  mkdir -p "$kernel_dir/modules"
  cp "$unpacked/boot/vmlinuz-$version" "$kernel_dir/vmlinuz"
  # Booting the uncompressed ELF through its PVH entry point skips the firmware's kernel
  # loader and the xz decompression, ~3 s of the boot without KVM. The bzImage carries it
  # xz-compressed after its setup code; keep it only if it has the PVH note (Xen note 18).
  xz_offset=$(LC_ALL=C grep -obUaP '\xfd7zXZ\x00' "$kernel_dir/vmlinuz" | head -n1 | cut -d: -f1 || true)
  if [[ -n "$xz_offset" ]]; then
    unxz=(busybox unxz -c)
    command -v xz >/dev/null && unxz=(xz -dcq)
    tail -c +$((xz_offset + 1)) "$kernel_dir/vmlinuz" | "${unxz[@]}" >"$kernel_dir/vmlinux" 2>/dev/null || true
    if command -v readelf >/dev/null &&
      readelf -n "$kernel_dir/vmlinux" 2>/dev/null | grep -qiE 'Xen.*(0x00000012|PHYS32)'; then
      say "extracted vmlinux with a PVH entry point (direct boot)"
    else
      rm -f "$kernel_dir/vmlinux"
    fi
  fi
  for rel in "${load_order[@]}"; do
    cp "$moddir/$rel" "$kernel_dir/modules/"
    basename "$rel" >>"$kernel_dir/modules/load-order"
  done
  echo "$version" >"$kernel_dir/version"
  rm -rf "$unpacked"
  touch "$kernel_dir/ready"
  # Kernel trees from an earlier package or module list are no longer used.
  find "$cache" -maxdepth 1 -name 'kernel-*' ! -name "kernel-$kernel_key" -exec rm -rf {} +
  say "kernel $version with $(wc -l <"$kernel_dir/modules/load-order") modules ready in $kernel_dir"
fi

# --- 3. Initramfs: busybox, the modules in load order, /init, systemd/ (for --systemd). ---
# Name = hash of its inputs.
inputs_hash=$( { cat "$here/guest-init.sh" "$here"/systemd/*; echo "$kernel_key"; } | sha256sum | cut -c1-16)
initramfs="$cache/initramfs-$inputs_hash.cpio.gz"
if [[ ! -f "$initramfs" ]]; then
  say "building initramfs $(basename "$initramfs") (busybox-static, modules, guest-init.sh, systemd/)"
  stage=$(mktemp -d "$cache/stage.XXXXXX")
  trap 'rm -rf "$stage"' EXIT
  mkdir -p "$stage"/{bin,dev,proc,sys,mnt,newroot,job,overlay,lib/modules}
  cp "$(command -v busybox)" "$stage/bin/busybox"
  if ldd "$stage/bin/busybox" >/dev/null 2>&1; then
    say "$(command -v busybox) is dynamically linked; install busybox-static"; exit 1
  fi
  for applet in $("$stage/bin/busybox" --list); do
    [[ "$applet" == busybox ]] || ln -s busybox "$stage/bin/$applet"
  done
  cp "$kernel_dir"/modules/* "$stage/lib/modules/"
  cp "$here/guest-init.sh" "$stage/init"
  # vm-run.sh --systemd: the job's units, the mask list, the job wrapper.
  mkdir -p "$stage/systemd"
  cp "$here"/systemd/* "$stage/systemd/"
  chmod 755 "$stage/init"
  (cd "$stage" && find . -print0 | sort -z | cpio --null -o -H newc --quiet | gzip -1) >"$initramfs.tmp"
  mv "$initramfs.tmp" "$initramfs"
  # Older initramfs images (from an earlier guest-init.sh) are no longer used.
  find "$cache" -maxdepth 1 -name 'initramfs-*.cpio.gz' ! -name "$(basename "$initramfs")" -delete
fi

kernel="$kernel_dir/vmlinuz"
[[ -f "$kernel_dir/vmlinux" ]] && kernel="$kernel_dir/vmlinux"
echo "$kernel $initramfs"
