// Atomic output files: the destination is either untouched or complete, and no temporary is left.
#include "dvoronoi/io/atomic_write.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#ifndef _WIN32
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace fs = std::filesystem;
using dvoronoi::io::AtomicFile;
using dvoronoi::io::OutputError;
using dvoronoi::io::write_atomically;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        std::random_device rd;
        path = fs::temp_directory_path() / ("dvoronoi_aw_" + std::to_string(rd()) + std::to_string(rd()));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::size_t entries() const {
        std::size_t n = 0;
        for (const auto& e : fs::directory_iterator(path)) {
            (void)e;
            ++n;
        }
        return n;
    }
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
}

}  // namespace

TEST_CASE("write_atomically writes the whole content and leaves only the destination") {
    TempDir dir;
    const fs::path out = dir.path / "out.json";
    write_atomically(out.string(), [](std::ostream& os) { os << "{\"a\": 1}\n"; });
    CHECK(slurp(out) == "{\"a\": 1}\n");
    CHECK(dir.entries() == 1);
}

TEST_CASE("a failing writer leaves no file and no temporary behind") {
    TempDir dir;
    const fs::path out = dir.path / "out.json";
    CHECK_THROWS_AS(write_atomically(out.string(),
                                     [](std::ostream& os) {
                                         os << "half of it";
                                         throw std::runtime_error("boom");
                                     }),
                    std::runtime_error);
    CHECK_FALSE(fs::exists(out));
    CHECK(dir.entries() == 0);
}

TEST_CASE("a failing writer leaves an existing destination untouched") {
    TempDir dir;
    const fs::path out = dir.path / "keep.csv";
    { std::ofstream(out) << "old content\n"; }
    CHECK_THROWS(write_atomically(out.string(), [](std::ostream& os) {
        os << "new";
        throw std::runtime_error("boom");
    }));
    CHECK(slurp(out) == "old content\n");
    CHECK(dir.entries() == 1);
    // ... and a successful one replaces it.
    write_atomically(out.string(), [](std::ostream& os) { os << "new content\n"; });
    CHECK(slurp(out) == "new content\n");
    CHECK(dir.entries() == 1);
}

TEST_CASE("AtomicFile: the temporary exists until commit; no commit means no file") {
    TempDir dir;
    const fs::path out = dir.path / "pic.svg";
    {
        AtomicFile f(out.string());
        CHECK(fs::exists(f.temp_path()));
        CHECK(fs::path(f.temp_path()).parent_path() == dir.path);
        CHECK_FALSE(fs::exists(out));
        f.stream() << "<svg/>";
    }
    CHECK_FALSE(fs::exists(out));
    CHECK(dir.entries() == 0);
    {
        AtomicFile f(out.string());
        f.stream() << "<svg/>";
        f.commit();
        CHECK_FALSE(fs::exists(f.temp_path()));
    }
    CHECK(slurp(out) == "<svg/>");
    CHECK(dir.entries() == 1);
}

TEST_CASE("an unwritable destination fails at construction, naming the path") {
    TempDir dir;
    const fs::path missing = dir.path / "no_such_dir" / "out.json";
    CHECK_THROWS_WITH_AS(AtomicFile(missing.string()), doctest::Contains(missing.string().c_str()),
                         OutputError);
    CHECK_THROWS_AS(AtomicFile(dir.path.string()), OutputError);  // a directory
    CHECK(dir.entries() == 0);
}

#ifndef _WIN32
TEST_CASE("a link is followed: the file it names gets the content, the link stays a link") {
    // Before: the rename replaced the link by a regular file and the file it named kept its old content.
    TempDir dir;
    const fs::path real = dir.path / "real.json", link = dir.path / "link.json";
    std::ofstream(real) << "old";
    fs::create_symlink("real.json", link);  // relative, as `ln -s` makes it
    write_atomically(link.string(), [](std::ostream& os) { os << "new"; });
    CHECK(fs::is_symlink(link));
    CHECK(slurp(real) == "new");
    CHECK(dir.entries() == 2);
}

TEST_CASE("a pipe is written in place, not replaced by a file") {
    // Before: the rename replaced a FIFO (or, run as root, `--svg /dev/null`'s device) by a regular file.
    TempDir dir;
    const fs::path fifo = dir.path / "out.svg";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // a reader, so that the writer's open returns
    REQUIRE(fd >= 0);
    write_atomically(fifo.string(), [](std::ostream& os) { os << "<svg/>"; });
    char buf[16] = {};
    const auto n = ::read(fd, buf, sizeof buf);
    ::close(fd);
    CHECK(std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0) == "<svg/>");
    CHECK(fs::is_fifo(fifo));
    CHECK(dir.entries() == 1);
}
#endif
