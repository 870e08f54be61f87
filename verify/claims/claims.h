// Per-paper check lists; verify/registry.cpp concatenates them into the registry.
#pragma once

#include <vector>

#include "verify/check.h"

namespace glintlab::verify {

std::vector<Check> smooth_checks();  // verify/claims/smooth.cpp
std::vector<Check> smooth_sampler_checks();  // verify/claims/smooth_samplers.cpp

}  // namespace glintlab::verify
