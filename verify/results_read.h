// Reading a verify run back: the rows of claims.json as RunRecords, so that `glintlab merge` can
// write the files of one run from the shards' rows (the suite adjustment recomputed over all).
#pragma once

#include <string>
#include <vector>

#include "verify/results.h"

namespace glintlab::verify {

// The rows of a claims.json text (verify::to_json's output) as RunRecords of the registered checks,
// in the file's order: every measured field of CheckResult and the seconds; suite_adjusted_p is
// left empty (adjust_for_suite recomputes it). A value written as null (JSON has no NaN) reads as
// NaN. std::invalid_argument naming `source` and the row on text that is not such a file, a row
// of an unregistered check, or a row of another budget than `budget`.
std::vector<RunRecord> read_records(const std::string& claims_json, Budget budget,
                                    const std::string& source);

}  // namespace glintlab::verify
