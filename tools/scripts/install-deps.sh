#!/usr/bin/env bash
# Installs the Debian 12 packages that headingd's build and tests need, and only those that
# are missing. Idempotent: when everything is present it changes nothing and does not touch
# the network. Meant to run as root on Debian 12 (falls back to sudo if not root).
set -euo pipefail

packages=(
  build-essential      # g++, make
  cmake
  pkg-config           # finds toml++ and GeographicLib
  libeigen3-dev        # math
  zlib1g-dev           # gzip'd CSV input
  libcli11-dev         # command lines
  libtomlplusplus-dev  # configuration files
  libgtest-dev         # unit and accuracy tests
  libbenchmark-dev     # benchmarks
  libspdlog-dev        # logging
  libboost-dev         # Asio, Lockfree
  libgeographiclib-dev # World Magnetic Model, geodesy
  libceres-dev         # maximum-likelihood calibration (automatic differentiation)
  ccache               # compiled objects kept: rebuilds, and the selfcontained test's fresh clone
  gzip                 # the demo recording and BROAD trials are gzip'd
  time                 # /usr/bin/time: peak RSS in tools/scripts/bench-replay.sh
  liblcm-dev           # LCM messages (daemon)
  liblcm-bin           # lcm-gen, lcm-logger
  liblcm-java          # lcm.jar for lcm-spy and the Java message classes
  libjchart2d-java     # lcm-spy's charts (it fails to start without)
  libglib2.0-dev       # liblcm-dev's pkg-config file requires glib
  default-jdk-headless # javac/jar: the lcm-spy jar of headingd's messages
  libsystemd-dev       # sd_notify, watchdog (daemon)
  nlohmann-json3-dev   # gpsd's JSON reports ([gps] source = "gpsd")
  gpsd                 # a real gpsd in the tests: [gps] source = "gpsd", and [nmea_out] -> gpsd
  gpsd-clients         # gpspipe, the tests' gpsd client
  systemd              # systemd-analyze verify in the tests; PID 1 of vm-run.sh --systemd
  dbus                 # the system bus systemd-analyze security asks (vm-run.sh --systemd)
  python3              # the systemd VM test's pty GPS and LCM log check (system interpreter)
  can-utils            # cansend/candump/canplayer in the vcan tests
  qemu-system-x86      # the VM that gives the vcan tests a kernel with CAN
  busybox-static       # the VM's initramfs userland
  cpio                 # packs the initramfs
  kmod                 # modinfo/depmod for the VM's CAN modules
  xz-utils             # unpacks the VM kernel's modules
  binutils             # readelf: the VM boots the uncompressed kernel (3 s faster)
  python3              # packaging/config-doc.py: headingd.toml(5) and the installed config
  help2man             # the programs' man pages, from their --help
  dpkg-dev             # dpkg-shlibdeps, dpkg-buildflags: the Debian package (build-deb.sh)
  lintian              # checks the Debian package (tests/package)
  clang                # the libFuzzer targets (tests/fuzz, tools/scripts/fuzz.sh)
  libclang-rt-14-dev   # libFuzzer and clang's sanitizer runtimes
)

missing=()
for pkg in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == installed ]] || missing+=("$pkg")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages already installed, nothing to do"
  exit 0
fi

as_root=()
if [[ $(id -u) -ne 0 ]]; then
  if ! command -v sudo >/dev/null; then
    echo "install-deps: not root; as root run: apt-get install ${missing[*]}" >&2
    exit 1
  fi
  as_root=(sudo)
fi

echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
echo "install-deps: installed ${missing[*]}"
