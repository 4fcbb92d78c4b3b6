#pragma once
// The per-frame figures of a recording as a table of named numeric columns: what the recorder
// fills, frames.csv holds and `vegstream report` reads back. A cell is NaN when the figure does
// not exist (a stage that has not landed yet, per-pass GPU times on a CPU rasteriser, no
// pipeline statistics); it is written as an empty CSV cell, never as a made-up 0.

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::flight {

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

struct RecordColumn {
  std::string name;
  int decimals = 4;  // digits after the point in the CSV; 0 writes an integer
  std::string unit;  // what a cell counts ("ms", "bytes", "tiles", …); not written to the CSV
};

class RecordTable {
 public:
  RecordTable() = default;
  explicit RecordTable(std::vector<RecordColumn> columns) : columns_(std::move(columns)) {}

  const std::vector<RecordColumn>& columns() const { return columns_; }
  std::size_t rowCount() const { return rows_.size(); }
  // Index of a column by name; nullopt when absent.
  std::optional<std::size_t> find(const std::string& name) const;

  // Appends a row of NaN cells and returns it (size = column count).
  std::vector<double>& addRow();
  const std::vector<double>& row(std::size_t i) const { return rows_[i]; }
  double at(std::size_t row, std::size_t column) const { return rows_[row][column]; }

  // The column's non-empty cells in row order.
  std::vector<double> values(std::size_t column) const;

  // CSV: a header line of column names, one line per row, "\n" line ends, empty cells for NaN.
  std::string toCsv() const;
  // Reads toCsv's output back (decimals taken as 6 for every column). InvalidInput naming
  // `sourceName`, the line and the column for anything else.
  static Result<RecordTable> parseCsv(const std::string& text, const std::string& sourceName);
  static Result<RecordTable> loadCsv(const std::filesystem::path& file);

 private:
  std::vector<RecordColumn> columns_;
  std::vector<std::vector<double>> rows_;
};

}  // namespace vegstream::flight
