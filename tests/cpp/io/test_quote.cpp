// Input text in messages: control bytes escaped, so a NUL cannot end the message early.
#include "dvoronoi/io/quote.hpp"

#include <doctest/doctest.h>

#include <string>

using dvoronoi::io::in_quotes;
using dvoronoi::io::printable;

TEST_CASE("control bytes and backslashes are escaped; everything else is kept") {
    CHECK(printable(std::string("a\0b", 3)) == "a\\0b");
    CHECK(printable("\t\n\r\\") == "\\t\\n\\r\\\\");
    CHECK(printable("\x01\x1f\x7f") == "\\x01\\x1f\\x7f");
    CHECK(printable("x y,\"'\xc3\xa9") == "x y,\"'\xc3\xa9");  // UTF-8 stays
    CHECK(printable("") == "");
}

TEST_CASE("in_quotes cuts after max bytes and marks the cut") {
    CHECK(in_quotes("abc") == "'abc'");
    CHECK(in_quotes(std::string(41, 'a')) == "'" + std::string(40, 'a') + "...'");
    CHECK(in_quotes(std::string(40, 'a')) == "'" + std::string(40, 'a') + "'");
    CHECK(in_quotes(std::string("\0\0", 2), 1) == "'\\0...'");
}

TEST_CASE("bytes outside well-formed UTF-8 are escaped, so a message is always valid UTF-8") {
    // Before: kept as they were, so Python's ValueError became a UnicodeDecodeError (issue 20's fuzzing:
    // an obstacle file with "\xff\xfe" in a string)
    CHECK(printable("a\xff\xfe") == "a\\xff\\xfe");
    CHECK(printable("\xc3") == "\\xc3");                            // a lead byte at the end
    CHECK(printable("\xc3(") == "\\xc3(");                          // a lead byte without its continuation
    CHECK(printable("\x80") == "\\x80");                            // a lone continuation byte
    CHECK(printable("\xc0\xaf") == "\\xc0\\xaf");                   // overlong
    CHECK(printable("\xed\xa0\x80") == "\\xed\\xa0\\x80");          // a surrogate
    CHECK(printable("\xf4\x90\x80\x80") == "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
    CHECK(printable("\xe2\x82\xac \xf0\x9f\x98\x80") == "\xe2\x82\xac \xf0\x9f\x98\x80");  // kept
}

TEST_CASE("in_quotes never cuts a UTF-8 character") {
    const std::string e = "\xc3\xa9";  // 2 bytes
    CHECK(in_quotes("a" + e + "b", 2) == "'a...'");
    CHECK(in_quotes(e + e, 3) == "'" + e + "...'");
    CHECK(in_quotes(e + e, 2) == "'" + e + "...'");
    CHECK(in_quotes("\xf0\x9f\x98\x80x", 3) == "'...'");
}
