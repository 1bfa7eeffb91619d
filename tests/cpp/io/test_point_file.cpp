// Point files: text formats, column selection, .npy, and error locations (FILE:LINE:COLUMN).
#include "dvoronoi/io/point_file.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <utility>

using dvoronoi::InputError;
using dvoronoi::io::Columns;
using dvoronoi::io::parse_columns;
using dvoronoi::io::parse_npy;
using dvoronoi::io::parse_point_text;

namespace {

/// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, const Columns& cols = {}) {
    try {
        parse_point_text(text, "f.txt", cols);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

bool starts_with(const std::string& s, const std::string& prefix) {
    return s.compare(0, prefix.size(), prefix) == 0;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// A numpy .npy file's bytes (format 1.0) for the given descr, order, shape and raw data.
std::string npy_bytes(const std::string& descr, bool fortran, const std::string& shape,
                      const std::string& data) {
    std::string header = "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
                         ", 'shape': " + shape + ", }";
    while ((10 + header.size() + 1) % 64 != 0) header += ' ';
    header += '\n';
    std::string out("\x93NUMPY\x01\x00", 8);
    out += static_cast<char>(header.size() & 0xff);
    out += static_cast<char>(header.size() >> 8);
    return out + header + data;
}

template <class T>
std::string raw(std::initializer_list<T> values, bool big_endian = false) {
    std::string out;
    for (T v : values) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        if (big_endian)
            for (std::size_t a = 0, z = sizeof(T) - 1; a < z; ++a, --z) std::swap(b[a], b[z]);
        out.append(b, sizeof(T));
    }
    return out;
}

std::filesystem::path fresh_dir() {
    std::random_device rd;
    const auto dir = std::filesystem::temp_directory_path() /
                     ("dvoronoi_pf_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace

TEST_CASE("whitespace-separated x y, one point per line, in file order") {
    const auto f = parse_point_text("1 2\n3.5\t-4e2\n\n  5 6  \n", "f.txt");
    REQUIRE(f.points.rows() == 3);
    CHECK(f.points(0, 0) == 1.0);
    CHECK(f.points(0, 1) == 2.0);
    CHECK(f.points(1, 0) == 3.5);
    CHECK(f.points(1, 1) == -400.0);
    CHECK(f.points(2, 0) == 5.0);
    CHECK(f.points(2, 1) == 6.0);
    CHECK(f.line == std::vector<dvoronoi::Index>{1, 2, 4});
    CHECK(f.where(2) == "f.txt:4");
}

TEST_CASE("comments, a header line, commas, CRLF and a byte-order mark") {
    const std::string text = "\xEF\xBB\xBF# positions\r\n\r\nx, y   # header\r\n1,2 # first\r\n 3 ,\t4\r\n#end\r\n";
    const auto f = parse_point_text(text, "f.csv");
    REQUIRE(f.points.rows() == 2);
    CHECK(f.points(0, 0) == 1.0);
    CHECK(f.points(0, 1) == 2.0);
    CHECK(f.points(1, 0) == 3.0);
    CHECK(f.points(1, 1) == 4.0);
    CHECK(f.line == std::vector<dvoronoi::Index>{4, 5});
}

TEST_CASE("numbers are read exactly and locale-independently") {
    const auto f = parse_point_text("+1.5 .5\n5. -0.1\n1e-300 0.30000000000000004\n", "f");
    REQUIRE(f.points.rows() == 3);
    CHECK(f.points(0, 0) == 1.5);
    CHECK(f.points(0, 1) == 0.5);
    CHECK(f.points(1, 0) == 5.0);
    CHECK(f.points(1, 1) == -0.1);
    CHECK(f.points(2, 0) == 1e-300);
    CHECK(f.points(2, 1) == 0.30000000000000004);
}

TEST_CASE("empty input and comment-only input give 0 points") {
    CHECK(parse_point_text("", "f").points.rows() == 0);
    CHECK(parse_point_text("# nothing\n\n   \n", "f").points.rows() == 0);
    CHECK(parse_point_text("x y\n", "f").points.rows() == 0);  // header only
}

TEST_CASE("the header line is reported: where it was and what it said") {
    // The CLI warns about a file whose only content is a header ("hello world": probably the wrong file).
    const auto only = parse_point_text("# c\nhello world  # greeting\n", "f");
    CHECK(only.points.rows() == 0);
    CHECK(only.header_line == 2);
    CHECK(only.header == "hello world  ");
    const auto data = parse_point_text("x,y\n1,2\n", "f");
    CHECK(data.header_line == 1);
    CHECK(data.points.rows() == 1);
    CHECK(parse_point_text("1 2\n", "f").header_line == 0);
    CHECK(parse_point_text("", "f").header_line == 0);
}

TEST_CASE("quoted input is escaped: a NUL byte or a control byte does not cut or garble the message") {
    // Before: "f.txt:2:3: y value 'a" -- the NUL ended the C string, and the rest of the message.
    const std::string nul = error_of(std::string("1 2\n3 a\0b\n", 10));
    CHECK(nul == "f.txt:2:3: y value 'a\\0b' is not a number");
    CHECK(std::strlen(nul.c_str()) == nul.size());
    CHECK(error_of("1 2\n3 \x01\x1b[31m\x7f\\\n") == "f.txt:2:3: y value '\\x01\\x1b[31m\\x7f\\\\' is not a number");
    // UTF-8 is kept as it is; a long token is cut after 40 bytes.
    CHECK(contains(error_of("1 2\n3 \xc3\xa9t\xc3\xa9\n"), "'\xc3\xa9t\xc3\xa9' is not a number"));
    CHECK(contains(error_of("1 2\n3 " + std::string(50, 'z') + "\n"), "'" + std::string(40, 'z') + "...'"));
    // Header names too.
    Columns by_name;
    by_name.x_name = "lon";
    by_name.y_name = "lat";
    CHECK(contains(error_of(std::string("lon\tla\0t\n1 2\n", 13), by_name), "(columns: lon, la\\0t)"));
}

TEST_CASE("a token that is not a number is reported at its line and column") {
    CHECK(starts_with(error_of("1 2\n3 abc\n"), "f.txt:2:3: "));
    CHECK(contains(error_of("1 2\n3 abc\n"), "'abc' is not a number"));
    CHECK(starts_with(error_of("1 2\n\n# c\n  x7 4\n"), "f.txt:4:3: "));
    CHECK(starts_with(error_of("1\t2\n3\tabc\n"), "f.txt:2:3: "));
    CHECK(starts_with(error_of("1,2\n3,  zz\n"), "f.txt:2:5: "));
    CHECK(starts_with(error_of("0x10 1\n"), "f.txt:1:1: "));  // hex is not accepted
    CHECK(starts_with(error_of("1e 2\n"), "f.txt:1:1: "));
    // A header is only recognised before the data.
    CHECK(starts_with(error_of("1 2\nx y\n"), "f.txt:2:1: "));
}

TEST_CASE("NaN, inf and overflowing values are errors at their position") {
    const std::string nan_msg = error_of("1 2\n  nan 4\n");
    CHECK(starts_with(nan_msg, "f.txt:2:3: "));
    CHECK(contains(nan_msg, "not finite"));
    CHECK(starts_with(error_of("1 inf\n"), "f.txt:1:3: "));
    CHECK(starts_with(error_of("1 2\n3 -Infinity\n"), "f.txt:2:3: "));
    const std::string big = error_of("1 2\n1e999 0\n");
    CHECK(starts_with(big, "f.txt:2:1: "));
    CHECK(contains(big, "out of the range"));
}

TEST_CASE("a wrong number of fields without --columns says so and suggests --columns") {
    const std::string many = error_of("1 2\n3 4 5\n");
    CHECK(starts_with(many, "f.txt:2:5: "));
    CHECK(contains(many, "expected 2 fields"));
    CHECK(contains(many, "found 3"));
    CHECK(contains(many, "--columns"));
    const std::string few = error_of("1 2\n33\n");
    CHECK(starts_with(few, "f.txt:2:3: "));
    CHECK(contains(few, "found 1"));
    CHECK(starts_with(error_of("1,2,\n"), "f.txt:1:5: "));  // empty trailing field
    CHECK(starts_with(error_of("1,,2\n"), "f.txt:1:3: "));
}

TEST_CASE("column selection by index and by header name") {
    Columns c;
    c.x = 1;
    c.y = 2;
    const auto f = parse_point_text("7 1.5 2.5\n8 3 4 extra\n", "f", c);
    REQUIRE(f.points.rows() == 2);
    CHECK(f.points(0, 0) == 1.5);
    CHECK(f.points(0, 1) == 2.5);
    CHECK(f.points(1, 0) == 3.0);
    CHECK(f.points(1, 1) == 4.0);

    Columns swapped;
    swapped.x = 2;
    swapped.y = 0;
    const auto g = parse_point_text("1 name 2\n", "f", swapped);
    CHECK(g.points(0, 0) == 2.0);
    CHECK(g.points(0, 1) == 1.0);

    const std::string few = error_of("1 2 3\n4 5\n", c);
    CHECK(starts_with(few, "f.txt:2:4: "));
    CHECK(contains(few, "too few fields"));
    CHECK(starts_with(error_of("1 2 oops\n", c), "f.txt:1:5: "));

    const Columns named = parse_columns("lon,lat");
    const auto h = parse_point_text("id,lat,lon\n1,45.5,7.25\n", "f", named);
    REQUIRE(h.points.rows() == 1);
    CHECK(h.points(0, 0) == 7.25);
    CHECK(h.points(0, 1) == 45.5);
    CHECK(contains(error_of("id,x,y\n1,2,3\n", named), "no column named 'lon'"));
    CHECK(contains(error_of("1,2,3\n", named), "no header line"));
}

TEST_CASE("parse_columns accepts two distinct indices or names, nothing else") {
    const Columns c = parse_columns(" 1 , 2 ");
    CHECK(c.x == 1);
    CHECK(c.y == 2);
    CHECK(c.given());
    CHECK_FALSE(Columns{}.given());
    for (const char* bad : {"1", "1,1", "a,1", "-1,2", "1,2,3", ",2", "x,x", ""})
        CHECK_THROWS_AS(parse_columns(bad, "--columns"), InputError);
    try {
        parse_columns("1", "--columns");
    } catch (const InputError& e) {
        CHECK(starts_with(e.what(), "--columns: "));
    }
}

TEST_CASE("the Intel lab file: columns 1,2 select x and y; without them the error names line 4") {
    const std::string path = std::string(DVORONOI_TEST_DATA_DIR) + "/intel_lab_motes.txt";
    Columns c;
    c.x = 1;
    c.y = 2;
    const auto f = dvoronoi::io::read_point_file(path, c);
    REQUIRE(f.points.rows() == 54);
    CHECK(f.points(0, 0) == 21.5);
    CHECK(f.points(0, 1) == 23.0);
    CHECK(f.points(53, 0) == 26.5);
    CHECK(f.points(53, 1) == 2.0);
    CHECK(f.line.front() == 4);
    try {
        dvoronoi::io::read_point_file(path);
        FAIL("expected an InputError");
    } catch (const InputError& e) {
        CHECK(starts_with(e.what(), path + ":4:8: "));
        CHECK(contains(e.what(), "--columns"));
    }
}

TEST_CASE(".npy arrays: float64/float32/int64, C and Fortran order, either byte order") {
    const auto c = parse_npy(npy_bytes("<f8", false, "(3, 2)", raw<double>({1, 2, 3, 4, 5.5, -6})), "a.npy");
    REQUIRE(c.points.rows() == 3);
    CHECK(c.points(1, 0) == 3.0);
    CHECK(c.points(1, 1) == 4.0);
    CHECK(c.points(2, 0) == 5.5);
    CHECK(c.points(2, 1) == -6.0);
    CHECK(c.line.empty());
    CHECK(c.where(2) == "a.npy (row 2)");

    const auto f = parse_npy(npy_bytes("<f8", true, "(3, 2)", raw<double>({1, 3, 5, 2, 4, 6})), "a.npy");
    REQUIRE(f.points.rows() == 3);
    CHECK(f.points(0, 1) == 2.0);
    CHECK(f.points(1, 0) == 3.0);
    CHECK(f.points(2, 1) == 6.0);

    const auto s = parse_npy(npy_bytes("<f4", false, "(1, 2)", raw<float>({0.5f, 0.25f})), "a.npy");
    CHECK(s.points(0, 0) == 0.5);
    CHECK(s.points(0, 1) == 0.25);

    const auto b = parse_npy(npy_bytes(">f8", false, "(1, 2)", raw<double>({0.1, 7}, true)), "a.npy");
    CHECK(b.points(0, 0) == 0.1);
    CHECK(b.points(0, 1) == 7.0);

    const auto i = parse_npy(npy_bytes("<i8", false, "(1, 2)", raw<std::int64_t>({-3, 9})), "a.npy");
    CHECK(i.points(0, 0) == -3.0);
    CHECK(i.points(0, 1) == 9.0);

    CHECK(parse_npy(npy_bytes("<f8", false, "(0, 2)", ""), "a.npy").points.rows() == 0);
}

TEST_CASE(".npy errors name the file and what is wrong") {
    const auto msg = [](const std::string& bytes) {
        try {
            parse_npy(bytes, "a.npy");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(contains(msg(npy_bytes("<f8", false, "(4,)", raw<double>({1, 2, 3, 4}))), "shape (n, 2), got (4,)"));
    CHECK(contains(msg(npy_bytes("<f8", false, "(2, 3)", raw<double>({1, 2, 3, 4, 5, 6}))), "got (2, 3)"));
    CHECK(contains(msg(npy_bytes("<c16", false, "(1, 2)", std::string(32, '\0'))), "dtype"));
    CHECK(contains(msg(npy_bytes("<f8", false, "(3, 2)", raw<double>({1, 2}))), "truncated"));
    // n * 16 bytes wraps around to 16 (issue 20's fuzzing): was "out of memory", not an InputError
    CHECK(contains(msg(npy_bytes("<f8", false, "(1152921504606846977, 2)", raw<double>({1, 2}))),
                   "truncated .npy data: 1152921504606846977 rows need more bytes than a file can hold"));
    CHECK(contains(msg(npy_bytes("<i4", false, "(9223372036854775807, 2)", raw<double>({1, 2}))), "truncated"));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::string m = msg(npy_bytes("<f8", false, "(2, 2)", raw<double>({1, 2, nan, 4})));
    CHECK(starts_with(m, "a.npy: "));
    CHECK(contains(m, "points[1, 0]"));
    CHECK(contains(msg("not numpy at all"), "not a .npy file"));
}

TEST_CASE("read_point_file detects .npy by content and reports unreadable files") {
    const auto dir = fresh_dir();
    const auto npy = (dir / "p.npy").string();
    {
        std::ofstream out(npy, std::ios::binary);
        out << npy_bytes("<f8", false, "(2, 2)", raw<double>({1, 2, 3, 4}));
    }
    const auto f = dvoronoi::io::read_point_file(npy);
    REQUIRE(f.points.rows() == 2);
    CHECK(f.points(1, 1) == 4.0);
    Columns c;
    c.x = 0;
    c.y = 1;
    CHECK_THROWS_AS(dvoronoi::io::read_point_file(npy, c), InputError);

    const auto fake = (dir / "q.npy").string();
    { std::ofstream(fake) << "1 2\n"; }
    CHECK_THROWS_WITH_AS(dvoronoi::io::read_point_file(fake), doctest::Contains("not a .npy file"),
                         InputError);

    const auto missing = (dir / "missing.txt").string();
    CHECK_THROWS_WITH_AS(dvoronoi::io::read_point_file(missing),
                         doctest::Contains((missing + ": cannot open").c_str()), InputError);
    std::filesystem::remove_all(dir);
}

TEST_CASE("a radius column (heterogeneous teams): X,Y,R by index or by name") {
    using dvoronoi::io::parse_columns;
    using dvoronoi::io::parse_point_text;
    const Columns byname = parse_columns("x,y,r", "--columns", true);
    CHECK(byname.has_radius());
    CHECK(byname.r_name == "r");
    const Columns byindex = parse_columns("1,2,0", "--columns", true);
    CHECK(byindex.r == 0);
    CHECK(!parse_columns("1,2", "--columns", true).has_radius());
    // Three columns only where a radius is accepted; no mixing of names and indices; distinct.
    CHECK_THROWS_WITH_AS(parse_columns("x,y,r", "--columns"), doctest::Contains("--columns"), InputError);
    CHECK_THROWS_AS(parse_columns("1,2,r", "--columns", true), InputError);
    CHECK_THROWS_AS(parse_columns("1,2,2", "--columns", true), InputError);
    const auto f = parse_point_text("r x y\n2 0 0\n0.5 1 1\n", "team.txt", byname);
    REQUIRE(f.points.rows() == 2);
    CHECK(f.radii == std::vector<double>{2.0, 0.5});
    CHECK(f.points(1, 0) == 1.0);
    CHECK_THROWS_WITH_AS(parse_point_text("x y r\n0 0 0\n", "team.txt", byname), doctest::Contains("team.txt:2:5: radius"),
                         InputError);
    CHECK(parse_point_text("0 0\n1 1\n", "plain.txt").radii.empty());
}
