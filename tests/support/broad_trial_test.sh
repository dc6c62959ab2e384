# Sourced, with the script's arguments, by the shell tests that run headingd-replay and
# headingd-eval on one BROAD trial (tests/e2e/CMakeLists.txt passes them):
#   REPLAY EVAL BROAD_DIR KIND TRIAL
# BROAD_DIR and KIND as cmake/test_data.cmake chose them; TRIAL without .csv.gz. Sets replay,
# eval and trial (the trial's file), says which data set it is, and makes $work, a fresh folder
# removed when the script exits.
source "$(dirname "${BASH_SOURCE[0]}")/test_data.sh"
replay=$1 eval=$2 trial=$3/$5.csv.gz
announce_data_set "$3" "$4" .csv.gz trials
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# expect_replay_csv OUT: OUT, headingd-replay's output for $trial, has the documented header and
# one row per input row (the number of input rows is left in in_rows).
expect_replay_csv() {
  local header out_rows
  header=$(head -n 1 "$1")
  [ "$header" = "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg,heading_sigma_deg" ] || { echo "bad header: $header"; exit 1; }
  in_rows=$(( $(zcat -f "$trial" | wc -l) - 1 ))
  out_rows=$(( $(wc -l < "$1") - 1 ))
  [ "$in_rows" -eq "$out_rows" ] || { echo "rows: in $in_rows, out $out_rows"; exit 1; }
}
