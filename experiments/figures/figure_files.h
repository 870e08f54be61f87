// Atomic CSV and text outputs of a figure (core/io/atomic_file.h: a failed run leaves no file).
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"

namespace glintlab::experiments {

inline void write_figure_csv(const std::filesystem::path& path,
                             std::span<const std::string_view> header,
                             const std::function<void(io::CsvWriter&)>& rows) {
  io::AtomicFile file(path);
  {
    io::CsvWriter w(file.stream(), header);
    rows(w);
  }
  file.commit();
}

inline void write_figure_text(const std::filesystem::path& path, const std::string& text) {
  io::AtomicFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace glintlab::experiments
