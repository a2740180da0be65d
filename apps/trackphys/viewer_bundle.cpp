#include "viewer_bundle.hpp"

namespace trackphys::cli {

std::string_view viewer_bundle() {
#ifdef TRACKPHYS_VIEWER_BUNDLE
    // viewer/build.mjs writes the bundle as a raw string literal: included, its contents
    // are part of this file for the compiler and for ccache alike. GCC and Clang take
    // literals far beyond the 65,536 characters the standard guarantees (-Wpedantic's
    // -Woverlength-strings), and the bundle is ten times that.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Woverlength-strings"
    static constexpr char kBundle[] =
#include TRACKPHYS_VIEWER_BUNDLE
        ;
#pragma GCC diagnostic pop
    return {kBundle, sizeof kBundle - 1};
#else
    return {};
#endif
}

}  // namespace trackphys::cli
