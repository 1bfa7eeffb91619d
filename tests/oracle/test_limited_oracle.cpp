// dvoronoi::limited_cells and dvoronoi::limited_cell against the exact CGAL oracle.
//
// For both methods (Scan, Chords): limited-neighbour sets equal the exact ones, areas agree to
// 1e-9 relative (floor 1e-12 R^2), edge neighbours are symmetric, and exactly transformed copies
// of every input (permuted, translated and scaled by powers of two, rotated by 90°, mirrored) give
// the same sets. Inputs: seeded uniform points over a range of densities, random integer-grid
// subsets, and every case of tests/data/degenerate_corpus.txt.
#include "cgal_oracle.hpp"
#include "families.hpp"

#include <dvoronoi/partition/limited_partition.hpp>

#include <doctest/doctest.h>

#include <cstdio>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using dvoronoi_oracle::NamedCase;
using dvoronoi_oracle::OracleResult;
using dvoronoi_oracle::Transformed;
using dvoronoi_oracle::XY;

constexpr double kAreaRel = 1e-9;
constexpr double kAreaAbs = 1e-12;  // times R^2
constexpr int kMaxReports = 8;      // detailed reports per case and method

std::string fmt(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

template <class C>
std::string fmt_set(const C& c) {
    std::ostringstream s;
    s << '{';
    bool first = true;
    for (auto v : c) {
        s << (first ? "" : ", ") << v;
        first = false;
    }
    s << '}';
    return s.str();
}

dvoronoi::Points to_points(const std::vector<XY>& pts) {
    dvoronoi::Points m(static_cast<Eigen::Index>(pts.size()), 2);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        m(static_cast<Eigen::Index>(i), 0) = pts[i][0];
        m(static_cast<Eigen::Index>(i), 1) = pts[i][1];
    }
    return m;
}

bool area_close(double got, double expected, double radius) {
    return std::fabs(got - expected) <= kAreaRel * std::fabs(expected) + kAreaAbs * radius * radius;
}

/// Centroids: 1e-9 R, plus the rounding of a coordinate of magnitude |p| (64 units in the last place):
/// a centroid is stored in the caller's frame, so it cannot be closer than that.
bool centroid_close(const XY& got, const XY& expected, double radius) {
    const double mag = std::max(std::fabs(expected[0]), std::fabs(expected[1]));
    return std::hypot(got[0] - expected[0], got[1] - expected[1]) <=
           kAreaRel * radius + 64.0 * 0x1p-53 * mag;
}

/// Diagnostic for an area mismatch: the same cell computed by limited_cell with every point
/// recentred on the agent (exact when the differences are doubles, which the message says).
std::string recentred_area(const std::vector<XY>& input, std::size_t k, double radius,
                           dvoronoi::Method method) {
    const std::size_t n = input.size();
    dvoronoi::Points rel(static_cast<Eigen::Index>(n - 1), 2);
    bool exact = true;
    for (std::size_t r = 0, j = 0; j < n; ++j) {
        if (j == k) continue;
        for (int d = 0; d < 2; ++d) {
            const double v = input[j][static_cast<std::size_t>(d)] - input[k][static_cast<std::size_t>(d)];
            exact = exact && dvoronoi_oracle::families::exact_sum(input[j][static_cast<std::size_t>(d)],
                                                                  -input[k][static_cast<std::size_t>(d)]);
            rel(static_cast<Eigen::Index>(r), d) = v;
        }
        ++r;
    }
    try {
        const auto cell = dvoronoi::limited_cell(dvoronoi::Vec2::Zero(), rel, radius, method);
        return "; with the points recentred on the agent (" +
               std::string(exact ? "exactly" : "rounded") + ") limited_cell gives " +
               fmt(cell.measures().area);
    } catch (const std::exception& e) {
        return std::string("; recentred limited_cell threw: ") + e.what();
    }
}

