#include "trackphys/error.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace trackphys {

std::string exact_text(double x) {
    char text[32];  // the longest shortest form, "-2.2250738585072014e-308", takes 24
    return {text, std::to_chars(text, text + sizeof text, x).ptr};
}

std::string quoted_text(std::string_view text) {
    constexpr std::size_t shown_at_most = 120;
    std::size_t shown = std::min(text.size(), shown_at_most);
    // Not inside a UTF-8 sequence (at most 4 bytes): back to its lead byte, if it has one.
    for (int back = 0; back < 3 && shown < text.size() && (text[shown] & 0xC0) == 0x80; ++back)
        --shown;
    std::string quoted = "'";
    for (const char c : text.substr(0, shown)) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte != 0x7F) {
            quoted += c;
            continue;
        }
        char escape[5];
        std::snprintf(escape, sizeof escape, "\\x%02x", byte);
        quoted += escape;
    }
    quoted += '\'';
    if (shown < text.size())
        quoted += " (the first " + std::to_string(shown) + " of " + std::to_string(text.size()) +
                  " bytes)";
    return quoted;
}

}  // namespace trackphys
