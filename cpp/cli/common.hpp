// Pieces every `dvoronoi` subcommand shares: the usage-error type, the choice of output format, the
// progress counter, output files. Argument parsing and I/O only; all formatting lives in dvoronoi/io.
#pragma once

#include "dvoronoi/core/types.hpp"
#include "dvoronoi/io/atomic_write.hpp"
#include "dvoronoi/io/point_file.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#ifdef _WIN32
#include <io.h>
#define DVORONOI_ISATTY(f) _isatty(_fileno(f))
#else
#include <unistd.h>
#define DVORONOI_ISATTY(f) ::isatty(::fileno(f))
#endif

namespace dvoronoi::cli {

/// A bad command line (exit code 2). The message names the argument.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A subcommand: its CLI11 app (to see whether it was chosen) and the function that runs it after
/// parsing, returning the exit code. Each subcommand lives in its own .cpp and adds itself in main.
struct Command {
    CLI::App* app = nullptr;
    std::function<int()> run;
};

Command add_cells(CLI::App& parent);
Command add_voronoi(CLI::App& parent);
Command add_gvd(CLI::App& parent);
Command add_neighbors_from_distances(CLI::App& parent);
Command add_lloyd(CLI::App& parent);
Command add_network(CLI::App& parent);

/// A double as the user would write it ("-1", "0.5", "nan").
inline std::string show(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

/// Output formats chosen by file extension.
enum class Format { Json, GeoJson, Csv };

inline std::string lower_extension(const std::string& path) {
    const std::size_t slash = path.find_last_of("/\\");
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
}

/// Whether two paths name one file: as spelt, or by another path to it (./a.json, an absolute path,
/// a link, a hard link).
inline bool same_file(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    auto resolved = [](const std::string& p) {  // links and dots resolved as far as the path exists
        std::error_code ec;
        const fs::path c = fs::weakly_canonical(fs::absolute(fs::path(p), ec), ec);
        return ec ? fs::path(p).lexically_normal() : c;
    };
    std::error_code ec;
    return a == b || fs::equivalent(a, b, ec) || resolved(a) == resolved(b);
}

/// A file a command reads, and how a message names it ("INPUT", "--polygon", "the image of INPUT").
struct ReadFile {
    std::string path, name;
};

/// Refuses outputs that would lose a file: an --svg path naming the -o/--output file (both would be
/// written and one lost), and an output naming a file the command reads (INPUT, a YAML's image...):
/// it would be replaced. '-' is stdout (or stdin) and no file; `--svg -` is refused, as only -o may
/// write to stdout. One function for every command, so that each compares paths the same way.
inline void check_outputs(const std::string& output, const std::string& svg, const std::vector<ReadFile>& inputs = {}) {
    if (svg == "-") throw UsageError("--svg: '-' (stdout) is for -o/--output's JSON; give the SVG a file name");
    const bool to_file = !output.empty() && output != "-";
    if (to_file && !svg.empty() && same_file(output, svg)) throw UsageError("--svg: same file as -o/--output ('" + svg + "')");
    for (const ReadFile& in : inputs) {
        if (in.path.empty() || in.path == "-") continue;
        for (const auto& [path, option] : {std::pair<const std::string&, const char*>(output, "-o/--output"),
                                           std::pair<const std::string&, const char*>(svg, "--svg")})
            if (!path.empty() && path != "-" && same_file(path, in.path))
                throw UsageError(std::string(option) + ": '" + path + "' is the same file as " + in.name +
                                 (path == in.path ? std::string() : " ('" + in.path + "')") +
                                 ": an output may not overwrite an input");
    }
}

/// The format of an output path, from its extension. \throws UsageError naming `option`.
inline Format output_format(const std::string& path, const std::string& option) {
    const std::string ext = lower_extension(path);
    if (ext == ".json") return Format::Json;
    if (ext == ".geojson") return Format::GeoJson;
    if (ext == ".csv") return Format::Csv;
    throw UsageError(option + ": cannot tell the output format of '" + path + "' (extension '" + ext +
                     "'); use .json, .geojson or .csv, or leave " + option +
                     " out to write JSON to stdout");
}

/// Opens an output file atomically now (before any work), turning failures into usage errors that
/// name the option.
inline std::unique_ptr<io::AtomicFile> open_output(const std::string& path, const std::string& option) {
    try {
        return std::make_unique<io::AtomicFile>(path);
    } catch (const io::OutputError& e) {
        throw UsageError(option + ": " + e.what());
    }
}

/// A check for a count option: a whole number in [lo, hi], e.g. "must be a whole number from 0 (all
/// cores) to 2147483647, got -1". (CLI::NonNegativeNumber printed its range as 0 to DBL_MAX in 300
/// digits, and accepted 2.5.)
inline CLI::Validator count_check(long long lo, long long hi, const std::string& lo_means = "") {
    const std::string range = "a whole number from " + std::to_string(lo) + (lo_means.empty() ? "" : " (" + lo_means + ")") +
                              " to " + std::to_string(hi);
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            long long v = 0;
            const char* end = text.data() + text.size();
            const auto r = std::from_chars(text.data(), end, v);
            if (r.ec != std::errc() || r.ptr != end || v < lo || v > hi)
                return "must be " + range + ", got " + io::in_quotes(text);
            return std::string();
        },
        "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", "count");
}

