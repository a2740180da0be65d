#pragma once

#include "trackphys/world/world_settings.hpp"

namespace trackphys::cli {

/// The World settings the commands, the benchmark suite and the tests of several cars start
/// from: the phase clock on (they print phase times) and the hardware's threads (a race's
/// islands, the plane trees built at start), where the library's defaults are a game's
/// (profile off, one thread). States do not depend on either.
inline WorldSettings tool_world_settings() {
    WorldSettings settings;
    settings.profile = true;
    settings.threads = 0;
    return settings;
}

}  // namespace trackphys::cli
