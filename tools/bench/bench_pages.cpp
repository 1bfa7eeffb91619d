// One timed call of limited_cells, voronoi_cells or the grid diagram's feature transform on uniform
// random input, for tools/bench_pages.sh, which runs it built with and without page mapping
// (-DDVORONOI_NO_PAGE_MAPPING, core/pages.hpp) side by side.
//   bench_pages limited|voronoi|features N THREADS     (features: an N x N grid, 0.2% occupied)
// Prints the call's wall time in seconds; the script reads the process's CPU time around it.
#include "dvoronoi/gvd/feature_transform.hpp"
#include "dvoronoi/partition/limited_partition.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

int main(int argc, char** argv) {
    using namespace dvoronoi;
    if (argc != 4) {
        std::fprintf(stderr, "usage: bench_pages limited|voronoi|features N THREADS\n");
        return 2;
    }
    const std::string what = argv[1];
    const double n = std::atof(argv[2]);
    const int threads = std::atoi(argv[3]);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::size_t check = 0;  // something of the result, so that the call cannot be left out
    if (what == "features") {
        const auto side = static_cast<std::int32_t>(n);
        gvd::OccupancyGrid g(side, side);
        for (auto& o : g.occupied) o = u(rng) < 0.002;
        const auto t1 = std::chrono::steady_clock::now();
        check = static_cast<std::size_t>(gvd::feature_transform(g, threads).fx[0]);
        std::printf("%.4f %zu\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), check);
        return 0;
    }
    const auto count = static_cast<Index>(n);
    Points p(count, 2);
    for (Index i = 0; i < count; ++i) p(i, 0) = u(rng), p(i, 1) = u(rng);
    const double radius = std::sqrt(30.0 / (4.0 * 3.14159265358979323846 * n));  // ~30 agents within 2R
    const auto t1 = std::chrono::steady_clock::now();
    if (what == "limited")
        check = limited_cells(p, radius, Method::Auto, threads).indices.size();
    else
        check = voronoi_cells(p, AsrInner::Auto, threads).indices.size();
    std::printf("%.4f %zu\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), check);
    return 0;
}