/// A cell's pieces as the oracle writes them: neighbour (original index) or kArcPiece, counter-
/// clockwise (clockwise for a mirror image, then reversed), starting at the smallest neighbour.
std::vector<long> piece_pattern(const dvoronoi::LimitedPartition& part, dvoronoi::Index k,
                                const std::vector<std::size_t>& perm, bool reversed) {
    std::vector<long> out;
    for (dvoronoi::Index q = part.piece_ptr[static_cast<std::size_t>(k)];
         q < part.piece_ptr[static_cast<std::size_t>(k) + 1]; ++q) {
        const dvoronoi::Index nb = part.piece_neighbor[static_cast<std::size_t>(q)];
        out.push_back(nb < 0 || nb >= part.size()
                          ? (nb < 0 ? dvoronoi_oracle::kArcPiece : -2)
                          : static_cast<long>(perm[static_cast<std::size_t>(nb)]));
    }
    if (reversed) std::reverse(out.begin(), out.end());
    const auto first = std::min_element(out.begin(), out.end(), [](long a, long b) {
        return (a < 0 ? std::numeric_limits<long>::max() : a) <
               (b < 0 ? std::numeric_limits<long>::max() : b);
    });
    std::rotate(out.begin(), first, out.end());
    return out;
}

/// Mismatch bookkeeping for one (case, transform, method): the first few are reported in full.
struct Report {
    std::string label;
    int failures = 0;
    void fail(const std::string& what) {
        ++failures;
        if (failures <= kMaxReports) FAIL_CHECK(label << ": " << what);
    }
    void finish() {
        CHECK_MESSAGE(failures == 0, label << ": " << failures << " mismatches in all"
                                           << (failures > kMaxReports ? " (the first shown above)" : ""));
    }
};

/// Compares a partition of `input` (point k of input is original point perm[k]) with the oracle of
/// the original points.
void compare_partition(Report& rep, const std::vector<XY>& input, double radius,
                       const std::vector<std::size_t>& perm, double area_scale,
                       const std::function<XY(const XY&)>& map_point, bool reversed,
                       dvoronoi::Method method, const OracleResult& orc,
                       const dvoronoi::LimitedPartition& part) {
    const std::size_t n = input.size();
    if (static_cast<std::size_t>(part.size()) != n ||
        part.indptr.size() != n + 1 || part.areas.size() != n) {
        rep.fail("partition has the wrong size");
        return;
    }
    for (std::size_t k = 0; k < n; ++k) {
        const auto kk = static_cast<dvoronoi::Index>(k);
        const std::size_t o = perm[k];
        const auto [b, e] = part.neighbors(kk);
        std::vector<std::size_t> got;
        bool sorted = true, bad_index = false;
        for (const dvoronoi::Index* it = b; it != e; ++it) {
            if (it != b && *it <= *(it - 1)) sorted = false;
            if (*it < 0 || *it >= part.size() || *it == kk) {
                bad_index = true;
                continue;
            }
            got.push_back(perm[static_cast<std::size_t>(*it)]);
        }
        std::sort(got.begin(), got.end());
        const auto& want = orc.limited_neighbors[o];
        const double expected_area = orc.limited_areas[o] * area_scale;
        const double got_area = part.areas[k];
        const bool sets_ok = !bad_index && got == want;
        const bool area_ok = area_close(got_area, expected_area, radius);
        const XY want_c = map_point(orc.limited_centroids[o]);
        const XY got_c{part.centroids(kk, 0), part.centroids(kk, 1)};
        const bool centroid_ok = centroid_close(got_c, want_c, radius);
        const std::vector<long> got_pieces = piece_pattern(part, kk, perm, reversed);
        const bool pieces_ok = got_pieces == orc.limited_pieces[o];
        if (!sets_ok || !sorted || !area_ok || !centroid_ok || !pieces_ok) {
            std::ostringstream s;
            s << "agent " << o << " (row " << k << " here) at (" << fmt(input[k][0]) << ", "
              << fmt(input[k][1]) << "), R = " << fmt(radius) << ":";
            if (!sets_ok)
                s << " limited neighbours (original indices) expected " << fmt_set(want) << " got "
                  << fmt_set(got) << (bad_index ? " [self or out-of-range index]" : "");
            if (!sorted) s << " CSR row not strictly ascending (duplicates?)";
            if (!area_ok)
                s << " area expected " << fmt(expected_area) << " got " << fmt(got_area)
                  << " (rel. error " << std::fabs(got_area - expected_area) / expected_area << ")"
                  << recentred_area(input, k, radius, method);
            if (!pieces_ok && sets_ok)
                s << " pieces (neighbour or -1 for an arc, ccw) expected "
                  << fmt_set(orc.limited_pieces[o]) << " got " << fmt_set(got_pieces);
            if (!centroid_ok)
                s << " centroid expected (" << fmt(want_c[0]) << ", " << fmt(want_c[1]) << ") got ("
                  << fmt(got_c[0]) << ", " << fmt(got_c[1]) << ")";
            rep.fail(s.str());
        }
        // Symmetry of the edge relation within the partition itself.
        for (const dvoronoi::Index* it = b; it != e; ++it) {
            if (*it < 0 || *it >= part.size()) continue;
            const auto [b2, e2] = part.neighbors(*it);
            if (!std::binary_search(b2, e2, kk))
                rep.fail("edge relation not symmetric: row " + std::to_string(k) + " lists row " +
                         std::to_string(*it) + " but not conversely");
        }
    }
}

