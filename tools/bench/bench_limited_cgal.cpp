// bench_limited_cgal: dvoronoi's range-limited cells against CGAL's Delaunay triangulation, on the same
// uniform random points, in one process.
//
// What is timed (best of --reps rounds each; a round is ceil(--window / n) consecutive calls, so it
// covers at least --window agents (default 1e6) at every size, and its mean per call is the timing;
// destruction of the results excluded):
//   (a) CGAL: Delaunay_triangulation_2 with Exact_predicates_inexact_constructions_kernel, built by a
//       range insert of (point, index) pairs (CGAL spatially sorts them), then a neighbour walk: for
//       every agent, circulate its incident vertices and write the neighbour indices into CSR arrays
//       (input order, ascending per agent, like dvoronoi's). This is the full, unlimited Delaunay
//       graph: no cell geometry, no areas.
//   (b) dvoronoi::limited_cells(Method::Auto, the certified fast path, 1 thread): limited neighbours (CSR) and every cell's
//       boundary pieces, area, perimeter and centroid, exact combinatorics.
//   (c) the same with --threads threads (default 2).
//   (d) dvoronoi::limited_cells(Method::Chords, 1 thread): RCVC, same output.
// The two do different work: CGAL answers "who are the Voronoi neighbours" for the whole plane;
// dvoronoi answers "what is each agent's cell within R" (which a robot needs) and never builds a global
// structure. The ratio says what a user pays for one answer or the other on the same input.
//
// Points: n uniform in [0,1)^2 (std::mt19937_64, --seed). R = sqrt(k / (4 pi n)) so that about k agents
// (--k, default 30) lie within 2R of each agent.
//
// Sanity (outside the timings): Auto, Chords, 1 and T threads give identical neighbour CSR, and every
// limited neighbour is a Delaunay neighbour. A mismatch is printed and the exit code is 2.
//
// Usage:
//   bench_limited_cgal [--n 1e6] [--k 30] [--reps 3] [--threads 2] [--seed 1] [--window 1e6] [--json]
//   bench_limited_cgal --sizes 1e4,1e5,1e6      time per agent for each size (flatness check)

#include "bench_common.hpp"

#include <dvoronoi/partition/limited_partition.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace bench;

struct Timing {
    Index n = 0;
    double radius = 0.0;
    double mean_candidates = 0.0;      // agents within 2R
    double mean_limited = 0.0;         // limited neighbours
    double mean_delaunay = 0.0;        // Delaunay neighbours (CGAL)
    double cgal = 0.0, scan1 = 0.0, scant = 0.0, chords1 = 0.0;
    double scan1_call = 0.0;  // the fastest single call of (b)
    int calls = 1;            // calls per timing round
    int threads = 2;
    bool ok = true;
    std::string problem;
};

