#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "trackphys/export.hpp"

namespace trackphys {

/// Every error trackphys reports on bad input: a mesh file it cannot read, an invalid
/// ellipsoid, an inconsistent configuration. The message names the thing and the reason.
class TRACKPHYS_API Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// A number as trackphys's messages show it: the shortest text that reads back as the same
/// double ("0.1", "10.0000001", "1e+300", "-inf", "nan"). Six significant digits, as streams
/// and %g give, would show a value just past a bound as the bound ("must be <= 10, got 10"),
/// and std::to_string's six decimals a small negative one as "-0.000000".
TRACKPHYS_API std::string exact_text(double x);

/// Text read from a file (a name, a keyword, a key) as trackphys's messages quote it: in
/// single quotes, control characters as \xNN (a NUL would end the message early, an escape
/// sequence would drive the reader's terminal), and at most 120 bytes of a longer one, its
/// length said.
TRACKPHYS_API std::string quoted_text(std::string_view text);

}  // namespace trackphys
