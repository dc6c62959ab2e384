#pragma once
// The columns of one table: the union of the column names of its messages. A status_t's
// sources, rings and counters change from message to message (a source appears, a counter
// is added); the first pass over the log sees them all, so the header is written once and
// every row has a cell for each column (empty where its message has no such value).
// New names go in after the previous column of the message that brought them, so columns
// stay in declaration order, keyed elements in the order they first appeared.
#include <cstddef>
#include <string>
#include <unordered_map>
#include <vector>

#include "headingd/lcm_export/columns.hpp"

namespace headingd::lcm_export {

class ColumnLayout {
 public:
  // First pass: takes in the column names of `row`.
  void merge(const FlatRow& row);
  const std::vector<std::string>& columns() const { return columns_; }
  // Second pass: puts the row's cells at their columns' positions + `first`, the other
  // cells of `cells` (sized first + columns().size()) are emptied.
  void place(const FlatRow& row, std::vector<std::string>& cells, std::size_t first);

 private:
  std::vector<std::string> columns_;
  std::unordered_map<std::string, std::size_t> index_;
  // The previous row's names and their positions: most rows repeat them exactly.
  std::vector<std::string> last_keys_;
  std::vector<std::size_t> last_positions_;
  bool placing_ = false;
};

}  // namespace headingd::lcm_export
