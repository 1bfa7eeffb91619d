// CGAL's side of the C++ benchmarks (bench_cgal.hpp), compiled with CGAL's flags.
#include "bench_cgal.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/version.h>

#include <algorithm>
#include <utility>

namespace bench {

using dvoronoi::Index;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;

CgalResult cgal_delaunay_neighbors(const dvoronoi::Points& pts) {
    const Index n = pts.rows();
    CgalResult r;
    std::vector<std::pair<K::Point_2, Index>> input;
    input.reserve(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) input.emplace_back(K::Point_2(pts(i, 0), pts(i, 1)), i);
    auto dt = std::make_shared<Delaunay>();
    r.dt = dt;
    dt->insert(input.begin(), input.end());  // spatial sort + insertion

    // The neighbour walk in the triangulation's own vertex order (after CGAL's spatial sort each
    // vertex's faces lie near the previous one's in memory), rows placed by the input index: what a
    // user who wants the CSR writes. Walking by input index instead jumps through memory at every
    // vertex, a cache miss per face for large n, which is a cost of the walk, not of CGAL.
    Csr& g = r.graph;
    g.indptr.assign(static_cast<std::size_t>(n) + 1, 0);
    for (auto v : dt->finite_vertex_handles()) {
        Index degree = 0;
        auto c = dt->incident_vertices(v);
        const auto done = c;
        if (c != nullptr) {
            do {
                degree += dt->is_infinite(c) ? 0 : 1;
            } while (++c != done);
        }
        g.indptr[static_cast<std::size_t>(v->info()) + 1] = degree;
    }
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) g.indptr[i + 1] += g.indptr[i];
    g.indices.resize(static_cast<std::size_t>(g.indptr.back()));
    for (auto v : dt->finite_vertex_handles()) {
        Index* row = g.indices.data() + g.indptr[static_cast<std::size_t>(v->info())];
        Index* at = row;
        auto c = dt->incident_vertices(v);
        const auto done = c;
        if (c != nullptr) {
            do {
                if (!dt->is_infinite(c)) *at++ = c->info();
            } while (++c != done);
        }
        std::sort(row, at);
    }
    return r;
}

const char* cgal_version() { return CGAL_VERSION_STR; }

}  // namespace bench
