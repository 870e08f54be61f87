// A small strict CSV reader and a writer for numeric tables.
//
// Reader: the first line is a header of unique, non-empty column names; every later line is a
// data row with exactly one field per column. Fields are separated by commas, surrounding spaces
// and tabs are ignored, quoting is not supported, CRLF line ends are accepted, and empty lines at
// the end of the file and a leading UTF-8 byte order mark are ignored. Numeric fields are parsed
// with std::from_chars and must be finite. Every error names the file and, where it applies, the
// 1-based data row (the first line after the header is data row 1) and the column.
//
// Writer: doubles are printed with 17 significant digits ("{:.17g}"), which reads back to the
// identical double; NaN prints as "nan". write_csv_atomic writes a whole file that way.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <optional>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace glintlab::io {

// A malformed CSV file or field. The message names the file, data row and column where known.
struct CsvError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Parses `text` as a decimal floating-point number with std::from_chars (an optional leading '+'
// is accepted). Returns nothing unless the whole text is consumed and the value is finite.
std::optional<double> parse_finite_double(std::string_view text);
// Why parse_finite_double rejects `text`: "is not a number", "is not finite" or "is outside the
// range of a double" (for use after "'<text>' ").
std::string_view number_problem(std::string_view text);

class CsvTable {
 public:
  // Name of the source used in messages (usually the file path as given).
  const std::string& source() const { return source_; }
  const std::vector<std::string>& header() const { return header_; }
  std::size_t num_rows() const { return rows_.size(); }
  std::size_t num_columns() const { return header_.size(); }

  // Index of a column, or nothing if absent.
  std::optional<std::size_t> find_column(std::string_view name) const;
  // Index of a column; throws CsvError naming the file and the column if absent.
  std::size_t column(std::string_view name) const;

  // Raw (trimmed) text of a field; `row` is 0-based here, messages report it 1-based.
  std::string_view text(std::size_t row, std::size_t col) const;
  // The field parsed as a finite double; throws CsvError naming the file, 1-based data row and
  // column if it does not parse.
  double number(std::size_t row, std::size_t col) const;

  // "'<file>' data row <row+1>, column <name>": the location prefix used in every field message.
  std::string where(std::size_t row, std::size_t col) const;
  // "'<file>' data row <row+1>".
  std::string where(std::size_t row) const;

 private:
  friend CsvTable parse_csv(std::string_view text, std::string source);
  std::string source_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

// Parses CSV text; `source` names it in messages. Throws CsvError on a missing or malformed
// header, a row with the wrong number of fields, an empty field, or a quote character.
CsvTable parse_csv(std::string_view text, std::string source);
// Reads and parses a file; throws CsvError if the file cannot be read.
CsvTable read_csv(const std::filesystem::path& path);

// Formats a double with 17 significant digits.
std::string format_double(double x);

// Writes rows of fields to a stream: the header on construction, then cells row by row.
class CsvWriter {
 public:
  CsvWriter(std::ostream& out, std::span<const std::string_view> header);
  CsvWriter(std::ostream& out, std::initializer_list<std::string_view> header);

  CsvWriter& cell(double x);
  CsvWriter& cell(std::string_view text);
  CsvWriter& cell(const char* text) { return cell(std::string_view(text)); }
  CsvWriter& cell_int(long long x);
  // Ends the row; throws std::logic_error if the row does not have one cell per column.
  void end_row();
  // Writes buffered text to the stream.
  void flush();
  ~CsvWriter();

 private:
  void separator();
  std::ostream& out_;
  std::size_t num_columns_;
  std::size_t cells_in_row_ = 0;
  std::string buffer_;
};

// Writes a CSV file atomically (core/io/atomic_file.h): the header, then whatever `rows` writes;
// if anything throws, no file is left behind. Throws std::runtime_error naming the path when the
// file cannot be written.
void write_csv_atomic(const std::filesystem::path& path, std::span<const std::string_view> header,
                      const std::function<void(CsvWriter&)>& rows);
void write_csv_atomic(const std::filesystem::path& path,
                      std::initializer_list<std::string_view> header,
                      const std::function<void(CsvWriter&)>& rows);

}  // namespace glintlab::io
