#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "trackphys/build_target.hpp"
#include "trackphys/error.hpp"

int main(int argc, char** argv) {
    if (!trackphys::cpu_runs_build_target()) {
        std::fprintf(stderr,
                     "trackphys: error: this build is for %s CPUs and this one lacks some of its "
                     "instructions; rebuild with cmake -DTRACKPHYS_X86_64_LEVEL=v1\n",
                     trackphys::build_target());
        return 1;
    }
    CLI::App app{"trackphys: racing-game physics, ellipsoid cars on triangle-mesh tracks",
                 "trackphys"};
    app.require_subcommand(1);
    trackphys::cli::add_drive_command(app);
    trackphys::cli::add_race_command(app);
    trackphys::cli::add_track_command(app);
    trackphys::cli::add_info_command(app);
    trackphys::cli::add_bake_command(app);
    trackphys::cli::add_bench_command(app);
    trackphys::cli::add_view_command(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // CLI11 says only "A subcommand is required" for a word that names no command.
        if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
            std::string commands;
            for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
                commands += (commands.empty() ? "" : ", ") + command->get_name();
            std::fprintf(stderr, "trackphys: error: '%s' is not a command (%s; see --help)\n",
                         argv[1], commands.c_str());
            return e.get_exit_code();
        }
        return app.exit(e);
    } catch (const trackphys::Error& e) {
        std::fprintf(stderr, "trackphys: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trackphys: unexpected error: %s\n", e.what());
        return 2;
    }
    return 0;
}
