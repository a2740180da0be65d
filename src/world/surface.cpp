#include "trackphys/world/surface.hpp"

#include <algorithm>
#include <sstream>

#include "trackphys/error.hpp"

namespace trackphys {

std::string check_surface_table(std::span<const Surface> table, std::string_view name) {
    std::ostringstream why;
    if (table.size() > max_surfaces)
        why << name << " has " << table.size() << " entries, more than the " << max_surfaces
            << " surface ids";
    else if (const auto bad = std::find_if(
                 table.begin(), table.end(),
                 [](const Surface& s) { return !(s.grip > 0.0 && s.grip <= max_surface_grip); });
             bad != table.end())
        why << name << "[" << bad - table.begin() << "].grip must be in (0, "
            << exact_text(max_surface_grip) << "], got " << exact_text(bad->grip);
    return why.str();
}

}  // namespace trackphys
