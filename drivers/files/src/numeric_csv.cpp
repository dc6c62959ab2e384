#include "headingd/files/numeric_csv.hpp"

#include "headingd/files/csv_row_reader.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::files {

NumericCsv readNumericCsv(const std::string& path, const std::vector<std::string>& required,
                          const std::vector<std::string>& optional) {
  CsvRowReader reader(path, required, optional);
  NumericCsv csv;
  csv.path = path;
  csv.header = reader.header();
  std::vector<std::vector<double>*> destinations;
  for (const auto& name : reader.columns()) destinations.push_back(&csv.columns[name]);
  std::vector<double> row(reader.columns().size());
  while (reader.next(row)) {
    for (std::size_t i = 0; i < row.size(); ++i) destinations[i]->push_back(row[i]);
  }
  csv.rows = reader.rows();
  return csv;
}

}  // namespace headingd::files
