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

    std::vector<Delaunay::Vertex_handle> handle(static_cast<std::size_t>(n));
    for (auto v : dt->finite_vertex_handles()) handle[static_cast<std::size_t>(v->info())] = v;
    Csr& g = r.graph;
    g.indptr.assign(static_cast<std::size_t>(n) + 1, 0);
    g.indices.reserve(static_cast<std::size_t>(n) * 6 + 16);
    for (Index i = 0; i < n; ++i) {
        const std::size_t begin = g.indices.size();
        auto c = dt->incident_vertices(handle[static_cast<std::size_t>(i)]);
        const auto done = c;
        if (c != nullptr) {
            do {
                if (!dt->is_infinite(c)) g.indices.push_back(c->info());
            } while (++c != done);
        }
        std::sort(g.indices.begin() + static_cast<std::ptrdiff_t>(begin), g.indices.end());
        g.indptr[static_cast<std::size_t>(i) + 1] = static_cast<Index>(g.indices.size());
    }
    return r;
}

const char* cgal_version() { return CGAL_VERSION_STR; }

}  // namespace bench
