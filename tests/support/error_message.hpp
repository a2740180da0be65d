#pragma once

#include <string>

#include "trackphys/error.hpp"

namespace trackphys::test {

/// The message of the trackphys::Error that f throws, or "(no error)": tests match it
/// against what the message must name.
std::string error_of(auto&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace trackphys::test