Timing run(Index n, double k, int reps, double window, int threads, std::uint64_t seed, bool verbose) {
    Timing t;
    t.n = n;
    t.calls = calls_for(n, window);
    t.threads = threads;
    t.radius = std::sqrt(k / (4.0 * kPi * static_cast<double>(n)));
    const dvoronoi::Points pts = uniform_points(n, seed);
    auto note = [&](const char* what) {
        if (verbose) std::fprintf(stderr, "  n = %lld: %s ...\n", static_cast<long long>(n), what);
    };

    CgalResult cg;
    note("CGAL Delaunay_triangulation_2 + neighbour walk");
    t.cgal = best_of(reps, [&] { return cgal_delaunay_neighbors(pts); }, cg, t.calls);
    cg.dt.reset();  // untimed; only the neighbour CSR is needed from here on

    // Only the neighbour CSR (and the candidate counts) are kept for the checks: four partitions of
    // 1e6 agents alive at once would measure the allocator, not the algorithms.
    struct Kept {
        Csr graph;
        std::vector<Index> candidates;
    };
    auto keep = [](dvoronoi::LimitedPartition&& p) {
        Kept k;
        k.graph.indptr = std::move(p.indptr);
        k.graph.indices = std::move(p.indices);
        k.candidates = std::move(p.candidates);
        return k;
    };
    auto dv_run = [&](dvoronoi::Method m, int nthreads, double& seconds, double* best_call = nullptr) {
        dvoronoi::LimitedPartition p;
        seconds = best_of(reps, [&] { return dvoronoi::limited_cells(pts, t.radius, m, nthreads); }, p, t.calls,
                          best_call);
        return keep(std::move(p));
    };
    note("dvoronoi auto, 1 thread");
    const Kept scan1 = dv_run(dvoronoi::Method::Auto, 1, t.scan1, &t.scan1_call);
    note("dvoronoi auto, T threads");
    const Kept scant = dv_run(dvoronoi::Method::Auto, threads, t.scant);
    note("dvoronoi Chords, 1 thread");
    const Kept chords1 = dv_run(dvoronoi::Method::Chords, 1, t.chords1);

    // Sanity, untimed.
    double cand = 0.0;
    for (Index c : scan1.candidates) cand += static_cast<double>(c);
    t.mean_candidates = n ? cand / static_cast<double>(n) : 0.0;
    t.mean_limited = n ? static_cast<double>(scan1.graph.indices.size()) / static_cast<double>(n) : 0.0;
    t.mean_delaunay = n ? static_cast<double>(cg.graph.indices.size()) / static_cast<double>(n) : 0.0;
    auto same = [](const Kept& a, const Kept& b) {
        return a.graph.indptr == b.graph.indptr && a.graph.indices == b.graph.indices;
    };
    if (!same(scan1, scant)) { t.ok = false; t.problem += " scan(1 thread) != scan(T threads);"; }
    if (!same(scan1, chords1)) { t.ok = false; t.problem += " scan != chords;"; }
    Index bad = -1;
    for (Index i = 0; i < n && bad < 0; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const Index* lb = scan1.graph.indices.data() + scan1.graph.indptr[ii];
        const Index* le = scan1.graph.indices.data() + scan1.graph.indptr[ii + 1];
        const Index* db = cg.graph.indices.data() + cg.graph.indptr[ii];
        const Index* de = cg.graph.indices.data() + cg.graph.indptr[ii + 1];
        if (!std::includes(db, de, lb, le)) bad = i;
    }
    if (bad >= 0) {
        t.ok = false;
        t.problem += " agent " + std::to_string(bad) + " has a limited neighbour that is not a Delaunay neighbour;";
    }
    return t;
}

void usage() {
    std::puts(
        "usage: bench_limited_cgal [--n N] [--k K] [--reps R] [--threads T] [--seed S] [--window W] [--json]\n"
        "       bench_limited_cgal --sizes N1,N2,... [--k K] [--reps R] [--threads T] [--seed S] [--window W] [--json]\n"
        "  --n        agents (default 1e6)\n"
        "  --k        expected agents within 2R; R = sqrt(k / (4 pi n)) on the unit square (default 30)\n"
        "  --reps     timing rounds per method, the best is reported (default 3)\n"
        "  --window   agents per round: a round is ceil(W / n) consecutive calls, timed by its mean (default 1e6)\n"
        "  --threads  threads of the multi-threaded dvoronoi run (default 2)\n"
        "  --sizes    one row per size: time per agent (flatness check)\n"
        "  --json     print one JSON object instead of the tables");
}

void print_json(const std::vector<Timing>& rows, double k, int reps, double window) {
    std::printf("{\"cgal_version\": \"%s\", \"cpu\": \"%s\", \"hardware_threads\": %d, \"openmp\": %s, "
                "\"native\": %s, \"k\": %g, \"reps\": %d, \"window\": %g, \"rows\": [",
                cgal_version(), cpu_model().c_str(), hardware_threads(),
#ifdef _OPENMP
                "true",
#else
                "false",
#endif
#ifdef DVORONOI_BENCH_NATIVE
                "true",
#else
                "false",
#endif
                k, reps, window);
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const Timing& t = rows[r];
        std::printf("%s{\"n\": %lld, \"radius\": %.17g, \"threads\": %d, \"mean_candidates\": %.6g, "
                    "\"mean_limited_neighbors\": %.6g, \"mean_delaunay_neighbors\": %.6g, "
                    "\"calls_per_round\": %d, \"cgal_s\": %.6g, \"scan1_s\": %.6g, \"scan1_best_call_s\": %.6g, "
                    "\"scanT_s\": %.6g, \"chords1_s\": %.6g, \"ok\": %s, \"problem\": \"%s\"}",
                    r ? ", " : "", static_cast<long long>(t.n), t.radius, t.threads, t.mean_candidates,
                    t.mean_limited, t.mean_delaunay, t.calls, t.cgal, t.scan1, t.scan1_call, t.scant, t.chords1,
                    t.ok ? "true" : "false", t.problem.c_str());
    }
    std::printf("]}\n");
}

