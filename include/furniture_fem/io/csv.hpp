#pragma once
// furniture_fem/io/csv.hpp: time-series CSV output and a reader that returns columns by name.
//
// CsvWriter streams numeric rows under a header written once. Rows are buffered in memory and
// written whole, then flushed every `flush_rows` rows or `flush_seconds`, whichever comes first, so a
// run killed by Ctrl-C leaves a file whose complete lines are all valid. read_csv() drops a last line
// that lacks its newline (the row being written when the run died) and reports it via truncated().
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "../core/errors.hpp"
#include "../core/text.hpp"

namespace furniture_fem {

struct CsvOptions {
  int precision = 15;             // significant digits (as printf %.*g); 15 keeps ~1e-15 relative
  std::size_t flush_rows = 100;   // flush at least every this many rows ...
  double flush_seconds = 1.0;     // ... and at least this often (for slow runs)
};

namespace detail::csv {
// RFC 4180 quoting for header names that contain a comma, a quote or a line break.
inline std::string quote(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace detail::csv

class CsvWriter {
 public:
  CsvWriter(std::string path, std::vector<std::string> columns, CsvOptions opt = {})
      : path_(std::move(path)), columns_(std::move(columns)), opt_(opt), file_(path_, std::ios::binary | std::ios::trunc) {
    if (!file_) throw OutputError("CsvWriter: cannot open '" + path_ + "' for writing");
    if (columns_.empty()) throw InputError("CsvWriter '" + path_ + "': no columns");
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      if (i) buf_ += ',';
      buf_ += detail::csv::quote(columns_[i]);
    }
    buf_ += '\n';
    flush();  // the header is on disk even if the first row never comes
  }
  // Where a checkpoint leaves the file: its length in bytes (flushed) and its rows.
  struct Position {
    static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
    std::uint64_t bytes = 0, rows = 0;
  };
  // Goes on with a file a checkpoint left at `at` (RunOptions::resume): what a run stopped later wrote
  // after it is cut off, and rows follow without a second header. The file must be at least that long.
  CsvWriter(std::string path, std::vector<std::string> columns, Position at, CsvOptions opt = {})
      : path_(std::move(path)), columns_(std::move(columns)), opt_(opt), rows_(at.rows), bytes_(at.bytes) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path_, ec);
    if (ec || size < at.bytes)
      throw InputError(path_, 0, "",
                       "cannot go on from the checkpoint: the file " +
                           (ec ? "is missing (" + ec.message() + ")" : "has " + std::to_string(size) + " bytes") +
                           " where the checkpoint wrote " + std::to_string(at.bytes) + " (changed after the run stopped?)");
    std::filesystem::resize_file(path_, at.bytes, ec);
    if (ec) throw OutputError("CsvWriter: cannot cut '" + path_ + "' back to the checkpoint: " + ec.message());
    file_.open(path_, std::ios::binary | std::ios::app);
    if (!file_) throw OutputError("CsvWriter: cannot open '" + path_ + "' for writing");
  }
  Position position() {
    flush();
    return {bytes_, rows_};
  }
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  ~CsvWriter() {
    try {
      flush();
    } catch (...) {  // destructors must not throw; the last rows are lost, as in a crash
    }
  }

  void row(const double* values, std::size_t n) {
    if (n != columns_.size())
      throw InputError("CsvWriter '" + path_ + "': row " + std::to_string(rows_ + 1) + " has " +
                                  std::to_string(n) + " values for " + std::to_string(columns_.size()) + " columns");
    for (std::size_t i = 0; i < n; ++i) {
      if (i) buf_ += ',';
      append_number(values[i]);
    }
    end_row();
  }
  void row(const std::vector<double>& v) { row(v.data(), v.size()); }
  void row(std::initializer_list<double> v) { row(v.begin(), v.size()); }

  // A row of numbers and labels (a long-format file: "t, item_a, item_b, fx, ..."); labels are quoted
  // as the header's names are.
  struct Cell {
    Cell(double v) : value(v) {}
    Cell(std::string_view t) : text(t), is_text(true) {}
    std::string_view text;
    double value = 0;
    bool is_text = false;
  };
  void cells_row(std::initializer_list<Cell> cells) {
    if (cells.size() != columns_.size())
      throw InputError("CsvWriter '" + path_ + "': row " + std::to_string(rows_ + 1) + " has " +
                       std::to_string(cells.size()) + " cells for " + std::to_string(columns_.size()) + " columns");
    bool first = true;
    for (const Cell& c : cells) {
      if (!first) buf_ += ',';
      first = false;
      if (c.is_text) buf_ += detail::csv::quote(std::string(c.text));
      else append_number(c.value);
    }
    end_row();
  }

