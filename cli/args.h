// Validation shared by the subcommands: NDF names, roughness and unit directions (the dispatch
// from a runtime NDF to the templated kernels is with_ndf, core/ndf/ndf_kind.h). Every check throws
// cli::InputError with a one-line message "<where>: <problem> (valid: <range>)".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "core/math/vec.h"
#include "core/ndf/ndf_kind.h"

namespace glintlab::cli {

inline constexpr std::string_view kNdfNames = "ggx, beckmann";
inline constexpr double kUnitTolerance = 1e-6;

// "ggx" or "beckmann"; throws InputError naming `where` otherwise.
NdfKind parse_ndf(std::string_view text, std::string_view where);
std::string_view ndf_name(NdfKind kind);

// The canonical spelling of `text` given to `option`: an old spelling the CLI still accepts
// (`--sampler caps`, `--sampler bounded`, `--bound exact-isotropic`) is replaced by its canonical
// name, with one line on stderr: "glintlab: note: --sampler caps is spelled spherical_caps". Any
// other text is returned as it is.
std::string canonical_spelling(std::string_view option, std::string_view text);

// Throws unless α is finite and > 0.
void check_alpha(double alpha, std::string_view where);
// Throws unless |‖w‖ − 1| ≤ 1e-6; the message gives the length.
void check_unit(Vec3<double> w, std::string_view where);

// Parses a decimal number (finite) / a comma-separated list of them; throws naming `where` and
// `valid` (the description of the valid range used in the message).
double parse_number(std::string_view text, std::string_view where, std::string_view valid);
std::vector<double> parse_number_list(std::string_view text, std::string_view where,
                                      std::string_view valid);
// Parses "x,y,z", three numbers of a unit vector (check_unit); throws naming `where`.
Vec3<double> parse_unit_direction(std::string_view text, std::string_view where);
// Parses a non-negative decimal integer in [lo, hi]; throws naming `where` and the range.
std::uint64_t parse_integer(std::string_view text, std::string_view where, std::uint64_t lo,
                            std::uint64_t hi);

}  // namespace glintlab::cli
