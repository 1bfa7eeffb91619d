// bench_voronoi_cgal: dvoronoi's exact Voronoi cells (Adjust-Sensing-Radius, every agent) against
// CGAL's Delaunay triangulation + neighbour walk, on the same uniform random points, in one process.
//
// What is timed (best of --reps runs each):
//   (a) CGAL: Delaunay_triangulation_2 (Epick), range insert with spatial sort, then the neighbour
//       walk into CSR arrays (bench_common.hpp).
//   (b) dvoronoi::voronoi_cells(AsrInner::Auto, the fast path, 1 thread): exact Voronoi neighbours (CSR), hull flags,
//       areas and centroids of the bounded cells, per-agent radius steps and agents used.
//   (c) the same with --threads threads.
//   (d) dvoronoi::voronoi_cells(AsrInner::Evt, 1 thread).
// CGAL builds one global structure; dvoronoi computes each agent's cell from nearby agents only (what
// each robot would do), then certifies it. Sanity (untimed): (b) = (c) = (d), and equal to CGAL's
// Delaunay graph (uniform random doubles have no cocircular quadruples, so the graphs coincide).
//
// Usage: bench_voronoi_cgal [--n 1e6] [--reps 3] [--threads 2] [--seed 1] [--sizes 1e4,1e5,1e6]
#include "bench_common.hpp"

#include <dvoronoi/partition/voronoi_partition.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using namespace bench;

struct Row {
    Index n = 0;
    double cgal = 0, scan1 = 0, scant = 0, evt1 = 0;
    double mean_steps = 0, median_used = 0;
    bool ok = true;
};

Csr csr_of(dvoronoi::VoronoiPartition&& p) {
    Csr c;
    c.indptr = std::move(p.indptr);
    c.indices = std::move(p.indices);
    return c;
}

Row run(Index n, int reps, int threads, std::uint64_t seed) {
    Row r;
    r.n = n;
    const dvoronoi::Points pts = uniform_points(n, seed);
    std::fprintf(stderr, "  n = %lld: CGAL ...\n", static_cast<long long>(n));
    CgalResult cg;
    r.cgal = best_of(reps, [&] { return cgal_delaunay_neighbors(pts); }, cg);
    cg.dt.reset();
    dvoronoi::VoronoiPartition p;
    std::fprintf(stderr, "  n = %lld: dvoronoi ASR+BS, 1 thread ...\n", static_cast<long long>(n));
    r.scan1 = best_of(reps, [&] { return dvoronoi::voronoi_cells(pts, dvoronoi::AsrInner::Auto, 1); }, p);
    double steps = 0;
    for (Index i = 0; i < n; ++i) steps += p.radius_steps[static_cast<std::size_t>(i)];
    r.mean_steps = steps / static_cast<double>(n);
    // The median: agents near the hull use every agent, so the mean says little.
    std::vector<Index> used(p.agents_used);
    std::nth_element(used.begin(), used.begin() + static_cast<std::ptrdiff_t>(used.size() / 2), used.end());
    r.median_used = n > 0 ? static_cast<double>(used[used.size() / 2]) : 0.0;
    const Csr scan1 = csr_of(std::move(p));
    std::fprintf(stderr, "  n = %lld: dvoronoi ASR+BS, %d threads ...\n", static_cast<long long>(n), threads);
    r.scant = best_of(reps, [&] { return dvoronoi::voronoi_cells(pts, dvoronoi::AsrInner::Auto, threads); }, p);
    const Csr scant = csr_of(std::move(p));
    std::fprintf(stderr, "  n = %lld: dvoronoi ASR+EVT, 1 thread ...\n", static_cast<long long>(n));
    r.evt1 = best_of(reps, [&] { return dvoronoi::voronoi_cells(pts, dvoronoi::AsrInner::Evt, 1); }, p);
    const Csr evt1 = csr_of(std::move(p));
    const auto same = [](const Csr& a, const Csr& b) { return a.indptr == b.indptr && a.indices == b.indices; };
    r.ok = same(scan1, scant) && same(scan1, evt1) && same(scan1, cg.graph);
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    Index n = 1000000;
    int reps = 3, threads = 2;
    std::uint64_t seed = 1;
    std::string sizes;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (a + 1 >= argc) {
            std::fprintf(stderr, "usage: bench_voronoi_cgal [--n N] [--reps R] [--threads T] [--seed S] [--sizes N1,N2]\n");
            return 1;
        }
        const std::string v = argv[++a];
        if (arg == "--n") n = static_cast<Index>(std::llround(std::stod(v)));
        else if (arg == "--reps") reps = std::stoi(v);
        else if (arg == "--threads") threads = std::stoi(v);
        else if (arg == "--seed") seed = std::stoull(v);
        else if (arg == "--sizes") sizes = v;
        else {
            std::fprintf(stderr, "bench_voronoi_cgal: unknown argument %s\n", arg.c_str());
            return 1;
        }
    }
    std::vector<Index> ns = sizes.empty() ? std::vector<Index>{n} : parse_sizes(sizes);
    std::printf("dvoronoi voronoi_cells (ASR, exact cells) vs CGAL %s Delaunay_triangulation_2 (Epick) + neighbour walk\n",
                cgal_version());
    std::printf("CPU: %s, %d hardware threads; uniform points in [0,1)^2, seed %llu, best of %d\n\n",
                cpu_model().c_str(), hardware_threads(), static_cast<unsigned long long>(seed), reps);
    std::printf("| %9s | %8s | %8s | %8s | %8s | %11s | %11s | %12s | %6s | %5s |\n", "n", "CGAL s", "BS 1t s",
                "BS Tt s", "EVT 1t s", "BS1 / CGAL", "EVT1 / CGAL", "BS speed-up", "steps", "used*");
    bool ok = true;
    for (Index s : ns) {
        const Row r = run(s, reps, threads, seed);
        ok = ok && r.ok;
        std::printf("| %9lld | %8.3f | %8.3f | %8.3f | %8.3f | %10.2fx | %10.2fx | %11.2fx | %6.2f | %5.1f |%s\n",
                    static_cast<long long>(r.n), r.cgal, r.scan1, r.scant, r.evt1, r.scan1 / r.cgal,
                    r.evt1 / r.cgal, r.scan1 / r.scant, r.mean_steps, r.median_used, r.ok ? "" : "  MISMATCH");
        std::fflush(stdout);
    }
    std::printf("\nsteps: mean radius steps; used*: median agents within twice the final radius (ASR's own\n"
                "numbers per agent). ratios > 1: dvoronoi slower than CGAL. Checks (neighbours of BS 1t = BS Tt = EVT = CGAL): %s\n",
                ok ? "ok" : "FAILED");
    return ok ? 0 : 2;
}
