// `glintlab schema`: the JSON Schema of a file the program writes (cli/schema.cpp).
#pragma once

#include "cli/cli11_fwd.h"

namespace glintlab::cli {

void add_schema_command(CLI::App& app);

}  // namespace glintlab::cli
