// RecordTable (record_table.h): CSV writing and strict reading.

#include "flight/record_table.h"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/printable.h"
#include "core/text_file.h"

namespace vegstream::flight {

std::optional<std::size_t> RecordTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i].name == name) return i;
  return std::nullopt;
}

std::vector<double>& RecordTable::addRow() {
  rows_.emplace_back(columns_.size(), kNoValue);
  return rows_.back();
}

std::vector<double> RecordTable::values(std::size_t column) const {
  std::vector<double> out;
  out.reserve(rows_.size());
  for (const auto& r : rows_)
    if (!std::isnan(r[column])) out.push_back(r[column]);
  return out;
}

std::string RecordTable::toCsv() const {
  std::string out;
  out.reserve(64 + rows_.size() * columns_.size() * 10);
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (c) out += ',';
    out += columns_[c].name;
  }
  out += '\n';
  char cell[64];
  for (const auto& r : rows_) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (c) out += ',';
      if (std::isnan(r[c])) continue;
      std::snprintf(cell, sizeof(cell), "%.*f", columns_[c].decimals, r[c]);
      out += cell;
    }
    out += '\n';
  }
  return out;
}

namespace {
std::vector<std::string_view> splitCells(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}
}  // namespace

Result<RecordTable> RecordTable::parseCsv(const std::string& text, const std::string& sourceName) {
  auto fail = [&](std::size_t line, const std::string& what) {
    return makeError(ErrorKind::InvalidInput, sourceName + ":" + std::to_string(line) + ": " + what);
  };
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line.empty()) return fail(1, "no header line (expected frames.csv column names)");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<RecordColumn> columns;
  for (auto name : splitCells(line)) {
    if (name.empty()) return fail(1, "empty column name in the header");
    columns.push_back({std::string(name), 6});
  }
  RecordTable table(std::move(columns));
  std::size_t lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const auto cells = splitCells(line);
    if (cells.size() != table.columns_.size())
      return fail(lineNo,
                  std::to_string(cells.size()) + " cells, the header has " + std::to_string(table.columns_.size()));
    auto& row = table.addRow();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].empty()) continue;
      double v = 0.0;
      const auto [end, ec] = std::from_chars(cells[c].data(), cells[c].data() + cells[c].size(), v);
      if (ec != std::errc() || end != cells[c].data() + cells[c].size() || !std::isfinite(v))
        return fail(lineNo, "column " + printable(table.columns_[c].name) + ": \"" + printable(cells[c]) +
                                "\" is not a number");
      row[c] = v;
    }
  }
  return table;
}

Result<RecordTable> RecordTable::loadCsv(const std::filesystem::path& file) {
  auto text = readTextFile(file, "no such file", kTableFileCeiling);
  if (!text) return text.error();
  return parseCsv(*text, file.string());
}

}  // namespace vegstream::flight
