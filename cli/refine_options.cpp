#include "refine_options.h"

namespace eqhb::cli {

void addRefineOptions(CLI::App* cmd, RefineArguments& a) {
  cmd->add_option("--refine", a.method,
                  "shoot: harmonic balance followed by shooting; reports the exact periodic orbit (its Fourier "
                  "truncation on the same harmonics, its exact max|x|)")
      ->check(CLI::IsMember({"shoot"}));
  cmd->add_option("--restitution", a.restitution, "With --refine shoot: Newton impact coefficient e of contact laws")
      ->capture_default_str();
  cmd->add_option("--refine-harmonics", a.harmonics,
                  "With --refine shoot: the orbit's Fourier truncation on this many harmonics (default: --harmonics); "
                  "shooting costs about the same from any H, so a coarse solve can report many harmonics")
      ->check(CLI::PositiveNumber);
}

}  // namespace eqhb::cli
