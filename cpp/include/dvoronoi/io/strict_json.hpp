// Reading JSON input documents (obstacle files): nlohmann's parser, plus what it accepts silently but
// a document must not have. Every error names NAME:LINE:COLUMN (1-based line, byte column):
//   * a syntax error, at the first character of the offending token;
//   * a key repeated within one object ({"radius": 1, "radius": 2}: the parser keeps the last, so a
//     typo or a merge conflict would pass unseen), naming the key and where it first appeared;
//   * a number beyond the range of a double (1e999: the parser either refuses it without a
//     position or reads it as infinity).
// Text quoted from the document is escaped (io/quote.hpp).
#pragma once

#include "dvoronoi/core/types.hpp"
#include "dvoronoi/io/quote.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dvoronoi::io {

namespace detail {

/// "NAME:LINE:COLUMN" of byte `offset` of `text`.
inline std::string json_where(std::string_view text, std::size_t offset, const std::string& name) {
    offset = std::min(offset, text.size());
    std::size_t line = 1, line_start = 0;
    for (std::size_t k = 0; k < offset; ++k)
        if (text[k] == '\n') ++line, line_start = k + 1;
    return name + ":" + std::to_string(line) + ":" + std::to_string(offset - line_start + 1);
}

/// Walks JSON text that nlohmann's parser accepted (or refused only for a number's range) and throws
/// InputError at the first repeated key or out-of-range number.
inline void check_keys_and_numbers(std::string_view text, const std::string& name) {
    struct Frame {
        bool object = false;
        bool expect_key = false;
        std::map<std::string, std::size_t> keys;  // key -> offset of its first occurrence
    };
    std::vector<Frame> stack;
    const std::size_t n = text.size();
    std::size_t i = 0;
    while (i < n) {
        const char ch = text[i];
        if (ch == '{' || ch == '[') {
            stack.emplace_back();
            stack.back().object = ch == '{';
            stack.back().expect_key = ch == '{';
            ++i;
        } else if (ch == '}' || ch == ']') {
            if (!stack.empty()) stack.pop_back();
            ++i;
        } else if (ch == ',') {
            if (!stack.empty() && stack.back().object) stack.back().expect_key = true;
            ++i;
        } else if (ch == '"') {
            std::size_t j = i + 1;
            while (j < n && text[j] != '"') j += text[j] == '\\' ? 2 : 1;
            const std::string_view token = text.substr(i, std::min(j + 1, n) - i);
            if (!stack.empty() && stack.back().object && stack.back().expect_key) {
                Frame& f = stack.back();
                f.expect_key = false;
                std::string key(token.substr(1, token.size() >= 2 ? token.size() - 2 : 0));
                if (key.find('\\') != std::string::npos) {
                    try {
                        key = nlohmann::json::parse(token).get<std::string>();
                    } catch (const nlohmann::json::exception&) {  // not reached after a full parse; never escapes
                        throw InputError(json_where(text, i, name) + ": invalid JSON: malformed key " + in_quotes(key));
                    }
                }
                const auto [at, fresh] = f.keys.emplace(key, i);
                if (!fresh)
                    throw InputError(json_where(text, i, name) + ": duplicate key " + in_quotes(key) +
                                     " in one object (first at " + json_where(text, at->second, name) +
                                     "); a key may appear once");
            }
            i = j + 1;
        } else if (ch == '-' || (ch >= '0' && ch <= '9')) {
            std::size_t j = i;
            while (j < n && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '-' || text[j] == '+' ||
                             text[j] == '.' || text[j] == 'e' || text[j] == 'E'))
                ++j;
            const std::string number(text.substr(i, j - i));
            errno = 0;
            const double v = std::strtod(number.c_str(), nullptr);
            if (std::isinf(v))
                throw InputError(json_where(text, i, name) + ": number " + in_quotes(number) +
                                 " is beyond the range of a double (about 1.8e308)");
            i = j;
        } else {
            ++i;  // whitespace, ':', true, false, null
        }
    }
}

}  // namespace detail

/// Parses a JSON document. `name` (a file name, or a label such as "obstacles") starts every message.
/// \throws InputError "NAME:LINE:COLUMN: ..." for a syntax error, a key repeated within one object, or
///         a number beyond the range of a double.
/// \note O(size of the text): the text is parsed, then walked once more for keys and numbers.
inline nlohmann::json parse_json(std::string_view text, const std::string& name) {
    using nlohmann::json;
    // A NUL byte ended the parser's input early: '"a"\0{...' was the document "a", and the key walk
    // below then met the rest (a parse_error escaped: RuntimeError in Python, status 1 from the CLI).
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos)
        throw InputError(detail::json_where(text, nul, name) + ": invalid JSON: a NUL byte (JSON text has none)");
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        // nlohmann reports the last byte it read (1-based); point at the first character of that token
        std::size_t idx = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.empty() ? 0 : text.size() - 1);
        auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+'; };
        if (!text.empty() && text[idx] == '"' && idx > 0) {
            std::size_t k = idx;
            while (k > 0 && !(text[k - 1] == '"' && (k < 2 || text[k - 2] != '\\'))) --k;
            if (k > 0) idx = k - 1;
        } else if (!text.empty() && word(text[idx])) {
            while (idx > 0 && word(text[idx - 1])) --idx;
        }
        const std::string what = e.what();
        const auto pos = what.find("syntax error");
        throw InputError(detail::json_where(text, idx, name) + ": invalid JSON: " +
                         printable(pos == std::string::npos ? what : what.substr(pos)));
    } catch (const json::out_of_range&) {
        detail::check_keys_and_numbers(text, name);  // finds the number and names its place
        throw InputError(name + ": invalid JSON: a number is beyond the range of a double");
    }
    detail::check_keys_and_numbers(text, name);
    return doc;
}

}  // namespace dvoronoi::io