/// The check of -t/--threads: 0 = all cores, else that many threads.
inline CLI::Validator threads_check() { return count_check(0, 2147483647, "all cores"); }

/// The options every point-file command shares: POINTS (required), --columns and -t/--threads.
inline void add_points_options(CLI::App* sub, std::string& points, std::string& columns, int& threads) {
    sub->add_option("POINTS", points,
                    "point file: 'x y' per line, whitespace- or comma-separated, '#' comments, "
                    "optional header line (a first line without a number; a file of only a header "
                    "has no points, with a warning); or a numpy .npy array of shape (n, 2); '-' reads stdin")
        ->required();
    sub->add_option("--columns", columns,
                    "X,Y: the fields holding x and y, as 0-based indices (e.g. 1,2 for 'id x y') or "
                    "header names (e.g. lon,lat); `cells` and `lloyd` also take X,Y,R, a radius per agent (e.g. x,y,r)");
    sub->add_option("-t,--threads", threads, "worker threads (0 = all cores)")
        ->check(threads_check())
        ->capture_default_str();
}

/// Reads the POINTS argument with an optional --columns selection (InputError carries FILE:LINE:COL).
/// A file whose only content is a header line is valid and has no points (docs/spec.md), but a file of
/// "hello world" is more likely the wrong file than an empty team: a warning on stderr says which
/// line was taken for a header.
inline io::PointFile read_points_argument(const std::string& path, const std::string& columns, bool allow_radius = false) {
    const io::Columns cols = columns.empty() ? io::Columns{} : io::parse_columns(columns, "--columns", allow_radius);
    io::PointFile file = io::read_point_file(path, cols);
    if (file.points.rows() == 0 && file.header_line > 0)
        std::cerr << "dvoronoi: warning: " << file.name << ":" << file.header_line << ": "
                  << io::in_quotes(file.header, 60)
                  << " was read as a header line (none of its fields is a number) and no data line follows: "
                     "the file has no points\n";
    return file;
}

/// Rewrites a CoincidentError in terms of the file: both lines, the later one as the location.
inline std::string coincident_message(const io::PointFile& file, const CoincidentError& e) {
    const auto i = e.first(), j = e.second();
    if (static_cast<std::size_t>(j) < file.line.size())
        return file.where(j) + ":1: point " + std::to_string(j) + " coincides with point " +
               std::to_string(i) + " (line " + std::to_string(file.line[static_cast<std::size_t>(i)]) +
               "); coinciding agents have no Voronoi cells";
    return file.name + ": " + e.what();
}

/// Rewrites a RangeError ("points[i]: out of the exact range ...") in terms of the file: the point's
/// line (text) or row (.npy) first, so the message names the file like every other input error.
inline std::string range_message(const io::PointFile& file, const RangeError& e) {
    const std::string what = e.what();
    const std::string prefix = "points[";
    if (what.compare(0, prefix.size(), prefix) == 0) {
        const std::size_t close = what.find(']');
        const std::string digits = close == std::string::npos ? "" : what.substr(prefix.size(), close - prefix.size());
        if (!digits.empty() && digits.size() < 19 && digits.find_first_not_of("0123456789") == std::string::npos)
            return file.where(static_cast<Index>(std::stoll(digits))) + ": " + what;
    }
    return file.name + ": " + what;
}

