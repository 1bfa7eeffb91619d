// Input text quoted in error messages. A message is a C string on its way out (what(), a terminal),
// so a NUL byte in a quoted token would cut it short and other control bytes would garble the
// terminal: they are written as escapes (\0, \t, \n, \r, \xNN), and a backslash as \\.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace dvoronoi::io {

/// `s` with control bytes (0x00-0x1F, 0x7F) and backslashes escaped; other bytes (UTF-8 included)
/// as they are.
inline std::string printable(std::string_view s) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    out.reserve(s.size());
    for (const char ch : s) {
        const auto u = static_cast<unsigned char>(ch);
        switch (ch) {
            case '\0': out += "\\0"; break;
            case '\t': out += "\\t"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\\': out += "\\\\"; break;
            default:
                if (u < 0x20 || u == 0x7F) {
                    out += "\\x";
                    out += hex[u >> 4];
                    out += hex[u & 15];
                } else {
                    out += ch;
                }
        }
    }
    return out;
}

/// `'s'` for a message: printable, and cut to its first `max` bytes ("..." marks the cut).
inline std::string in_quotes(std::string_view s, std::size_t max = 40) {
    return "'" + printable(s.substr(0, max)) + (s.size() > max ? "...'" : "'");
}

}  // namespace dvoronoi::io
