#pragma once
/// Subcommands of the `radiosity` executable. Each add_* registers its options on `app` and,
/// when that subcommand is chosen, stores the work to do in `run` (executed after parsing, so
/// usage errors are all reported before any work starts).
#include <CLI/CLI.hpp>
#include <functional>

namespace rad::cli {

using Run = std::function<void()>;

void add_info_command(CLI::App& app, Run& run);
void add_render_command(CLI::App& app, Run& run);
void add_solve_command(CLI::App& app, Run& run);
void add_probe_command(CLI::App& app, Run& run);
void add_sweep_command(CLI::App& app, Run& run);
void add_compare_command(CLI::App& app, Run& run);
void add_export_command(CLI::App& app, Run& run);

}  // namespace rad::cli
