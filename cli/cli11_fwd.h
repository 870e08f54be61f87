// CLI11's two types by name, for the headers and units that only pass them on: <CLI/CLI.hpp>
// costs about 4 s of compile time in every unit that includes it (docs/building.md), so only
// the units that configure options themselves include it.
#pragma once

namespace CLI {
class App;
class Option;
}  // namespace CLI
