// bench_distances: dvoronoi's distance-only Voronoi neighbours (Elwin, Freeman & Lynch) against what a
// user would otherwise do with distances only — localise, then triangulate — in one process.
//
// Robots: n uniform in [0,1)^2 (std::mt19937_64, --seed); every pair closer than R detects each other,
// R = sqrt(k / (pi n)) so that a robot detects about k others (--k, default 30). Distances are the
// exact Euclidean ones rounded to double.
//
// What is timed:
//   (a) one robot with exactly k detected robots: dvoronoi::dist::voronoi_neighbors on its local
//       table (distances to its detected robots and among them), cycling over 1000 different robots
//       so branch predictors cannot learn one input; and the same including building the table from
//       the CSR graph.
//   (b) the alternative for the same robots: classical MDS (Eigen's SelfAdjointEigenSolver on the
//       (k+1) x (k+1) double-centred squared-distance matrix) to place the robot and its detected
//       robots, then CGAL's Delaunay_triangulation_2 (Epick) of those k+1 points and a circulation
//       around the robot. MDS needs every pairwise distance, which two robots up to 2R apart have not
//       measured; we hand it the complete true local matrix, which favours the alternative.
//   (c) all n robots: dvoronoi::dist::neighbors_from_distances with 1 and --threads threads (no
//       consistency step, to time the same thing as (b)); (b) extrapolated to n from the 1000 robots.
// Sanity (outside timings): for the 1000 robots, how often the MDS+Delaunay answer equals ours.
//
// Usage: bench_distances [--n 1e5] [--k 30] [--threads 2] [--seed 1]
#include <dvoronoi/distances/neighbors_from_distances.hpp>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {
using dvoronoi::Index;
namespace dd = dvoronoi::dist;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using Clock = std::chrono::steady_clock;
double secs(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

/// MDS + Delaunay: the local indices of the centre's Delaunay neighbours (the centre is local m).
std::set<int> mds_delaunay(const Eigen::MatrixXd& d2) {
    const Eigen::Index m = d2.rows();
    const Eigen::MatrixXd J = Eigen::MatrixXd::Identity(m, m) - Eigen::MatrixXd::Constant(m, m, 1.0 / double(m));
    const Eigen::MatrixXd B = -0.5 * J * d2 * J;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(B);
    const Eigen::VectorXd w = es.eigenvalues().tail(2).cwiseMax(0.0).cwiseSqrt();
    const Eigen::MatrixXd X = es.eigenvectors().rightCols(2) * w.asDiagonal();
    std::vector<std::pair<K::Point_2, int>> pts;
    for (Eigen::Index r = 0; r < m; ++r) pts.push_back({K::Point_2(X(r, 0), X(r, 1)), int(r)});
    Delaunay dt(pts.begin(), pts.end());
    std::set<int> out;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
        if (v->info() != int(m - 1)) continue;
        auto c = dt.incident_vertices(v), done = c;
        do {
            if (!dt.is_infinite(c)) out.insert(c->info());
        } while (++c != done);
    }
    return out;
}
}  // namespace

