// Writing output files atomically: the content goes to a temporary file in the target's directory,
// which is renamed over the target only when everything was written and flushed. A failure (an
// exception, a full disk, a crash) never leaves a half-written output: either the old file (or no
// file) or the complete new one is there. A link is followed (the file it names is replaced, the link
// stays), and a device or a pipe (/dev/null, /dev/stdout, a FIFO) is written in place: renaming over
// it would replace the device itself.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <system_error>

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include <process.h>
#include <sys/stat.h>
#else
#include <fcntl.h>
#include <unistd.h>
#endif

namespace dvoronoi::io {

/// An output file could not be created, written or moved into place.
class OutputError : public Error {
public:
    using Error::Error;
};

/// A file written atomically. The constructor creates the temporary file (so an unwritable
/// destination fails before any work is done); write to stream(), then commit(). If commit() is not
/// reached (an exception, an early return), the destructor removes the temporary file and the
/// destination is untouched.
///
/// \note Not copyable. Each object is independent; distinct objects may be used from distinct
///       threads. A process killed between creation and commit leaves a hidden temporary file
///       `.NAME.tmp.*` next to the destination.
class AtomicFile {
public:
    /// \throws OutputError "PATH: ..." if PATH is a directory or the temporary file cannot be created.
    explicit AtomicFile(std::string path) : path_(std::move(path)) {
        namespace fs = std::filesystem;
        const fs::path target = followed(path_);
        target_ = target.string();
        std::error_code ec;
        const fs::file_status st = fs::status(target, ec);
        if (fs::is_directory(st)) throw OutputError(path_ + ": is a directory");
        if (fs::exists(st) && !fs::is_regular_file(st)) {  // a device or a pipe: written in place
            out_.open(target_, std::ios::binary);
            if (!out_) throw OutputError(path_ + ": cannot open for writing");
            return;
        }
        const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
        const std::string base = target.filename().string();
        if (base.empty() || base == "." || base == "..") throw OutputError(path_ + ": not a file name");
        std::random_device rd;
        int last_err = 0;
        for (int attempt = 0; attempt < 100; ++attempt) {
            char suffix[32];
            std::snprintf(suffix, sizeof suffix, "%08x%08x", rd(), rd());
            const fs::path tmp = dir / ("." + base + ".tmp." + std::to_string(pid()) + "." + suffix);
            const int err = create_exclusive(tmp.string());
            if (err == 0) {
                temp_ = tmp.string();
                break;
            }
            last_err = err;
            if (err != EEXIST) break;
        }
        if (temp_.empty())
            throw OutputError(path_ + ": cannot create a file in " + dir.string() + ": " +
                              std::strerror(last_err));
        out_.open(temp_, std::ios::binary | std::ios::trunc);
        if (!out_) {
            remove_temp();
            throw OutputError(path_ + ": cannot open a temporary file for writing");
        }
    }

    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    ~AtomicFile() {
        if (!committed_) {
            if (out_.is_open()) out_.close();
            remove_temp();
        }
    }

    /// The stream to write the content to.
    std::ostream& stream() { return out_; }

    const std::string& path() const noexcept { return path_; }
    const std::string& temp_path() const noexcept { return temp_; }

    /// Flushes, closes and renames the temporary file over the destination (keeping the permissions
    /// of a file it replaces).
    /// \throws OutputError if writing failed at any point (e.g. disk full) or the rename fails; the
    ///         temporary file is removed and the destination is untouched.
    void commit() {
        namespace fs = std::filesystem;
        if (committed_) return;
        out_.flush();
        const bool write_ok = static_cast<bool>(out_);
        out_.close();
        if (!write_ok || out_.fail()) {
            remove_temp();
            throw OutputError(path_ + ": writing failed (disk full or I/O error)");
        }
        if (temp_.empty()) {  // written in place
            committed_ = true;
            return;
        }
        std::error_code ec;
        const fs::file_status old = fs::status(target_, ec);
        if (!ec && fs::is_regular_file(old))
            fs::permissions(temp_, old.permissions(), fs::perm_options::replace, ec);
        fs::rename(temp_, target_, ec);
        if (ec) {
            remove_temp();
            throw OutputError(path_ + ": cannot move the finished file into place: " + ec.message());
        }
        committed_ = true;
    }

private:
    /// `path` with its links followed as far as they lead (at most 40, as the kernel): the file a
    /// write through the link lands in. A dangling link gives the path it names.
    static std::filesystem::path followed(const std::string& path) {
        namespace fs = std::filesystem;
        fs::path p(path);
        std::error_code ec;
        for (int hop = 0; hop < 40 && fs::is_symlink(p, ec); ++hop) {
            const fs::path to = fs::read_symlink(p, ec);
            if (ec) break;
            p = to.is_absolute() ? to : p.parent_path() / to;
        }
        return p;
    }

    static long pid() {
#ifdef _WIN32
        return static_cast<long>(_getpid());
#else
        return static_cast<long>(::getpid());
#endif
    }

    /// Creates the file if it does not exist (permissions as for any new file, after the umask);
    /// returns 0 or an errno value.
    static int create_exclusive(const std::string& name) {
#ifdef _WIN32
        const int fd = _open(name.c_str(), _O_WRONLY | _O_CREAT | _O_EXCL | _O_BINARY,
                             _S_IREAD | _S_IWRITE);
        if (fd < 0) return errno;
        _close(fd);
#else
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) return errno;
        ::close(fd);
#endif
        return 0;
    }

    void remove_temp() noexcept {
        if (temp_.empty()) return;
        std::error_code ec;
        std::filesystem::remove(temp_, ec);
    }

    std::string path_, target_, temp_;  // target_: path_ with its links followed
    std::ofstream out_;
    bool committed_ = false;
};

/// Writes PATH atomically: calls `write` with a stream to a temporary file, then renames it into
/// place. If `write` throws, the exception propagates and nothing is written.
/// \throws OutputError as AtomicFile, or whatever `write` throws.
inline void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
    AtomicFile file(path);
    write(file.stream());
    file.commit();
}

}  // namespace dvoronoi::io
