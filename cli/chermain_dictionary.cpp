// `glintlab chermain-dictionary --out FILE.exr [--seed N] [--distributions N] [--levels L]
// [--resolution R] [--alpha-dict A] [--lobe-std S]`: regenerates the multiscale 1D dictionary of
// Chermain et al. 2020 (2021 Sec. 3, Fig. 3) deterministically and writes it as an EXR.
#include "core/glints/chermain_dictionary.h"

#include <fmt/format.h>

#include <memory>
#include <string>

#include "cli/commands.h"
#include "core/parameter_check.h"

namespace glintlab::cli {

void add_chermain_dictionary_command(CLI::App& app) {
  struct Options {
    std::string out;
    chermain2021::DictionaryConfig config;
  };
  auto opt = std::make_shared<Options>();
  Options& o = *opt;
  CLI::App* cmd = app.add_subcommand(
      "chermain-dictionary",
      "Regenerate the Chermain et al. 2020 dictionary of multiscale 1D slope marginals as an EXR "
      "(same options and seed -> identical file contents)");
  cmd->add_option("--out", o.out, "output EXR (rows: (n/3)*levels + k; R,G,B: distributions)")
      ->required();
  cmd->add_option("--seed", o.config.seed, "seed of the lobe means")->capture_default_str();
  cmd->add_option("--distributions", o.config.distributions, "N, a positive multiple of 3")
      ->capture_default_str();
  cmd->add_option("--levels", o.config.levels, "L, levels 0..L-1 (level k: 2^k lobes), 1..20")
      ->capture_default_str();
  cmd->add_option("--resolution", o.config.resolution,
                  "texels over |slope| in [0, 4 sigma_o), a power of two 4..4096")
      ->capture_default_str();
  cmd->add_option("--alpha-dict", o.config.alpha_dict, "Beckmann alpha of the limit, (0, 2]")
      ->capture_default_str();
  cmd->add_option("--lobe-std", o.config.lobe_std, "lobe standard deviation, (0, alpha/sqrt 2)")
      ->capture_default_str();
  cmd->callback([opt] {
    const Options& c = *opt;
    try {
      validate(c.config);
    } catch (const ParameterError& e) {
      throw InputError(fmt::format("chermain-dictionary: {}", e.what()));
    }
    const chermain2021::Dictionary d(c.config);
    chermain2021::write_chermain_dictionary_exr(c.out, d);
    fmt::print("wrote {} ({} distributions x {} levels x {} texels, seed {})\n", c.out,
               c.config.distributions, c.config.levels, c.config.resolution, c.config.seed);
  });
}

}  // namespace glintlab::cli