  // Writes buffered rows and flushes the stream to the operating system.
  void flush() {
    if (!buf_.empty()) {
      file_.write(buf_.data(), std::streamsize(buf_.size()));
      bytes_ += buf_.size();
      buf_.clear();
    }
    file_.flush();
    pending_ = 0;
    last_flush_ = std::chrono::steady_clock::now();
    if (!file_) throw OutputError("CsvWriter: error while writing '" + path_ + "'");
  }

  std::size_t rows() const { return rows_; }
  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  void append_number(double v) {
    char num[64];
    // to_chars ignores the C locale, so a decimal comma can never corrupt the file.
    const auto r = std::to_chars(num, num + sizeof num, v, std::chars_format::general, opt_.precision);
    buf_.append(num, r.ptr);
  }
  void end_row() {
    buf_ += '\n';
    ++rows_;
    if (++pending_ >= opt_.flush_rows || std::chrono::steady_clock::now() - last_flush_ >= flush_period()) flush();
  }
  std::chrono::steady_clock::duration flush_period() const {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(opt_.flush_seconds));
  }
  std::string path_;
  std::vector<std::string> columns_;
  CsvOptions opt_;
  std::ofstream file_;
  std::string buf_;
  std::size_t rows_ = 0, pending_ = 0;
  std::uint64_t bytes_ = 0;  // written to the file
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
};

// Numeric columns of a CSV file with a header line. Lines starting with '#' and blank lines are
// skipped; an empty field reads as NaN.
class CsvTable {
 public:
  const std::vector<std::string>& columns() const { return names_; }
  std::size_t rows() const { return data_.empty() ? 0 : data_[0].size(); }
  bool has(const std::string& name) const { return find(name) < names_.size(); }
  // True when the last line had no newline (a run killed mid-row) and was dropped.
  bool truncated() const { return truncated_; }

  const std::vector<double>& column(const std::string& name) const {
    const std::size_t i = find(name);
    if (i == names_.size()) throw InputError(path_, 0, name, "the CSV file has no such column");
    return data_[i];
  }
  const std::vector<double>& column(std::size_t i) const { return data_.at(i); }

  static CsvTable read(const std::string& path) {
    std::string bytes;
    if (!text::read_file(path, bytes)) throw InputError(path, 0, "", "read_csv: cannot open the file for reading");
    text::Lines lines = text::split_lines(path, bytes);
    lines.lines.pop_back();  // the text after the last newline: empty, or the row being written when the run died

    CsvTable t;
    t.path_ = path;
    t.truncated_ = !bytes.empty() && bytes.back() != '\n';
    bool header = false;
    for (long lineno = 1; lineno <= static_cast<long>(lines.size()); ++lineno) {
      const std::string& line = lines.line(lineno);
      if (text::is_blank(line) || line[0] == '#') continue;
      std::vector<std::string> fields = text::split_fields(line);
      if (!header) {
        for (auto& s : fields) t.names_.emplace_back(text::trim(s));
        t.data_.resize(t.names_.size());
        header = true;
        continue;
      }
      if (fields.size() != t.names_.size())
        throw InputError(path, lineno, "", "row has " + std::to_string(fields.size()) + " fields, header has " +
                                               std::to_string(t.names_.size()));
      for (std::size_t i = 0; i < fields.size(); ++i) t.data_[i].push_back(parse(fields[i], path, lineno, t.names_[i]));
    }
    if (!header) throw InputError(path, 0, "", "no header line");
    return t;
  }

 private:
  std::size_t find(const std::string& name) const {
    std::size_t i = 0;
    while (i < names_.size() && names_[i] != name) ++i;
    return i;
  }
  static double parse(const std::string& raw, const std::string& path, long line, const std::string& col) {
    const std::string_view s = text::trim(raw);
    if (s.empty()) return std::nan("");
    double v = 0;  // locale-independent, like the writer; "nan" and "inf" are what it writes for them
    if (!text::parse_double(s, v)) throw InputError(path, line, col, "'" + std::string(s) + "' is not a number");
    return v;
  }
  std::string path_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> data_;
  bool truncated_ = false;
};

inline CsvTable read_csv(const std::string& path) { return CsvTable::read(path); }

}  // namespace furniture_fem
