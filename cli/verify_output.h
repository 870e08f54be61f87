// What `glintlab verify` and `glintlab merge` write and print for a run's records: the suite's
// Holm–Šidák adjustment over every row, claims.json, claims.csv and claims.md in `out`, the
// verdict table on stdout, and the exit status (0 as recorded, 1 a verdict differs or a control
// was not rejected, 3 a check could not run).
#pragma once

#include <string>
#include <vector>

#include "verify/results.h"

namespace glintlab::cli {

int write_verify_run(std::vector<verify::RunRecord>& records, const verify::RunInfo& info,
                     const std::string& out);

}  // namespace glintlab::cli
