// `glintlab chermain-dictionary --out FILE.exr [--seed N] [--distributions N] [--levels L]
// [--resolution R] [--alpha-dict A] [--lobe-std S]`: regenerates the multiscale 1D dictionary of
// Chermain et al. 2020 (2021 Sec. 3, Fig. 3) deterministically and writes it as an EXR.
#include "core/glints/chermain_dictionary.h"

#include <fmt/format.h>
#include <tbb/global_control.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/input.h"
#include "core/parameter_check.h"

namespace glintlab::cli {

void add_chermain_dictionary_command(CLI::App& app) {
  // Texts, parsed in the callback so that every bad value gets the house error; the defaults
  // are the config's.
  struct Options {
    std::string out;
    chermain2021::DictionaryConfig config;
    std::string seed = std::to_string(config.seed),
                distributions = std::to_string(config.distributions),
                levels = std::to_string(config.levels),
                resolution = std::to_string(config.resolution),
                alpha_dict = fmt::format("{}", config.alpha_dict),
                lobe_std = fmt::format("{}", config.lobe_std), threads;
  };
  auto opt = std::make_shared<Options>();
  Options& o = *opt;
  CLI::App* cmd = add_command(
      app, "chermain-dictionary",
      "Regenerate the Chermain et al. 2020 dictionary of multiscale 1D slope marginals as an EXR "
      "(same options and seed -> identical file contents)");
  set_required(add_text_option(cmd, "--out", o.out,
                               "output EXR file (rows: (n/3)*levels + k; R,G,B: distributions)",
                               "FILE"));
  add_text_option(cmd, "--seed", o.seed,
                  "seed of the lobe means: an integer in [0, 18446744073709551615]", "INT");
  add_text_option(cmd, "--distributions", o.distributions, "N: a positive multiple of 3", "INT");
  add_text_option(cmd, "--levels", o.levels,
                  "L, levels 0..L-1 (level k: 2^k lobes): an integer in [1, 20]", "INT");
  add_text_option(cmd, "--resolution", o.resolution,
                  "texels over |slope| in [0, 4 sigma_o): a power of two in [4, 4096]", "INT");
  add_text_option(cmd, "--alpha-dict", o.alpha_dict,
                  "Beckmann alpha of the limit: a number in (0, 2]", "NUMBER");
  add_text_option(cmd, "--lobe-std", o.lobe_std,
                  "lobe standard deviation: a number in (0, alpha/sqrt 2)", "NUMBER");
  add_threads_option(cmd, o.threads);
  set_callback(cmd, [opt] {
    Options& c = *opt;
    const int threads = resolve_threads(c.threads);
    constexpr auto kIntMax = std::uint64_t(std::numeric_limits<int>::max());
    c.config.seed = integer_option(c.seed, "--seed", 0, UINT64_MAX);
    c.config.distributions = int(integer_option(c.distributions, "--distributions", 1, kIntMax));
    c.config.levels = int(integer_option(c.levels, "--levels", 1, 20));
    c.config.resolution = int(integer_option(c.resolution, "--resolution", 4, 4096));
    c.config.alpha_dict = parse_number(c.alpha_dict, "--alpha-dict", "a number in (0, 2]");
    c.config.lobe_std = parse_number(c.lobe_std, "--lobe-std", "a number in (0, alpha/sqrt 2)");
    try {
      validate(c.config);
    } catch (const ParameterError& e) {
      throw InputError(fmt::format("chermain-dictionary: {}", e.what()));
    }
    check_output_file(c.out, "--out");
    register_staging_parent(std::filesystem::path(c.out).has_parent_path()
                                ? std::filesystem::path(c.out).parent_path()
                                : std::filesystem::path("."));
    // The distributions are built in parallel; the file is the same for any thread count.
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(threads));
    const chermain2021::Dictionary d(c.config);
    try {
      chermain2021::write_chermain_dictionary_exr(c.out, d);
    } catch (const std::exception& e) {
      throw InputError(fmt::format("--out: {}", e.what()));
    }
    fmt::print("wrote {} ({} distributions x {} levels x {} texels, seed {})\n", c.out,
               c.config.distributions, c.config.levels, c.config.resolution, c.config.seed);
  });
}

}  // namespace glintlab::cli
