// JSON input documents: what nlohmann's parser accepts silently (a key twice in one object, 1e999) is
// refused, and every error names FILE:LINE:COLUMN.
#include "dvoronoi/io/strict_json.hpp"

#include <doctest/doctest.h>

#include <string>

using dvoronoi::InputError;
using dvoronoi::io::parse_json;

namespace {
/// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text) {
    try {
        parse_json(text, "d.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST_CASE("valid documents parse as nlohmann's parser reads them") {
    const auto j = parse_json(R"({"a": [1, {"a": 2, "b": "x\"}"}], "b": {"a": {"a": -1.5e300}}, "c": true})", "d");
    CHECK(j["a"][1]["a"] == 2);
    CHECK(j["a"][1]["b"] == "x\"}");
    CHECK(j["b"]["a"]["a"] == -1.5e300);
    // The same key in different objects, in arrays of objects, after a nested object: fine.
    CHECK(error_of(R"([{"k": 1}, {"k": 2}, {"k": {"k": {"k": 3}}, "j": 0}])") == "");
    CHECK(error_of(R"({"k": {"x": 1}, "x": 2})") == "");
    CHECK(error_of("1e308") == "");
    CHECK(error_of("1e-400") == "");  // rounds to 0, like any rounding
}

TEST_CASE("a key twice in one object is an error at the second, naming the first") {
    // Before: the obstacle loader kept the last "radius" and said nothing.
    CHECK(error_of("{\"r\": 1,\n \"s\": 2,\n   \"r\": 3}") ==
          "d.json:3:4: duplicate key 'r' in one object (first at d.json:1:2); a key may appear once");
    CHECK(error_of(R"({"o": [{"a": 1, "b": {"a": 2}, "a": 3}]})") ==
          "d.json:1:32: duplicate key 'a' in one object (first at d.json:1:9); a key may appear once");
    // Keys are compared as strings, escapes decoded.
    CHECK(error_of(R"({"ab": 1, "a\u0062": 2})") ==
          "d.json:1:11: duplicate key 'ab' in one object (first at d.json:1:2); a key may appear once");
    // A key holding a NUL byte is escaped in the message.
    CHECK(error_of(R"({"a\u0000b": 1, "a\u0000b": 2})") ==
          "d.json:1:17: duplicate key 'a\\0b' in one object (first at d.json:1:2); a key may appear once");
}

TEST_CASE("a number beyond the range of a double is an error at its place") {
    // Before: nlohmann threw out_of_range.406 without a place (the CLI), Python read it as inf.
    CHECK(error_of("{\"a\": [0,\n  1e999]}") == "d.json:2:3: number '1e999' is beyond the range of a double (about 1.8e308)");
    CHECK(error_of("[-2E+400]") == "d.json:1:2: number '-2E+400' is beyond the range of a double (about 1.8e308)");
}

TEST_CASE("syntax errors name the first character of the offending token") {
    CHECK(error_of("{\"a\": [,]}").rfind("d.json:1:8: invalid JSON: syntax error", 0) == 0);
    CHECK(error_of("{\"a\": 1\n \"b\": 2}").rfind("d.json:2:2: invalid JSON: syntax error", 0) == 0);
    CHECK(error_of("").rfind("d.json:1:1: invalid JSON", 0) == 0);
}

TEST_CASE("a NUL byte is an error at its place (it ended the parser's input)") {
    // issue 20's fuzzing: '"type"\0{..., "\0bst\u0061cles": []}' parsed as the string "type", and the
    // key walk's parse of the escaped key threw nlohmann's parse_error, not an InputError
    const std::string text("\"type\"\0{\"area\": 1, \"\0bst\\u0061cles\": []}", 40);
    CHECK(error_of(text) == "d.json:1:7: invalid JSON: a NUL byte (JSON text has none)");
    CHECK(error_of(std::string("{\"a\": 1}\n\0", 10)) == "d.json:2:1: invalid JSON: a NUL byte (JSON text has none)");
}
