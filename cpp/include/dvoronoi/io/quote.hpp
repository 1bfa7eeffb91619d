// Input text quoted in error messages. A message is a C string on its way out (what(), a terminal),
// so a NUL byte in a quoted token would cut it short and other control bytes would garble the
// terminal: they are written as escapes (\0, \t, \n, \r, \xNN), and a backslash as \\. A message
// is also UTF-8 text on its way to Python (a ValueError's str): a byte that is not part of a
// well-formed UTF-8 sequence is written as \xNN too (before, Python raised UnicodeDecodeError in place
// of the ValueError), and a quote is never cut inside a character.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace dvoronoi::io {

namespace detail {

/// Length of the well-formed UTF-8 sequence of two or more bytes starting at s[k], or 0 (RFC 3629:
/// no overlong forms, no surrogates, nothing above U+10FFFF).
inline std::size_t utf8_sequence(std::string_view s, std::size_t k) {
    const auto at = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
    const unsigned a = at(k);
    std::size_t len = 0;
    unsigned lo = 0x80, hi = 0xBF;  // the range of the second byte
    if (a >= 0xC2 && a <= 0xDF) len = 2;
    else if (a >= 0xE0 && a <= 0xEF) len = 3, lo = a == 0xE0 ? 0xA0 : 0x80, hi = a == 0xED ? 0x9F : 0xBF;
    else if (a >= 0xF0 && a <= 0xF4) len = 4, lo = a == 0xF0 ? 0x90 : 0x80, hi = a == 0xF4 ? 0x8F : 0xBF;
    else return 0;
    if (k + len > s.size() || at(k + 1) < lo || at(k + 1) > hi) return 0;
    for (std::size_t i = 2; i < len; ++i)
        if (at(k + i) < 0x80 || at(k + i) > 0xBF) return 0;
    return len;
}

}  // namespace detail

/// `s` with control bytes (0x00-0x1F, 0x7F), backslashes and bytes outside well-formed UTF-8
/// escaped; well-formed UTF-8 as it is. The result is valid UTF-8.
inline std::string printable(std::string_view s) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    out.reserve(s.size());
    for (std::size_t k = 0; k < s.size(); ++k) {
        const char ch = s[k];
        const auto u = static_cast<unsigned char>(ch);
        switch (ch) {
            case '\0': out += "\\0"; break;
            case '\t': out += "\\t"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\\': out += "\\\\"; break;
            default:
                if (u >= 0x80) {
                    if (const std::size_t len = detail::utf8_sequence(s, k)) {
                        out.append(s.substr(k, len));
                        k += len - 1;
                        break;
                    }
                }
                if (u < 0x20 || u >= 0x7F) {
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

/// `'s'` for a message: printable, and cut to its first `max` bytes, or fewer so that no UTF-8
/// character is cut ("..." marks the cut).
inline std::string in_quotes(std::string_view s, std::size_t max = 40) {
    if (s.size() <= max) return "'" + printable(s) + "'";
    std::size_t cut = max;
    while (cut > 0 && max - cut < 3 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
    return "'" + printable(s.substr(0, cut)) + "...'";
}

}  // namespace dvoronoi::io
