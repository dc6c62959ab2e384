#include "headingd/lcm_export/column_layout.hpp"

#include <stdexcept>

namespace headingd::lcm_export {

void ColumnLayout::merge(const FlatRow& row) {
  if (row.sameKeysAs(last_keys_)) return;
  std::size_t insert_at = 0;
  for (std::size_t i = 0; i < row.size; ++i) {
    const auto found = index_.find(row.keys[i]);
    if (found != index_.end()) {
      insert_at = found->second + 1;
      continue;
    }
    columns_.insert(columns_.begin() + static_cast<std::ptrdiff_t>(insert_at), row.keys[i]);
    for (std::size_t c = insert_at; c < columns_.size(); ++c) index_[columns_[c]] = c;
    ++insert_at;
  }
  last_keys_.assign(row.keys.begin(), row.keys.begin() + static_cast<std::ptrdiff_t>(row.size));
}

void ColumnLayout::place(const FlatRow& row, std::vector<std::string>& cells, std::size_t first) {
  if (!placing_) {
    placing_ = true;
    last_keys_.clear();
  }
  if (!row.sameKeysAs(last_keys_)) {
    last_keys_.assign(row.keys.begin(), row.keys.begin() + static_cast<std::ptrdiff_t>(row.size));
    last_positions_.resize(row.size);
    for (std::size_t i = 0; i < row.size; ++i) {
      const auto found = index_.find(row.keys[i]);
      // The first pass saw every name; a new one means the log changed between the passes.
      if (found == index_.end()) throw std::runtime_error("column " + row.keys[i] + " was not in the first pass");
      last_positions_[i] = found->second;
    }
  }
  for (std::size_t c = first; c < cells.size(); ++c) cells[c].clear();
  for (std::size_t i = 0; i < row.size; ++i) cells[first + last_positions_[i]] = row.cells[i];
}

}  // namespace headingd::lcm_export
