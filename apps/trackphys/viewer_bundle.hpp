#pragma once

#include <string_view>

namespace trackphys::cli {

/// The replay viewer's JavaScript (viewer/, bundled by esbuild at build time and embedded
/// into the executable, so an installed `trackphys view` needs no other file); empty when
/// the build left the viewer out (TRACKPHYS_BUILD_VIEWER=OFF).
std::string_view viewer_bundle();

}  // namespace trackphys::cli
