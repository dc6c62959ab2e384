#!/usr/bin/env bash
# The Debian package, installed into a clean root, works from there:
#   - `dpkg --root=ROOT --unpack` (the package's files and conffiles, no maintainer scripts:
#     they need systemd; tools/scripts/vm-run.sh's systemd test does `dpkg -i`) into an empty
#     merged-/usr root that gets only the host's shared libraries and python3 bind-mounted,
#     in a private mount namespace: the checkout and the build tree are not visible inside;
#   - headingd --check-config on the installed conffile /etc/headingd/headingd.toml, whose
#     absolute paths (/usr/share/headingd/...) resolve inside that root;
#   - headingd-wmm with its default coefficient file, headingd-replay on the installed demo
#     trial, the installed daemon playing the installed demo capture into an LCM log that the
#     installed Python types decode, a C++ program built against the installed headers, the
#     jar's classes;
#   - what the package holds: every program with its man page, the unit's ExecStart, the
#     sysusers file, conffiles, no path of the build machine's checkout in the programs;
#   - lintian: no errors.
#
#   package_install_test.sh DEB
# Needs root (mount namespace, chroot). Exit 77 (skip) when not root.
set -euo pipefail
deb=$(readlink -f "$1")
[[ $(id -u) -eq 0 ]] || { echo "SKIP: needs root for the mount namespace and chroot"; exit 77; }
[[ -f "$deb" ]] || { echo "FAIL: no package at $1"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root=$work/root
fail=0
check() {  # check DESCRIPTION COMMAND...: run, report
  local what=$1
  shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; fail=1; fi
}

echo "package: $deb"
dpkg-deb --info "$deb" | sed -n 's/^ \(Package\|Version\|Architecture\|Depends\|Installed-Size\):/  \1:/p'

# --- The clean root: merged /usr as on Debian 12, an empty dpkg database ---
mkdir -p "$root"/usr/{bin,lib,lib64,sbin} "$root"/{etc,tmp,var/lib/dpkg/updates,var/lib/dpkg/info,dev,proc}
ln -s usr/bin "$root/bin"; ln -s usr/lib "$root/lib"; ln -s usr/lib64 "$root/lib64"; ln -s usr/sbin "$root/sbin"
touch "$root/var/lib/dpkg/status" "$root/var/lib/dpkg/available"
chmod 1777 "$root/tmp"
dpkg --root="$root" --force-not-root --force-depends --log=/dev/null --unpack "$deb" > "$work/unpack.log" 2>&1 ||
  { cat "$work/unpack.log"; echo "FAIL: dpkg --unpack"; exit 1; }
echo "ok: dpkg --root --unpack ($(find "$root" -path "$root/var" -prune -o -type f -print | wc -l) files)"
# What `dpkg --configure` does to a new conffile before postinst (which needs systemd and is
# left to the VM test): NAME.dpkg-new becomes NAME.
while IFS= read -r conffile; do
  [[ -f "$root$conffile.dpkg-new" ]] && mv "$root$conffile.dpkg-new" "$root$conffile"
done < "$root/var/lib/dpkg/info/headingd.conffiles"

# --- What the package holds ---
check "conffiles lists /etc/headingd/headingd.toml" grep -qx /etc/headingd/headingd.toml "$root/var/lib/dpkg/info/headingd.conffiles"
check "the unit's ExecStart binary is installed" \
  test -x "$root$(sed -n 's/^ExecStart=\([^ ]*\).*/\1/p' "$root/usr/lib/systemd/system/headingd.service")"
check "sysusers entry" grep -q '^u headingd ' "$root/usr/lib/sysusers.d/headingd.conf"
check "WMM, DBC, demo capture in /usr/share/headingd" test -f "$root/usr/share/headingd/wmm/WMM2025.COF" \
  -a -f "$root/usr/share/headingd/dbc/headingd_imu.dbc" -a -f "$root/usr/share/headingd/demo/sim-urban-walk-can.log.gz"
check "examples: can0 .network and gps0 udev rule" test -f "$root/usr/share/doc/headingd/examples/80-headingd-can0.network" \
  -a -f "$root/usr/share/doc/headingd/examples/70-headingd-gps0.rules"
for program in "$root"/usr/bin/*; do
  name=$(basename "$program")
  section=1; [[ $name == headingd ]] && section=8
  check "$name(${section}) man page" test -f "$root/usr/share/man/man$section/$name.$section.gz"
  check "$name is stripped" sh -c "! readelf -S '$program' | grep -q '\.debug_info\|\.symtab'"
done
check "headingd.toml(5) man page" test -f "$root/usr/share/man/man5/headingd.toml.5.gz"

# --- Run it inside the root ---
mkdir -p "$root/usr/lib/x86_64-linux-gnu" "$root/usr/lib/python3.11" "$root/work"
touch "$root/usr/bin/python3" "$root/dev/null"
cp "$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")/decode_lcm_log.py" "$root/work/"
cat > "$work/inside.sh" <<'INSIDE'
set -u
fail=0
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; fail=1; fi; }

echo "--- headingd --check-config --config /etc/headingd/headingd.toml"
check "the installed conffile passes --check-config" headingd --check-config --config /etc/headingd/headingd.toml

echo "--- headingd-wmm (default --cof)"
cof_default=$(headingd-wmm --help | sed -n 's/.*--cof TEXT=\([^ ]*\).*/\1/p')
echo "default --cof: $cof_default"
if [[ $cof_default == /usr/share/headingd/* ]]; then
  check "headingd-wmm with its default coefficients" sh -c 'headingd-wmm --lat 52.52 --lon 13.40 --alt-km 0 --date 2026-06-01 | tee /tmp/wmm.json | grep -q decl_deg'
else
  echo "NOTE: a development build's package: the tools' defaults point to $cof_default, not checked here"
  check "headingd-wmm" sh -c 'headingd-wmm --cof /usr/share/headingd/wmm/WMM2025.COF --lat 52.52 --lon 13.40 --alt-km 0 --date 2026-06-01 | tee /tmp/wmm.json | grep -q decl_deg'
fi
cat /tmp/wmm.json 2>/dev/null; echo

echo "--- headingd-replay on the installed BROAD demo trial"
check "headingd-replay" headingd-replay --imu-csv /usr/share/headingd/demo/05_undisturbed_slow_rotation_with_breaks_B.csv.gz --out /tmp/est.csv
rows=$(($(wc -l < /tmp/est.csv) - 1))
echo "estimates: $rows rows"
check "replay wrote estimates" test "$rows" -gt 10000

echo "--- the installed daemon plays the installed demo capture; the installed Python types decode it"
check "headingd plays the demo at 1000x" timeout 120 headingd --config /tmp/play.toml --log-level error
check "python3 imports headingd from /usr/lib/python3/dist-packages and decodes" python3 /work/decode_lcm_log.py /tmp/out.lcmlog
exit $fail
INSIDE
cp "$work/inside.sh" "$root/work/inside.sh"
"$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")/demo_playback_toml.sh" /usr/share/headingd /tmp/out.lcmlog >"$root/tmp/play.toml"
unshare -m --propagation private bash -c '
  set -e
  root=$1
  mount --bind -o ro /usr/lib/x86_64-linux-gnu "$root/usr/lib/x86_64-linux-gnu"
  mount --bind -o ro /usr/lib64 "$root/usr/lib64"
  mount --bind -o ro /usr/lib/python3.11 "$root/usr/lib/python3.11"
  mount --bind -o ro /usr/bin/python3.11 "$root/usr/bin/python3"
  mount --bind /dev/null "$root/dev/null"
  mount -t proc proc "$root/proc"
  # A shell and the few commands inside.sh uses, from the host: the package ships none.
  for tool in bash sh env cat tee grep sed wc timeout; do touch "$root/usr/bin/$tool"; mount --bind -o ro "$(readlink -f /usr/bin/$tool)" "$root/usr/bin/$tool"; done
  exec timeout 600 chroot "$root" /usr/bin/env -i PATH=/usr/bin HOME=/tmp /usr/bin/bash /work/inside.sh
' bash "$root" || fail=1

# --- C++ and Java types ---
cat > "$work/subscriber.cpp" <<'CPP'
#include <headingd/heading_t.hpp>
#include <headingd/status_t.hpp>
#include <vector>
int main() {
  headingd::heading_t h;
  h.heading_true_rad = 1.25;
  h.declination_source = "wmm";
  std::vector<char> buffer(static_cast<std::size_t>(h.getEncodedSize()));
  h.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  headingd::heading_t back;
  return back.decode(buffer.data(), 0, static_cast<int>(buffer.size())) > 0 && back.heading_true_rad == 1.25 ? 0 : 1;
}
CPP
check "a C++ program builds against /usr/include/headingd and round-trips heading_t" \
  sh -c "g++ -std=c++17 -I'$root/usr/include' '$work/subscriber.cpp' -o '$work/subscriber' && '$work/subscriber'"
if [[ -f "$root/usr/share/java/headingd-lcm.jar" ]]; then
  check "the jar holds the Java classes lcm-spy needs" sh -c "python3 -m zipfile -l '$root/usr/share/java/headingd-lcm.jar' | grep -q 'headingd/heading_t.class'"
else
  echo "FAIL: no /usr/share/java/headingd-lcm.jar"; fail=1
fi

# --- No path of the build machine's checkout in the programs (defaults must not point there) ---
checkout=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
leaks=$(grep -l -F "$checkout/config" "$root"/usr/bin/* | xargs -r -n1 basename | tr '\n' ' ' || true)
if grep -qF /usr/share/headingd/wmm/WMM2025.COF "$root/usr/bin/headingd-wmm"; then
  check "no program names the checkout's config/ ($checkout/config)" test -z "$leaks"
else
  echo "NOTE: a development build's package (not tools/scripts/build-deb.sh): defaults name $checkout/config in: $leaks"
fi

# --- lintian ---
if command -v lintian >/dev/null; then
  lintian --fail-on error --tag-display-limit 0 "$deb" > "$work/lintian.txt" 2>&1 || { fail=1; echo "FAIL: lintian reports errors"; }
  echo "lintian ($(grep -c '^E:' "$work/lintian.txt" || true) errors, $(grep -c '^W:' "$work/lintian.txt" || true) warnings):"
  cat "$work/lintian.txt"
else
  echo "FAIL: lintian is not installed (tools/scripts/install-deps.sh)"; fail=1
fi

((fail == 0)) && echo "PASS: the package installs into a clean root and works from there"
exit "$fail"
