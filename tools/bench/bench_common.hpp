// Shared by the C++ benchmarks: CGAL's Delaunay triangulation + neighbour walk (the reference a
// user would otherwise pick; bench_cgal.hpp), timing, the uniform inputs, and what machine the
// numbers come from.
#pragma once

#include "bench_cgal.hpp"

#include <dvoronoi/core/types.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace bench {

using dvoronoi::Index;

constexpr double kPi = 3.14159265358979323846;

inline double now_seconds() {
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

/// Best of `reps` rounds of `calls` consecutive calls of f(), which returns a result: the mean time
/// per call of the best round. The clock stops while a result is destroyed; the last call's result is
/// kept in `keep`; `best_call`, if given, receives the fastest single call. Rounds of many calls for
/// small inputs (Google Benchmark's "minimum time" rule): every timing then spans about as much work
/// and wall time whatever n is, so a 10 ms call cannot win by landing in the machine's quiet
/// moments, where a 1 s call always takes the machine's interruptions in.
template <class F, class R>
double best_of(int reps, F&& f, R& keep, int calls = 1, double* best_call = nullptr) {
    double best = 1e300, single = 1e300;
    for (int r = 0; r < reps; ++r) {
        double total = 0.0;
        for (int c = 0; c < calls; ++c) {
            R tmp;
            const double t0 = now_seconds();
            tmp = f();
            const double t1 = now_seconds();
            total += t1 - t0;
            single = std::min(single, t1 - t0);
            if (r + 1 == reps && c + 1 == calls) keep = std::move(tmp);
        }
        best = std::min(best, total / calls);
    }
    if (best_call) *best_call = single;
    return best;
}

/// Calls per timing round so that a round covers at least `window` agents.
inline int calls_for(Index n, double window) {
    return static_cast<int>(std::max(1.0, std::ceil(window / static_cast<double>(std::max<Index>(n, 1)))));
}

inline dvoronoi::Points uniform_points(Index n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    dvoronoi::Points p(n, 2);
    for (Index i = 0; i < n; ++i) {
        p(i, 0) = u(rng);
        p(i, 1) = u(rng);
    }
    return p;
}

inline double ns_per_agent(double seconds, Index n) { return n ? seconds * 1e9 / static_cast<double>(n) : 0.0; }

inline std::vector<Index> parse_sizes(const std::string& s) {
    std::vector<Index> out;
    std::size_t pos = 0;
    while (pos <= s.size()) {
        const std::size_t comma = s.find(',', pos);
        const std::string tok = s.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
        if (!tok.empty()) out.push_back(static_cast<Index>(std::llround(std::stod(tok))));
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    return out;
}

inline int hardware_threads() {
#ifdef _OPENMP
    return omp_get_num_procs();
#else
    return static_cast<int>(std::thread::hardware_concurrency());
#endif
}

inline std::string cpu_model() {
    std::ifstream f("/proc/cpuinfo");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(colon + 2);
        }
    return "unknown";
}

}  // namespace bench
