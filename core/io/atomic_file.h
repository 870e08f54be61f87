// Atomic output: write to a temporary file beside the target and rename it into place, so a
// failed run never leaves a partial output file.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace glintlab::io {

class AtomicFile {
 public:
  // Opens `<path>.tmp.<pid>`; throws std::runtime_error naming the path if that fails.
  explicit AtomicFile(std::filesystem::path path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  // Removes the temporary file unless commit() succeeded.
  ~AtomicFile();

  std::ofstream& stream() { return out_; }
  // Flushes, closes and renames over the target; throws std::runtime_error on failure.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path tmp_;
  std::ofstream out_;
  bool committed_ = false;
};

// Writes `text` to `path` atomically.
void write_file_atomic(const std::filesystem::path& path, const std::string& text);

}  // namespace glintlab::io