/// The per-agent call for a sample of agents equals the partition's cell (same neighbour set after
/// mapping the rows of `others`, same area).
void compare_single_cells(Report& rep, const std::vector<XY>& input, double radius,
                          dvoronoi::Method method, const dvoronoi::LimitedPartition& part,
                          std::size_t stride) {
    const std::size_t n = input.size();
    if (n == 0) return;
    const dvoronoi::Points all = to_points(input);
    for (std::size_t i = 0; i < n; i += stride) {
        dvoronoi::Points others(static_cast<Eigen::Index>(n - 1), 2);
        for (std::size_t r = 0, k = 0; k < n; ++k) {
            if (k == i) continue;
            others.row(static_cast<Eigen::Index>(r++)) = all.row(static_cast<Eigen::Index>(k));
        }
        const dvoronoi::Vec2 c(input[i][0], input[i][1]);
        const dvoronoi::LimitedCell cell = dvoronoi::limited_cell(c, others, radius, method);
        std::vector<dvoronoi::Index> got;
        for (const dvoronoi::Index r : cell.neighbors()) got.push_back(r < static_cast<dvoronoi::Index>(i) ? r : r + 1);
        const auto [b, e] = part.neighbors(static_cast<dvoronoi::Index>(i));
        const std::vector<dvoronoi::Index> want(b, e);
        const double a = cell.measures().area;
        if (got != want || !area_close(a, part.areas[i], radius))
            rep.fail("limited_cell(center, others) for row " + std::to_string(i) +
                     " differs from limited_cells: neighbours " + fmt_set(got) + " vs " +
                     fmt_set(want) + ", area " + fmt(a) + " vs " + fmt(part.areas[i]));
    }
}

constexpr dvoronoi::Method kMethods[] = {dvoronoi::Method::Auto, dvoronoi::Method::Scan, dvoronoi::Method::Chords};

/// Runs every check on one input and its transformed copies.
/// Most inputs are small (one block of the partition), so they run on one thread: an OpenMP team per
/// call only adds barrier waits, which a loaded machine stretches by orders of magnitude. The large
/// inputs run with `threads` = 2 and several blocks.
void check_case(const NamedCase& c, std::uint64_t seed, std::size_t single_stride,
                bool transforms = true, bool oracle_transform_check = false, int threads = 1) {
    const OracleResult orc = dvoronoi_oracle::compute_oracle(c.points, c.radius, true);
    // The oracle's two ways to the limited neighbours must agree.
    for (std::size_t i = 0; i < c.points.size(); ++i)
        if (orc.limited_neighbors[i] != orc.limited_neighbors_by_clipping[i])
            FAIL_CHECK(c.name << ": oracle self-check failed at agent " << i << ": Delaunay "
                              << fmt_set(orc.limited_neighbors[i]) << " vs clipping "
                              << fmt_set(orc.limited_neighbors_by_clipping[i]));

    std::vector<std::size_t> id(c.points.size());
    std::iota(id.begin(), id.end(), std::size_t{0});
    const auto identity = [](const XY& p) { return p; };
    for (const dvoronoi::Method method : kMethods) {
        Report rep{c.name + " [" + dvoronoi::method_name(method) + "]"};
        try {
            const auto part =
                dvoronoi::limited_cells(to_points(c.points), c.radius, method, threads);
            compare_partition(rep, c.points, c.radius, id, 1.0, identity, false, method, orc,
                              part);
            compare_single_cells(rep, c.points, c.radius, method, part, single_stride);
        } catch (const std::exception& ex) {
            rep.fail(std::string("threw: ") + ex.what());
        }
        rep.finish();
    }
    if (!transforms) return;
    for (const Transformed& t : dvoronoi_oracle::exact_transforms(c.points, c.radius, seed)) {
        if (oracle_transform_check) {
            const OracleResult o2 = dvoronoi_oracle::compute_oracle(t.points, t.radius);
            for (std::size_t k = 0; k < t.points.size(); ++k) {
                std::vector<std::size_t> m;
                for (std::size_t j : o2.limited_neighbors[k]) m.push_back(t.perm[j]);
                std::sort(m.begin(), m.end());
                if (m != orc.limited_neighbors[t.perm[k]] ||
                    o2.on_hull[k] != orc.on_hull[t.perm[k]])
                    FAIL_CHECK(c.name << " / " << t.name << ": oracle not invariant at agent "
                                      << t.perm[k]);
            }
        }
        for (const dvoronoi::Method method : kMethods) {
            Report rep{c.name + " / " + t.name + " [" + dvoronoi::method_name(method) + "]"};
            try {
                const auto part =
                    dvoronoi::limited_cells(to_points(t.points), t.radius, method, threads);
                compare_partition(rep, t.points, t.radius, t.perm, t.area_scale, t.map,
                                  t.reverses_orientation, method, orc, part);
            } catch (const std::exception& ex) {
                rep.fail(std::string("threw: ") + ex.what());
            }
            rep.finish();
        }
    }
}

