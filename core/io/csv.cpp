// Strict CSV reading and 17-digit CSV writing; see csv.h.
#include "core/io/csv.h"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <system_error>

#include "core/io/atomic_file.h"

namespace glintlab::io {
namespace {

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// Splits one line (without its line end) at commas, trimming each field.
std::vector<std::string> split_fields(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? line.size() : comma;
    fields.emplace_back(trim(line.substr(start, end - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

// Shortens a field for quoting in a message.
std::string excerpt(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (char c : s.substr(0, kMax)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  if (s.size() > kMax) out += "...";
  return out;
}

}  // namespace

std::optional<double> parse_finite_double(std::string_view text) {
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    // "+-1" and "++1" are not numbers.
    if (text.empty() || text.front() == '+' || text.front() == '-') return std::nullopt;
  }
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
  if (ec != std::errc() || ptr != last || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string_view number_problem(std::string_view text) {
  std::string_view t = text;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (!t.empty() && ptr == t.data() + t.size()) {
    if (ec == std::errc::result_out_of_range) return "is outside the range of a double";
    if (ec == std::errc() && !std::isfinite(value)) return "is not finite";
  }
  return "is not a number";
}

std::optional<std::size_t> CsvTable::find_column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return i;
  }
  return std::nullopt;
}

std::size_t CsvTable::column(std::string_view name) const {
  if (const auto i = find_column(name)) return *i;
  throw CsvError(fmt::format("'{}': missing column '{}' in the header", source_, name));
}

std::string_view CsvTable::text(std::size_t row, std::size_t col) const {
  return rows_.at(row).at(col);
}

std::string CsvTable::where(std::size_t row) const {
  return fmt::format("'{}' data row {}", source_, row + 1);
}

std::string CsvTable::where(std::size_t row, std::size_t col) const {
  return fmt::format("'{}' data row {}, column {}", source_, row + 1, header_.at(col));
}

double CsvTable::number(std::size_t row, std::size_t col) const {
  const std::string_view t = text(row, col);
  if (const auto v = parse_finite_double(t)) return *v;
  throw CsvError(fmt::format("{}: '{}' {} (valid: a finite decimal number)", where(row, col),
                             excerpt(t), number_problem(t)));
}

CsvTable parse_csv(std::string_view text, std::string source) {
  CsvTable table;
  table.source_ = std::move(source);

  // A UTF-8 byte order mark (written by some spreadsheet programs) is not part of the header.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);

  // Split into lines, accepting "\n" and "\r\n".
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string_view::npos) nl = text.size();
    std::string_view line = text.substr(start, nl - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = nl + 1;
  }
  // Blank lines at the end of the file are ignored; anywhere else they are malformed rows.
  while (!lines.empty() && trim(lines.back()).empty()) lines.pop_back();
  if (lines.empty()) {
    throw CsvError(fmt::format("'{}': the file is empty (expected a header row of column names)",
                               table.source_));
  }

  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find('"') != std::string_view::npos) {
      const std::string loc = i == 0 ? fmt::format("'{}' header row", table.source_)
                                     : fmt::format("'{}' data row {}", table.source_, i);
      throw CsvError(
          fmt::format("{}: contains a quote character (quoted fields are not supported)", loc));
    }
  }

  table.header_ = split_fields(lines[0]);
  std::set<std::string_view> seen;
  for (std::size_t c = 0; c < table.header_.size(); ++c) {
    const std::string& name = table.header_[c];
    if (name.empty()) {
      throw CsvError(
          fmt::format("'{}' header row: column {} has an empty name", table.source_, c + 1));
    }
    if (!seen.insert(name).second) {
      throw CsvError(fmt::format("'{}' header row: column '{}' appears more than once",
                                 table.source_, excerpt(name)));
    }
  }

  table.rows_.reserve(lines.size() - 1);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::size_t row = i - 1;
    std::vector<std::string> fields = split_fields(lines[i]);
    if (fields.size() != table.header_.size()) {
      throw CsvError(fmt::format("{}: has {} field{}, expected {} (one per header column)",
                                 table.where(row), fields.size(), fields.size() == 1 ? "" : "s",
                                 table.header_.size()));
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      if (fields[c].empty()) {
        throw CsvError(
            fmt::format("{}: empty field (valid: a value in every column)", table.where(row, c)));
      }
    }
    table.rows_.push_back(std::move(fields));
  }
  return table;
}

CsvTable read_csv(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw CsvError(fmt::format("'{}': cannot read the file: it is a directory", path.string()));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw CsvError(fmt::format("'{}': cannot read the file: {}", path.string(),
                               err != 0 ? std::strerror(err) : "cannot open file"));
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad())
    throw CsvError(fmt::format("'{}': cannot read the file: read error", path.string()));
  return parse_csv(ss.str(), path.string());
}

std::string format_double(double x) { return fmt::format("{:.17g}", x); }

CsvWriter::CsvWriter(std::ostream& out, std::span<const std::string_view> header)
    : out_(out), num_columns_(header.size()) {
  for (std::string_view h : header) cell(h);
  end_row();
}

CsvWriter::CsvWriter(std::ostream& out, std::initializer_list<std::string_view> header)
    : CsvWriter(out, std::span<const std::string_view>(header.begin(), header.size())) {}

CsvWriter::~CsvWriter() { flush(); }

void CsvWriter::separator() {
  if (cells_in_row_ > 0) buffer_ += ',';
  ++cells_in_row_;
}

CsvWriter& CsvWriter::cell(double x) {
  separator();
  fmt::format_to(std::back_inserter(buffer_), "{:.17g}", x);
  return *this;
}

CsvWriter& CsvWriter::cell(std::string_view text) {
  separator();
  buffer_ += text;
  return *this;
}

CsvWriter& CsvWriter::cell_int(long long x) {
  separator();
  fmt::format_to(std::back_inserter(buffer_), "{}", x);
  return *this;
}

void CsvWriter::end_row() {
  if (cells_in_row_ != num_columns_) {
    throw std::logic_error(fmt::format("CsvWriter: row has {} cells, header has {} columns",
                                       cells_in_row_, num_columns_));
  }
  buffer_ += '\n';
  cells_in_row_ = 0;
  if (buffer_.size() >= (std::size_t(1) << 16)) flush();
}

void CsvWriter::flush() {
  out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

void write_csv_atomic(const std::filesystem::path& path, std::span<const std::string_view> header,
                      const std::function<void(CsvWriter&)>& rows) {
  AtomicFile file(path);
  {
    CsvWriter w(file.stream(), header);
    rows(w);
  }  // the writer flushes its buffer here, before the commit
  file.commit();
}

void write_csv_atomic(const std::filesystem::path& path,
                      std::initializer_list<std::string_view> header,
                      const std::function<void(CsvWriter&)>& rows) {
  write_csv_atomic(path, std::span<const std::string_view>(header.begin(), header.size()), rows);
}

}  // namespace glintlab::io