void print_header(double k, int reps, double window) {
    std::printf("dvoronoi limited_cells vs CGAL %s Delaunay_triangulation_2 (Epick) + neighbour walk\n",
                cgal_version());
    std::printf("CPU: %s, %d hardware threads, OpenMP: %s, -march=native: %s; best of %d rounds of\n"
                "ceil(%g / n) calls each (the mean call of a round)\n",
                cpu_model().c_str(), hardware_threads(),
#ifdef _OPENMP
                "yes",
#else
                "no (the T-thread run is single-threaded)",
#endif
#ifdef DVORONOI_BENCH_NATIVE
                "yes",
#else
                "no",
#endif
                reps, window);
    std::printf("points: uniform in [0,1)^2, R = sqrt(%g / (4 pi n)) (about %g agents within 2R)\n", k, k);
}

}  // namespace

int main(int argc, char** argv) {
    Index n = 1000000;
    double k = 30.0;
    int reps = 3, threads = 2;
    double window = 1e6;
    std::uint64_t seed = 1;
    bool json = false;
    std::string sizes;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        auto value = [&]() -> std::string {
            if (a + 1 >= argc) {
                std::fprintf(stderr, "bench_limited_cgal: %s needs a value\n", arg.c_str());
                std::exit(1);
            }
            return argv[++a];
        };
        try {
            if (arg == "--n") n = static_cast<Index>(std::llround(std::stod(value())));
            else if (arg == "--k") k = std::stod(value());
            else if (arg == "--reps") reps = std::stoi(value());
            else if (arg == "--threads") threads = std::stoi(value());
            else if (arg == "--seed") seed = static_cast<std::uint64_t>(std::stoull(value()));
            else if (arg == "--sizes") sizes = value();
            else if (arg == "--window") window = std::stod(value());
            else if (arg == "--json") json = true;
            else if (arg == "-h" || arg == "--help") { usage(); return 0; }
            else {
                std::fprintf(stderr, "bench_limited_cgal: unknown argument %s\n", arg.c_str());
                usage();
                return 1;
            }
        } catch (const std::exception&) {
            std::fprintf(stderr, "bench_limited_cgal: bad value for %s\n", arg.c_str());
            return 1;
        }
    }
    if (n < 1 || reps < 1 || threads < 1 || !(k > 0.0) || !(window >= 0.0)) {
        std::fprintf(stderr, "bench_limited_cgal: --n, --reps, --threads and --k must be positive, --window not negative\n");
        return 1;
    }
#ifndef _OPENMP
    threads = 1;
