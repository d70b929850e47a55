// overflight: one program, one subcommand per job (DESIGN sec. 6).
#include "Commands.h"
#include "Loading.h"
#include "OptionErrors.h"
#include "StandardOutput.h"
#include "core/Error.h"

#include <cstdio>
#include <exception>
#include <new>
#include <string>

int main(int argc, char** argv) {
    CLI::App app{"Overflight: fly over large height-field terrains with objects on them"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "overflight 0.1.0");
    overflight::app::add_info_command(app);
    overflight::app::add_render_command(app);
    overflight::app::add_bench_command(app);
    overflight::app::add_sim_command(app);
    overflight::app::add_fly_command(app);
    overflight::app::add_tile_command(app);
    overflight::app::add_web_command(app);
    try {
        app.parse(argc, argv);
        overflight::app::finish_stdout();
    } catch (const CLI::ParseError& e) {
        // --help and --version print as CLI11 formats them; a bad command line
        // is one line and exit 1 like every other error of the user's
        // ("overflight: --steps: '1x' is not a whole decimal number").
        if (e.get_exit_code() == 0) return app.exit(e);
        std::fprintf(stderr, "overflight: %s\n", e.what());
        return 1;
    } catch (const overflight::Error& e) {
        std::fprintf(stderr, "overflight: %s\n", overflight::app::in_option_terms(e).what());
        return 1;
    } catch (const std::bad_alloc&) {
        // The last resort: loaders report their own sizes, but a process
        // limit can still stop an allocation they could not foresee.
        const std::string& what = overflight::app::being_loaded();
        if (!what.empty()) {
            std::fprintf(stderr, "overflight: %s: not enough memory to load it\n", what.c_str());
        } else {
            const auto commands = app.get_subcommands();
            std::fprintf(stderr, "overflight: %s: not enough memory\n",
                         commands.empty() ? "overflight" : commands.front()->get_name().c_str());
        }
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "overflight: %s\n", e.what());
        return 1;
    }
    return 0;
}
