#!/bin/sh
# Prints a daemon configuration that plays the demo capture (candump and NMEA logs) as fast as
# it can into an LCM log file and exits: the package tests' way to make real LCM traffic.
# The rings hold the whole capture (60001 IMU samples, 600 GPS epochs): at 1000x a stall of
# the machine of a few tens of ms would otherwise fill the default 64-epoch GPS ring and
# drop epochs (counted), which the tests that count every message would take for a fault.
# Likewise the LCM send queue holds all that is published (about 11 MB): with the default
# 1 MiB, a clean-clone run under the suite's parallel fuzz build held the sender back long
# enough to drop 2932 of the 60001 IMU messages (counted).
#   demo_playback_toml.sh DATA_DIR LCM_LOG   (DATA_DIR: config/ of a checkout or /usr/share/headingd)
set -eu
data=$1 log=$2
cat <<TOML
[daemon]
wmm = "$data/wmm/WMM2025.COF"
[lcm]
url = "file://$log?mode=w"
send_queue_bytes = 67108864
[rings]
imu_capacity = 65536
gps_capacity = 1024
[playback]
speed = 1000.0
at_end = "exit"
[candump_log]
enabled = true
path = "$data/demo/sim-urban-walk-can.log.gz"
can_config = "$data/can-headingd.toml"
[nmea_log]
enabled = true
path = "$data/demo/sim-urban-walk.nmea"
TOML
