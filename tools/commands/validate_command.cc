// `gearpath validate`: recompute, on the seed's Table-1 lumped model, the decoupling check of
// the seed's Fig. 5 and the noise-robustness table of its Table 2, and print them next to the
// seed's figures. A thin printer over core/inverse/table1_validation.h (which documents the
// error norms, the noise model and the identification system).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <vector>

#include "core/inverse/table1_validation.h"
#include "tools/commands/commands.h"
#include "tools/common/cli_checks.h"

namespace gearpath::tools {
namespace {

void PrintValidation(const Table1ValidationOptions& options, const Table1ValidationResult& r) {
  std::printf("Table-1 model, %d bins, %.0f-%.0f Hz\n\n", options.bins, options.f_lo_hz,
              options.f_hi_hz);
  std::printf("(a) Virtual vs physical decoupling (seed Fig. 5; seats = masses 4,5,6, housing = 7)\n");
  std::printf("    max rel. error = max over bins |virtual - physical| / |physical|\n");
  std::printf("    H_ij = response at mass i to a force at mass j (the seed's H_47 is our H_74)\n");
  std::printf("  %-8s %-6s %16s %20s\n", "system", "entry", "max rel. error", "FRAC");
  for (const DecouplingEntryError& e : r.decoupling) {
    std::printf("  %-8s %-6s %16.3e %20.15f\n", e.system.c_str(), e.entry.c_str(),
                e.max_relative_error, e.frac);
  }
  std::printf("\n(b) Force identification error (seed Table 2), ||F_hat - F||_F / ||F||_F over\n"
              "    all bins and the 3 bearing paths, mean of %d draws (seed %u) of complex\n"
              "    Gaussian noise per channel and bin, E|n|^2 = (level * RMS of that bin's responses)^2.\n"
              "    System: stacked [H_d,pp; H_d,mp] (4 channels x 3 paths, virtually decoupled).\n"
              "    Noise-free check, converged MWI (alpha 1e-8, K 1e5): %.2e\n",
              options.draws, options.seed, r.noise_free_error_mwi);
  std::printf("  %-34s", "method (rule)");
  for (double level : r.noise_levels) std::printf(" %12g", level);
  std::printf("\n");
  for (const IdentificationMethodResult& m : r.methods) {
    std::printf("  %-34s", m.name.c_str());
    for (double e : m.mean_error) std::printf(" %11.3f%%", 100.0 * e);
    std::printf("\n");
  }
  if (r.noise_levels == std::vector<double>{1e-4, 1e-3, 1e-2}) {
    std::printf("  %-34s %11.2f%% %11.2f%% %11.2f%%\n", "seed: MWI", 0.05, 0.11, 7.62);
    std::printf("  %-34s %11.2f%% %11.2f%% %11.2f%%\n", "seed: Tikhonov", 1.92, 17.28, 325.53);
  }
}

}  // namespace

void AddValidateCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<Table1ValidationOptions>();
  auto band = std::make_shared<std::vector<double>>(std::vector<double>{1.0, 4000.0});
  CLI::App* cmd = app.add_subcommand(
      "validate", "Recompute the seed's Fig. 5 decoupling check and Table 2 identification "
                  "errors on the Table-1 model");
  cmd->add_option("--draws", options->draws, "noise draws per level")
      ->capture_default_str()
      ->check(Positive());
  cmd->add_option("--seed", options->seed, "random seed of the noise")->capture_default_str();
  cmd->add_option("--band", *band, "frequency band F_LO F_HI in Hz")
      ->expected(2)
      ->capture_default_str();
  cmd->add_option("--bins", options->bins, "frequency bins in the band")->capture_default_str();
  cmd->callback([options, band, &exit_code] {
    options->f_lo_hz = (*band)[0];
    options->f_hi_hz = (*band)[1];
    Result<Table1ValidationResult> r = ValidateOnTable1Model(*options);
    if (!r) {
      std::fprintf(stderr, "gearpath validate: %s\n", r.error().c_str());
      exit_code = kExitBadInput;
      return;
    }
    PrintValidation(*options, *r);
    exit_code = kExitOk;
  });
}

}  // namespace gearpath::tools
