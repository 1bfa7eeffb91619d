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