std::vector<NamedCase> corpus() {
    return dvoronoi_oracle::read_corpus(std::string(DVORONOI_TEST_DATA_DIR) +
                                        "/degenerate_corpus.txt");
}

}  // namespace

TEST_CASE("oracle: Voronoi neighbours and hull flags by clipping with a huge radius") {
    // With R far beyond every Voronoi vertex (2^110 times the extent: no circumcentre of doubles is
    // farther), the clipping side of the oracle finds every Voronoi edge: its limited neighbours are
    // the Voronoi neighbours, computed independently from the Delaunay side; and a cell keeps a side
    // of its box exactly when it is unbounded.
    int checked = 0;
    for (const NamedCase& c : corpus()) {
        if (c.points.size() > 400) continue;
        double m = 1.0;
        for (const XY& p : c.points) m = std::max({m, std::fabs(p[0]), std::fabs(p[1])});
        const double big = std::ldexp(m, 110);
        const OracleResult o = dvoronoi_oracle::compute_oracle(c.points, big, true);
        for (std::size_t i = 0; i < c.points.size(); ++i) {
            CHECK_MESSAGE(o.voronoi_neighbors[i] == o.limited_neighbors[i],
                          c.name << " agent " << i);
            CHECK_MESSAGE(o.voronoi_neighbors[i] == o.limited_neighbors_by_clipping[i],
                          c.name << " agent " << i << ": Delaunay "
                                 << fmt_set(o.voronoi_neighbors[i]) << " vs clipping "
                                 << fmt_set(o.limited_neighbors_by_clipping[i]));
            CHECK_MESSAGE(o.on_hull[i] == o.box_side_survives[i], c.name << " agent " << i);
        }
        ++checked;
    }
    CHECK(checked > 100);
}