/// "LABEL: done/total" on stderr. On a terminal it is updated in place (only once a run has taken
/// more than half a second); otherwise only runs of at least `large` items report, a line every 5 s
/// and a final line. --quiet turns it off.
class Progress {
public:
    Progress(std::string label, Index total, bool quiet, Index large = 100000)
        : label_(std::move(label)), total_(total), tty_(DVORONOI_ISATTY(stderr) != 0),
          start_(Clock::now()), last_(start_) {
        enabled_ = !quiet && total > 0 && (tty_ || total >= large);
    }

    /// The library's progress callback (called from one thread).
    void operator()(Index done, Index /*total*/) {
        if (!enabled_) return;
        const auto now = Clock::now();
        const double since_start = seconds(now - start_), since_last = seconds(now - last_);
        if (tty_) {
            if (since_start < 0.5 || (printed_ && since_last < 0.1)) return;
            std::fprintf(stderr, "\r%s: %lld/%lld", label_.c_str(), static_cast<long long>(done),
                         static_cast<long long>(total_));
        } else {
            if (since_last < 5.0) return;
            std::fprintf(stderr, "%s: %lld/%lld\n", label_.c_str(), static_cast<long long>(done),
                         static_cast<long long>(total_));
        }
        std::fflush(stderr);
        printed_ = true;
        last_ = now;
    }

    /// Final line (on a terminal only if the counter was shown).
    void finish() {
        if (!enabled_ || (tty_ && !printed_)) return;
        std::fprintf(stderr, "%s%s: %lld/%lld (%.2f s)\n", tty_ ? "\r" : "", label_.c_str(),
                     static_cast<long long>(total_), static_cast<long long>(total_),
                     seconds(Clock::now() - start_));
        std::fflush(stderr);
    }

    /// Ends an in-place line before an error message.
    void abort() {
        if (enabled_ && tty_ && printed_) std::fputc('\n', stderr);
        enabled_ = false;
    }

private:
    using Clock = std::chrono::steady_clock;
    static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

    std::string label_;
    Index total_;
    bool tty_, enabled_ = false, printed_ = false;
    Clock::time_point start_, last_;
};

/// Runs `work(callback)` under a progress counter `label` over `total` items: the counter line is
/// ended before an error leaves, and a CoincidentError or RangeError is rewritten in terms of `file`
/// (its lines) when one is given.
template <class Work>
auto with_progress(const std::string& label, Index total, bool quiet, const io::PointFile* file, Work&& work) {
    Progress progress(label, total, quiet);
    try {
        auto result = work([&progress](Index done, Index all) { progress(done, all); });
        progress.finish();
        return result;
    } catch (const CoincidentError& e) {
        progress.abort();
        if (file) throw InputError(coincident_message(*file, e));
        throw;
    } catch (const RangeError& e) {
        progress.abort();
        if (file) throw InputError(range_message(*file, e));
        throw;
    } catch (...) {
        progress.abort();
        throw;
    }
}

/// Writes the main result to `out` (or to stdout when there is no output file) and the picture to
/// `svg`, then commits the files only when every one is complete, so a failure leaves none behind.
/// Returns the exit code (1 when stdout fails).
inline int deliver(std::unique_ptr<io::AtomicFile>& out, std::unique_ptr<io::AtomicFile>& svg,
                   const std::function<void(std::ostream&)>& write_main,
                   const std::function<void(std::ostream&)>& write_svg = nullptr, const char* program = "dvoronoi") {
    if (svg && write_svg) write_svg(svg->stream());
    if (out) write_main(out->stream());
    if (out) out->commit();
    if (svg) svg->commit();
    if (!out) {
        write_main(std::cout);
        std::cout.flush();
        if (!std::cout) {
            std::cerr << program << ": error: writing to stdout failed\n";
            return 1;
        }
    }
    return 0;
}

}  // namespace dvoronoi::cli
