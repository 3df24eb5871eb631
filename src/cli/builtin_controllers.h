// The built-in controllers of `prs test` that live in other stages (the simulated case study),
// registered with the harness's registry before the command looks them up.
#pragma once

namespace prs::cli {

/// Registers `table-cube` (src/sim's case-study controller). Idempotent and thread-safe.
void RegisterBuiltInControllers();

}  // namespace prs::cli