TEST_CASE("oracle: hand-checked small inputs") {
    using dvoronoi_oracle::compute_oracle;
    const double pi = std::acos(-1.0);
    SUBCASE("empty and single") {
        CHECK(compute_oracle({}, 1.0).limited_areas.empty());
        const auto o = compute_oracle({{3.0, 4.0}}, 2.0);
        CHECK(o.on_hull[0]);
        CHECK(o.voronoi_neighbors[0].empty());
        CHECK(o.limited_areas[0] == doctest::Approx(4.0 * pi).epsilon(1e-15));
    }
    SUBCASE("pair: tangent bisector is not a limited neighbour") {
        const auto o = compute_oracle({{0.0, 0.0}, {2.0, 0.0}}, 1.0);
        CHECK(o.voronoi_neighbors[0] == std::vector<std::size_t>{1});
        CHECK(o.limited_neighbors[0].empty());
        CHECK(o.limited_areas[0] == doctest::Approx(pi).epsilon(1e-15));
        const auto o2 = compute_oracle({{0.0, 0.0}, {2.0, 0.0}}, 1.0000000000000002);
        CHECK(o2.limited_neighbors[0] == std::vector<std::size_t>{1});
    }
    SUBCASE("unit square + centre: diagonals touch at a point") {
        // Centre 4 at (0.5, 0.5); corners' cells meet the centre's in edges, and opposite corners
        // do not touch at all; adjacent corners share a ray.
        const auto o = compute_oracle({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}}, 10.0);
        CHECK(o.voronoi_neighbors[4] == std::vector<std::size_t>{0, 1, 2, 3});
        CHECK(o.voronoi_neighbors[0] == std::vector<std::size_t>{1, 3, 4});
        CHECK(!o.on_hull[4]);
        CHECK(o.on_hull[0]);
        CHECK(o.limited_areas[4] == doctest::Approx(0.5).epsilon(1e-14));
    }
    SUBCASE("four cocircular points: the diagonal is not a neighbour") {
        const auto o = compute_oracle({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 10.0);
        CHECK(o.voronoi_neighbors[0] == std::vector<std::size_t>{1, 3});
        CHECK(o.voronoi_neighbors[1] == std::vector<std::size_t>{0, 2});
    }
    SUBCASE("collinear: consecutive points, everyone on the hull") {
        const auto o = compute_oracle({{2, 0}, {0, 0}, {1, 0}, {3, 0}}, 0.75);
        CHECK(o.dimension == 1);
        CHECK(o.voronoi_neighbors[2] == std::vector<std::size_t>{0, 1});
        CHECK(o.limited_neighbors[2] == std::vector<std::size_t>{0, 1});
        CHECK(o.on_hull[2]);
        // Strip |x - 1| <= 0.5 ∩ disk of radius 0.75.
        const double r = 0.75, h = 0.5;
        const double seg = r * r * std::acos(h / r) - h * std::sqrt(r * r - h * h);
        CHECK(o.limited_areas[2] == doctest::Approx(pi * r * r - 2 * seg).epsilon(1e-13));
    }
    SUBCASE("middle of a hull edge is on the hull") {
        const auto o = compute_oracle({{0, 0}, {1, 0}, {2, 0}, {1, 1}}, 1.0);
        CHECK(o.dimension == 2);
        CHECK(o.on_hull[1]);
    }
}

TEST_CASE("limited cells vs oracle: uniform random points") {
    const double densities[] = {0.5, 2.0, 6.0, 15.0, 30.0, 60.0};
    for (std::uint64_t seed = 0; seed < 40; ++seed)
        for (const double d : densities) {
            const std::size_t n = d < 10.0 ? 120 : 250;
            check_case(dvoronoi_oracle::families::uniform(n, d, seed), seed, 11);
        }
    // Larger inputs (the grid index over many cells, several blocks of the partition on two
    // threads), fewer seeds.
    for (std::uint64_t seed = 100; seed < 103; ++seed)
        for (const double d : {3.0, 20.0})
            check_case(dvoronoi_oracle::families::uniform(9000, d, seed), seed, 251, false, false, 2);
}

TEST_CASE("limited cells vs oracle: lattices jittered by a few units in the last place") {
    const double radii[] = {0.5, 0.7071067811865476, 0.7071067811865475, 1.0, 1.5};
    for (std::uint64_t seed = 0; seed < 8; ++seed)
        for (const double jitter : {0x1p-50, 0x1p-40, 1e-12})
            for (const double r : radii)
                check_case(dvoronoi_oracle::families::jittered_lattice(9, jitter, r, seed), seed, 5,
                           seed % 4 == 0);
}

TEST_CASE("limited cells vs oracle: random integer-grid subsets") {
    const double radii[] = {0.5, 1.0, 1.118033988749895, 1.5, 2.0, 2.5};
    for (std::uint64_t seed = 0; seed < 20; ++seed)
        for (const int keep : {150, 500, 900})
            for (const double r : radii)
                check_case(dvoronoi_oracle::families::grid_subset(12, keep, r, seed), seed, 7);
}

TEST_CASE("limited cells vs oracle: degenerate corpus") {
    const auto cases = corpus();
    REQUIRE(cases.size() > 200);
    std::uint64_t seed = 0;
    for (const NamedCase& c : cases) check_case(c, ++seed, 3, true, true);
}
