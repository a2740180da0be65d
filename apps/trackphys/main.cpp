#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "command_line.hpp"
#include "trackphys/build_target.hpp"
#include "trackphys/error.hpp"

namespace {

// A report lost to a full disk or a closed pipe is a failure: stdout is fully buffered when
// it is not a terminal, so a write error often shows only at this last flush.
int check_stdout(int exit_code) {
    errno = 0;
    if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return exit_code;
    const int error = errno;
    std::fprintf(stderr, "trackphys: error: cannot write to standard output%s%s\n",
                 error != 0 ? ": " : "", error != 0 ? std::strerror(error) : "");
    return exit_code != 0 ? exit_code : 1;
}

}  // namespace

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
    trackphys::cli::add_commands(app);

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
        return check_stdout(app.exit(e));
    } catch (const trackphys::Error& e) {
        std::fprintf(stderr, "trackphys: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trackphys: unexpected error: %s\n", e.what());
        return 2;
    }
    return check_stdout(0);
}
