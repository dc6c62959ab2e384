#!/usr/bin/env bash
# The Python message types lcm-gen makes (installed as the package `headingd`) decode what
# the C++ daemon encodes: headingd plays the demo capture at 1000x into an LCM log file
# (the file:// provider), and python3 reads the log's events and decodes each HEADING,
# ATTITUDE and STATUS with headingd.<type>.decode(). Needs no LCM Python binding (Debian 12
# has none): the generated classes decode bytes themselves.
#
#   lcm_python_test.sh HEADINGD PYTHON3 LCM_PYTHON_DIR CONFIG_DIR
set -euo pipefail
headingd=$1 python=$2 lcm_python_dir=$3 config_dir=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$(dirname "${BASH_SOURCE[0]}")/demo_playback_toml.sh" "$config_dir" "$work/out.lcmlog" >"$work/play.toml"
"$headingd" --config "$work/play.toml" --log-level warn

PYTHONPATH="$lcm_python_dir" "$python" "$(dirname "${BASH_SOURCE[0]}")/decode_lcm_log.py" "$work/out.lcmlog"
