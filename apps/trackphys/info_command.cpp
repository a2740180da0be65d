#include "commands.hpp"

namespace trackphys::cli {

void add_info_command(CLI::App& app) {
    app.add_subcommand("info", "(under construction)");
}

}  // namespace trackphys::cli
