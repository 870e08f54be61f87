// Per-paper check lists; verify/registry.cpp concatenates them into the registry.
#pragma once

#include <vector>

#include "verify/check.h"

namespace glintlab::verify {

std::vector<Check> smooth_checks();  // verify/claims/smooth.cpp
std::vector<Check> smooth_consistency_checks();  // verify/claims/smooth_consistency.cpp
std::vector<Check> eto_checks();  // verify/claims/eto.cpp
std::vector<Check> kneiphof_checks();  // verify/claims/kneiphof.cpp

}  // namespace glintlab::verify