#endif

    std::vector<Timing> rows;
    try {
        if (!sizes.empty()) {
            for (Index s : parse_sizes(sizes)) rows.push_back(run(s, k, reps, window, threads, seed, !json));
        } else {
            rows.push_back(run(n, k, reps, window, threads, seed, !json));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_limited_cgal: %s\n", e.what());
        return 1;
    }
    bool ok = true;
    for (const Timing& t : rows) ok = ok && t.ok;

    if (json) {
        print_json(rows, k, reps, window);
        return ok ? 0 : 2;
    }
    print_header(k, reps, window);
    if (sizes.empty()) {
        const Timing& t = rows[0];
        std::printf("n = %lld, seed %llu, R = %.6g; per agent: %.2f agents within 2R, %.2f limited neighbours, "
                    "%.2f Delaunay neighbours\n\n",
                    static_cast<long long>(t.n), static_cast<unsigned long long>(seed), t.radius,
                    t.mean_candidates, t.mean_limited, t.mean_delaunay);
        std::printf("| %-46s | %9s | %9s | %-26s |\n", "what", "time (s)", "ns/agent", "ratio");
        std::printf("|%s|%s|%s|%s|\n", std::string(48, '-').c_str(), std::string(11, '-').c_str(),
                    std::string(11, '-').c_str(), std::string(28, '-').c_str());
        auto row = [&](const char* what, double s, const std::string& ratio) {
            std::printf("| %-46s | %9.3f | %9.0f | %-26s |\n", what, s, ns_per_agent(s, t.n), ratio.c_str());
        };
        char buf[128];
        row("(a) CGAL Delaunay + neighbour walk, 1 thread", t.cgal, "1 (reference)");
        std::snprintf(buf, sizeof buf, "%.2f x CGAL time", t.scan1 / t.cgal);
        row("(b) dvoronoi auto, 1 thread", t.scan1, buf);
        char what[64];
        std::snprintf(what, sizeof what, "(c) dvoronoi auto, %d threads", t.threads);
        std::snprintf(buf, sizeof buf, "%.2f x speed-up over (b)", t.scan1 / t.scant);
        row(what, t.scant, buf);
        std::snprintf(buf, sizeof buf, "%.2f x CGAL, %.2f x auto", t.chords1 / t.cgal, t.chords1 / t.scan1);
        row("(d) dvoronoi Chords (RCVC), 1 thread", t.chords1, buf);
        std::printf("\n(a) gives the full Delaunay graph only; (b)-(d) give limited neighbours plus every cell's\n"
                    "pieces, area, perimeter and centroid. Checks: %s\n",
                    t.ok ? "auto = Chords = multi-threaded, limited neighbours within Delaunay ones: ok"
                         : ("FAILED:" + t.problem).c_str());
    } else {
        std::printf("seed %llu; time per agent in ns (flat = linear scaling)\n\n",
                    static_cast<unsigned long long>(seed));
        std::printf("| %10s | %10s | %8s | %10s | %12s | %12s | %12s | %13s |\n", "n", "R", "in 2R",
                    "CGAL", "auto 1 thr", "auto T thr", "Chords 1 thr", "auto1 / CGAL");
        std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(12, '-').c_str(), std::string(12, '-').c_str(),
                    std::string(10, '-').c_str(), std::string(12, '-').c_str(), std::string(14, '-').c_str(),
                    std::string(14, '-').c_str(), std::string(14, '-').c_str(), std::string(15, '-').c_str());
        for (const Timing& t : rows)
            std::printf("| %10lld | %10.4g | %8.2f | %10.0f | %12.0f | %12.0f | %12.0f | %13.2f |\n",
                        static_cast<long long>(t.n), t.radius, t.mean_candidates, ns_per_agent(t.cgal, t.n),
                        ns_per_agent(t.scan1, t.n), ns_per_agent(t.scant, t.n), ns_per_agent(t.chords1, t.n),
                        t.scan1 / t.cgal);
        std::printf("\nT = %d threads. Checks: %s\n", rows.empty() ? threads : rows[0].threads,
                    ok ? "ok" : "FAILED (see --json)");
        if (rows.size() >= 2) {
            // Flatness of (b): the largest size against the smallest, per agent; also by the fastest
            // single call, the timing before rounds of equal work (it favours small, short calls).
            const Timing& a = rows.front();
            const Timing& b = rows.back();
            const auto per = [](double s, Index m) { return s / static_cast<double>(m); };
            std::printf("auto 1 thread, time per agent at n = %lld against n = %lld: %+.1f%% (rounds of %g agents), "
                        "%+.1f%% (fastest single calls)\n",
                        static_cast<long long>(b.n), static_cast<long long>(a.n),
                        100.0 * (per(b.scan1, b.n) / per(a.scan1, a.n) - 1.0), window,
                        100.0 * (per(b.scan1_call, b.n) / per(a.scan1_call, a.n) - 1.0));
        }
    }
    return ok ? 0 : 2;
}
