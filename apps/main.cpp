// overflight: one program, one subcommand per job (DESIGN sec. 6).
#include "Commands.h"
#include "OptionErrors.h"
#include "core/Error.h"

#include <cstdio>
#include <exception>

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
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const overflight::Error& e) {
        std::fprintf(stderr, "overflight: %s\n", overflight::app::in_option_terms(e).what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "overflight: %s\n", e.what());
        return 1;
    }
    return 0;
}
