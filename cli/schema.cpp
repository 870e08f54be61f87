// `glintlab schema FILE`: prints the JSON Schema of a file glintlab writes, so that tools reading
// it (the report, a user's scripts) check it against the program instead of a copy of its format.
#include "cli/schema.h"

#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/input.h"
#include "verify/claims_schema.h"

namespace glintlab::cli {
namespace {

struct Described {
  const char* file;
  std::string (*schema)();
};

constexpr Described kDescribed[] = {{"claims.json", verify::claims_json_schema}};

std::string valid_names() {
  std::string names;
  for (const Described& d : kDescribed)
    names += fmt::format("{}{}", names.empty() ? "" : ", ", d.file);
  return names;
}

}  // namespace

void add_schema_command(CLI::App& app) {
  CLI::App* cmd = add_command(app, "schema",
                              "Print the JSON Schema (draft 2020-12) of a file glintlab writes: "
                              "every field, its type and what it means");
  auto names = std::make_shared<std::vector<std::string>>();
  add_positional_list(cmd, "file", *names, "the file's name: " + valid_names(), "FILE");
  set_footer(cmd,
             "claims.json: the rows of glintlab verify (and of a report's verify/ and "
             "conformance/ parts); glintlab report checks them against this schema.");
  set_callback(cmd, [names] {
    if (names->size() != 1)
      throw InputError(fmt::format("schema: needs one file name, got {} (valid: {})", names->size(),
                                   valid_names()));
    for (const Described& d : kDescribed)
      if (names->front() == d.file) {
        fmt::print("{}", d.schema());
        return;
      }
    throw InputError(fmt::format("schema: '{}' is not a file glintlab describes (valid: {})",
                                 names->front(), valid_names()));
  });
}

}  // namespace glintlab::cli