int main(int argc, char** argv) {
    Index n = 100000;
    int k = 30, threads = 2;
    unsigned seed = 1;
    for (int a = 1; a + 1 < argc; a += 2) {
        const std::string arg = argv[a];
        if (arg == "--n") n = Index(std::llround(std::stod(argv[a + 1])));
        else if (arg == "--k") k = std::stoi(argv[a + 1]);
        else if (arg == "--threads") threads = std::stoi(argv[a + 1]);
        else if (arg == "--seed") seed = unsigned(std::stoul(argv[a + 1]));
        else { std::fprintf(stderr, "usage: bench_distances [--n 1e5] [--k 30] [--threads 2] [--seed 1]\n"); return 2; }
    }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> x(static_cast<size_t>(n)), y(static_cast<size_t>(n));
    for (Index i = 0; i < n; ++i) x[size_t(i)] = u(rng), y[size_t(i)] = u(rng);
    const double R = std::sqrt(double(k) / (M_PI * double(n)));
    // Detection graph with a uniform grid of cell size >= R.
    const int G = std::max(1, int(1.0 / R));
    std::vector<std::vector<Index>> cell(size_t(G) * size_t(G));
    const auto cidx = [&](double v) { return std::min(G - 1, int(v * G)); };
    for (Index i = 0; i < n; ++i) cell[size_t(cidx(y[size_t(i)])) * size_t(G) + size_t(cidx(x[size_t(i)]))].push_back(i);
    std::vector<Index> rows, cols;
    std::vector<double> vals;
    for (Index i = 0; i < n; ++i) {
        const int gx = cidx(x[size_t(i)]), gy = cidx(y[size_t(i)]);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int qx = gx + dx, qy = gy + dy;
                if (qx < 0 || qy < 0 || qx >= G || qy >= G) continue;
                for (Index j : cell[size_t(qy) * size_t(G) + size_t(qx)]) {
                    if (j <= i) continue;
                    const double d = std::hypot(x[size_t(i)] - x[size_t(j)], y[size_t(i)] - y[size_t(j)]);
                    if (d < R) rows.push_back(i), cols.push_back(j), vals.push_back(d);
                }
            }
    }
    const dd::DistanceGraph g = dd::make_distance_graph(n, rows, cols, vals);
    std::printf("bench_distances: n = %lld robots, R = %.4g (mean detected %.1f), seed %u\n", (long long)n, R,
                2.0 * double(rows.size()) / double(n), seed);

    // (a) one robot with exactly k detected robots, 1000 different ones.
    std::vector<Index> sample;
    for (Index i = 0; i < n && sample.size() < 1000; ++i)
        if (g.degree(i) == k) sample.push_back(i);
    std::vector<int> slot(size_t(n), -1);
    std::vector<dd::LocalTable> tables(sample.size());
    for (size_t s = 0; s < sample.size(); ++s) dd::local_table(g, sample[s], tables[s], slot);
    dd::NeighborPath path;
    dd::NeighborWorkspace ws;
    std::vector<std::set<int>> ours(sample.size());
    for (size_t s = 0; s < sample.size(); ++s) {
        dd::voronoi_neighbors(tables[s], path, ws);
        ours[s] = std::set<int>(path.order.begin(), path.order.end());
    }
    const int rounds = 20;
    double best_alg = 1e9, best_tab = 1e9;
    for (int r = 0; r < 5; ++r) {
        auto t0 = Clock::now();
        for (int q = 0; q < rounds; ++q)
            for (const auto& t : tables) dd::voronoi_neighbors(t, path, ws);
        auto t1 = Clock::now();
        dd::LocalTable t;
        for (int q = 0; q < rounds; ++q)
            for (Index i : sample) {
                dd::local_table(g, i, t, slot);
                dd::voronoi_neighbors(t, path, ws);
            }
        auto t2 = Clock::now();
        best_alg = std::min(best_alg, secs(t0, t1) / double(rounds * sample.size()));
        best_tab = std::min(best_tab, secs(t1, t2) / double(rounds * sample.size()));
    }
    // (b) MDS + Delaunay on the same robots (complete true local distance matrices).
    std::vector<Eigen::MatrixXd> d2s;
    for (Index i : sample) {
        std::vector<Index> ids(g.indices.begin() + g.indptr[size_t(i)], g.indices.begin() + g.indptr[size_t(i) + 1]);
        ids.push_back(i);  // the centre is the last local index
        const Eigen::Index m = Eigen::Index(ids.size());
        Eigen::MatrixXd d2(m, m);
        for (Eigen::Index a = 0; a < m; ++a)
            for (Eigen::Index b = 0; b < m; ++b) {
                const double ddx = x[size_t(ids[size_t(a)])] - x[size_t(ids[size_t(b)])], ddy = y[size_t(ids[size_t(a)])] - y[size_t(ids[size_t(b)])];
                d2(a, b) = ddx * ddx + ddy * ddy;
            }
        d2s.push_back(d2);
    }
    size_t agree = 0;
    double best_alt = 1e9;
    std::vector<std::set<int>> alt(sample.size());
    for (int r = 0; r < 3; ++r) {
        auto t0 = Clock::now();
        for (size_t s = 0; s < d2s.size(); ++s) alt[s] = mds_delaunay(d2s[s]);
        best_alt = std::min(best_alt, secs(t0, Clock::now()) / double(d2s.size()));
    }
    for (size_t s = 0; s < d2s.size(); ++s) agree += alt[s] == ours[s];
    // The exact answer: CGAL's Delaunay triangulation of all n robots (outside the timings).
    std::vector<std::pair<K::Point_2, int>> all;
    for (Index i = 0; i < n; ++i) all.push_back({K::Point_2(x[size_t(i)], y[size_t(i)]), int(i)});
    const Delaunay full(all.begin(), all.end());
    std::vector<std::set<Index>> truth(static_cast<size_t>(n));
    for (auto e = full.finite_edges_begin(); e != full.finite_edges_end(); ++e) {
        const int a = e->first->vertex(full.cw(e->second))->info(), b = e->first->vertex(full.ccw(e->second))->info();
        truth[size_t(a)].insert(b);
        truth[size_t(b)].insert(a);
    }
    size_t ours_exact = 0, alt_exact = 0;
    for (size_t s = 0; s < sample.size(); ++s) {
        const Index base = g.indptr[size_t(sample[s])];
        std::set<Index> go, ga;
        for (int v : ours[s]) go.insert(g.indices[size_t(base + v)]);
        for (int v : alt[s]) ga.insert(g.indices[size_t(base + v)]);
        ours_exact += go == truth[size_t(sample[s])];
        alt_exact += ga == truth[size_t(sample[s])];
    }
    std::printf("\n(a/b) one robot with %d detected robots (%zu robots, best of 5):\n", k, sample.size());
    std::printf("  dvoronoi voronoi_neighbors (table given)      %8.2f us\n", 1e6 * best_alg);
    std::printf("  dvoronoi incl. table from the CSR graph        %8.2f us\n", 1e6 * best_tab);
    std::printf("  MDS (Eigen) + CGAL Delaunay                    %8.2f us   ratio %.1fx\n", 1e6 * best_alt, best_alt / best_tab);
    std::printf("  MDS+Delaunay answer equal to ours: %zu / %zu robots\n", agree, sample.size());
    std::printf("  equal to the exact answer (CGAL Delaunay of all robots): dvoronoi %zu, MDS+Delaunay %zu of %zu\n",
                ours_exact, alt_exact, sample.size());

    // (c) all robots.
    double t1th = 1e9, tth = 1e9;
    for (int r = 0; r < 2; ++r) {
        auto t0 = Clock::now();
        const dd::DistanceNeighbors a = dd::neighbors_from_distances(g, false, 1);
        auto t1 = Clock::now();
        const dd::DistanceNeighbors b = dd::neighbors_from_distances(g, false, threads);
        auto t2 = Clock::now();
        t1th = std::min(t1th, secs(t0, t1));
        tth = std::min(tth, secs(t1, t2));
        if (a.indices != b.indices) { std::printf("MISMATCH between thread counts\n"); return 2; }
    }
    const double alt_all = best_alt * double(n);
    std::printf("\n(c) all %lld robots (best of 2):\n", (long long)n);
    std::printf("  dvoronoi, 1 thread                  %8.3f s  (%.2f us/robot)\n", t1th, 1e6 * t1th / double(n));
    std::printf("  dvoronoi, %d threads                 %8.3f s  (speed-up %.2fx)\n", threads, tth, t1th / tth);
    std::printf("  MDS + CGAL Delaunay per robot, 1 thread (extrapolated) %8.3f s   ratio %.1fx vs dvoronoi 1 thread\n", alt_all, alt_all / t1th);
    return 0;
}
