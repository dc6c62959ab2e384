# Sourced by the shell tests: the "data:" line test_data.hpp prints for C++ tests, naming the
# folder a test reads (cmake/test_data.cmake chose it) and whether it is the full set or the
# repository's subset.
# announce_data_set DIR KIND SUFFIX UNIT, e.g. announce_data_set "$broad" "$kind" .csv.gz trials
announce_data_set() {
  local dir=$1 kind=$2 suffix=$3 unit=$4 n
  n=$(find -L "$dir" -maxdepth 1 -type f -name "*$suffix" | wc -l)
  echo "data: $dir ($kind, $n $unit)"
}
