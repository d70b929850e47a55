#include "Commands.h"

namespace overflight::app {
void add_info_command(CLI::App& app) { app.add_subcommand("info", "Describe a terrain"); }
} // namespace overflight::app
