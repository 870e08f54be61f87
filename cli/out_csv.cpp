// The --out CSV of eval and sample; see out_csv.h.
#include "cli/out_csv.h"

#include <stdexcept>

#include "cli/commands.h"

namespace glintlab::cli {

void write_out_csv(const std::string& path, std::span<const std::string_view> header,
                   const std::function<void(io::CsvWriter&)>& rows) {
  try {
    io::write_csv_atomic(path, header, rows);
  } catch (const std::runtime_error& e) {
    // AtomicFile reports an unwritable --out as std::runtime_error naming the path.
    throw InputError(std::string("--out: ") + e.what());
  }
}

void write_out_csv(const std::string& path, std::initializer_list<std::string_view> header,
                   const std::function<void(io::CsvWriter&)>& rows) {
  write_out_csv(path, std::span<const std::string_view>(header.begin(), header.size()), rows);
}

}  // namespace glintlab::cli
