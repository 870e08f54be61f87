// The JSON Schema of the claims.json glintlab verify writes (verify/results.cpp), as the program
// prints it (`glintlab schema claims.json`): every field, its type and meaning, the verdicts. The
// report (reports/make_report.py) checks a claims.json against this schema instead of keeping its
// own copy of the format, and a test keeps the schema and the writer in step.
#pragma once

#include <array>
#include <string>

#include "verify/check.h"

namespace glintlab::verify {

// Every verdict, in the order of the enum.
inline constexpr std::array<Verdict, 7> kEveryVerdict = {
    Verdict::kHolds,        Verdict::kHoldsWithin, Verdict::kHoldsInRegime, Verdict::kFails,
    Verdict::kInconclusive, Verdict::kNotClaimed,  Verdict::kError};

// JSON Schema (draft 2020-12) of claims.json, two-space indented, ending in a newline.
std::string claims_json_schema();

}  // namespace glintlab::verify
