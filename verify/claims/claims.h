// Per-paper check lists; verify/registry.cpp concatenates them into the registry. A paper whose
// claims are types (verify/claim.h) has a list of types instead: verify/claims/<paper>/list.h.
#pragma once

#include <vector>

#include "verify/check.h"

namespace glintlab::verify {

std::vector<Check> kemppinen_glint_checks();  // verify/claims/kemppinen_glints.cpp

}  // namespace glintlab::verify
