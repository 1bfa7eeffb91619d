// CGAL's Delaunay triangulation + neighbour walk, the reference the C++ benchmarks compare against,
// compiled on its own (bench_cgal.cpp). Why a translation unit of its own: CGAL needs
// -frounding-math, which would otherwise apply to dvoronoi's code in the benchmark too (measured:
// about 1% of limited_cells); dvoronoi as it ships (the Python module, the CLI) is built without it.
#pragma once

#include <dvoronoi/core/types.hpp>

#include <memory>
#include <vector>

namespace bench {

struct Csr {
    std::vector<dvoronoi::Index> indptr, indices;
};

/// CGAL's answer: the triangulation (kept alive so its destruction is not timed) and the CSR graph
/// (each agent's Delaunay neighbours, ascending, in input order).
struct CgalResult {
    std::shared_ptr<void> dt;
    Csr graph;
};

/// Delaunay_triangulation_2 (Epick) of the points by a range insert of (point, index) pairs (CGAL
/// sorts them spatially), then the neighbour walk.
CgalResult cgal_delaunay_neighbors(const dvoronoi::Points& pts);

/// CGAL's version, as CGAL_VERSION_STR.
const char* cgal_version();

}  // namespace bench
