#pragma once
// Each subcommand of DESIGN sec. 6 lives in its own cmd_*.cpp and registers
// itself here. Subcommands parse, call the libraries and print; no algorithm
// lives in apps/.
#include <CLI/CLI.hpp>

namespace overflight::app {

void add_info_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_tile_command(CLI::App& app);
void add_sim_command(CLI::App& app);
void add_fly_command(CLI::App& app);
void add_web_command(CLI::App& app);

} // namespace overflight::app
