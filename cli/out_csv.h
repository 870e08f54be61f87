// The --out CSV file of `glintlab eval` and `glintlab sample` (with or without --model): written
// atomically (core/io/csv.h write_csv_atomic), a failure reported as the one-line --out error.
#pragma once

#include <functional>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

#include "core/io/csv.h"

namespace glintlab::cli {

// Writes `path` (the header, then what `rows` writes) or nothing; a std::runtime_error on the
// way (AtomicFile's, naming the path) becomes InputError("--out: <its message>").
void write_out_csv(const std::string& path, std::span<const std::string_view> header,
                   const std::function<void(io::CsvWriter&)>& rows);
void write_out_csv(const std::string& path, std::initializer_list<std::string_view> header,
                   const std::function<void(io::CsvWriter&)>& rows);

}  // namespace glintlab::cli
