#include "viewer_bundle.hpp"

namespace trackphys::cli {

std::string_view viewer_bundle() {
#ifdef TRACKPHYS_VIEWER_BUNDLE
    // viewer/build.mjs writes the bundle as a raw string literal: included, its contents
    // are part of this file for the compiler and for ccache alike.
    static constexpr char kBundle[] =
#include TRACKPHYS_VIEWER_BUNDLE
        ;
    return {kBundle, sizeof kBundle - 1};
#else
    return {};
#endif
}

}  // namespace trackphys::cli
