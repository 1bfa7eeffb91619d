// Shared by the C++ benchmarks: CGAL's Delaunay triangulation + neighbour walk (the reference a
// user would otherwise pick), timing, the uniform inputs, and what machine the numbers come from.
#pragma once

#include <dvoronoi/core/types.hpp>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/version.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
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
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;

constexpr double kPi = 3.14159265358979323846;

struct Csr {
    std::vector<Index> indptr, indices;
};

/// CGAL's answer: the triangulation (kept alive so its destruction is not timed) and the CSR graph.
struct CgalResult {
    std::unique_ptr<Delaunay> dt;
    Csr graph;
};

inline CgalResult cgal_delaunay_neighbors(const dvoronoi::Points& pts) {
    const Index n = pts.rows();
    CgalResult r;
    std::vector<std::pair<K::Point_2, Index>> input;
    input.reserve(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) input.emplace_back(K::Point_2(pts(i, 0), pts(i, 1)), i);
    r.dt = std::make_unique<Delaunay>();
    r.dt->insert(input.begin(), input.end());  // spatial sort + insertion

    std::vector<Delaunay::Vertex_handle> handle(static_cast<std::size_t>(n));
    for (auto v : r.dt->finite_vertex_handles()) handle[static_cast<std::size_t>(v->info())] = v;
    Csr& g = r.graph;
    g.indptr.assign(static_cast<std::size_t>(n) + 1, 0);
    g.indices.reserve(static_cast<std::size_t>(n) * 6 + 16);
    for (Index i = 0; i < n; ++i) {
        const std::size_t begin = g.indices.size();
        auto c = r.dt->incident_vertices(handle[static_cast<std::size_t>(i)]);
        const auto done = c;
        if (c != nullptr) {
            do {
                if (!r.dt->is_infinite(c)) g.indices.push_back(c->info());
            } while (++c != done);
        }
        std::sort(g.indices.begin() + static_cast<std::ptrdiff_t>(begin), g.indices.end());
        g.indptr[static_cast<std::size_t>(i) + 1] = static_cast<Index>(g.indices.size());
    }
    return r;
}

inline double now_seconds() {
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

/// Best of `reps` runs of f(), which returns a result; the result of the last run is kept in `keep`
/// and every other result is destroyed outside the timed region.
template <class F, class R>
double best_of(int reps, F&& f, R& keep) {
    double best = 1e300;
    for (int r = 0; r < reps; ++r) {
        R tmp;
        const double t0 = now_seconds();
        tmp = f();
        const double t1 = now_seconds();
        best = std::min(best, t1 - t0);
        if (r + 1 == reps) keep = std::move(tmp);
    }
    return best;
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
