// Serialisation of a verify run: claims.json (for tools and the report), claims.csv, claims.md.
#pragma once

#include <string>
#include <vector>

#include "verify/check.h"

namespace glintlab::verify {

struct RunRecord {
  const Check* check;
  CheckResult result;
  double seconds;
};

struct RunInfo {
  std::string budget;   // quick | full
  int threads;          // worker threads the run was allowed
  std::string machine;  // a short description of the machine
};

std::string to_json(const std::vector<RunRecord>& records, const RunInfo& info);
std::string to_csv(const std::vector<RunRecord>& records);
std::string to_markdown(const std::vector<RunRecord>& records, const RunInfo& info);

// True when the verdict is the one recorded for the check and its control was rejected.
bool as_expected(const RunRecord& r);

}  // namespace glintlab::verify
