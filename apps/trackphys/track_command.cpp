#include "commands.hpp"

namespace trackphys::cli {

void add_track_command(CLI::App& app) {
    app.add_subcommand("track", "(under construction)");
}

}  // namespace trackphys::cli
