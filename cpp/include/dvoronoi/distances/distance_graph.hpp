// The detection graph of the distance-only algorithm (Elwin, Freeman & Lynch, Section II-A): n robots,
// and a symmetric measured distance e_ij for every pair that detects each other, stored as CSR
// (rows ascending). Built from a list of measurements, validated once with messages that name the
// offending entry.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace dvoronoi::dist {

/// How a pair measured in both directions (i, j) and (j, i) becomes one edge weight.
enum class Symmetry {
    Require,  ///< both values must be equal (a symmetric matrix); a pair given once is taken as is
    Average,  ///< e_ij = (sigma_ij + sigma_ji) / 2, the paper's definition; a pair given once is kept
};

/// Symmetric detection graph in CSR form: robot i detects indices[indptr[i] .. indptr[i+1]) (ascending)
/// at distances values[...] (or squared distances when `squared`).
struct DistanceGraph {
    Index n = 0;
    bool squared = false;  ///< values are squared distances
    std::vector<Index> indptr{0};
    std::vector<Index> indices;
    std::vector<double> values;

    Index size() const noexcept { return n; }
    Index degree(Index i) const { return indptr[static_cast<std::size_t>(i) + 1] - indptr[static_cast<std::size_t>(i)]; }

    /// The measured value between i and j, or +inf when they do not detect each other. O(log degree).
    double value(Index i, Index j) const {
        const auto lo = indices.begin() + indptr[static_cast<std::size_t>(i)];
        const auto hi = indices.begin() + indptr[static_cast<std::size_t>(i) + 1];
        const auto it = std::lower_bound(lo, hi, j);
        if (it == hi || *it != j) return std::numeric_limits<double>::infinity();
        return values[static_cast<std::size_t>(it - indices.begin())];
    }

    /// The distance (not squared) between i and j, or +inf.
    double distance(Index i, Index j) const {
        const double v = value(i, j);
        return squared ? std::sqrt(v) : v;
    }

    void check_index(Index i) const {
        if (i < 0 || i >= n)
            throw InputError("robot index " + std::to_string(i) + " out of range [0, " + std::to_string(n) + ")");
    }
};

/// Builds the graph from measurements (rows[k], cols[k], vals[k]), k = 0 .. m-1.
///
/// A pair may be given in one direction or in both; `symmetry` says how two values combine. Entries
/// with an infinite value mean "not detected" and are skipped (a pair detected in one direction only
/// is then taken as given by the other direction's value).
/// \param where names entry k in messages (e.g. "distances[3, 7]" or "file.txt:12:5"); default "entry k".
/// \param ids names robot i as ids[i] in messages (the caller's robot IDs); empty: by its index.
/// \throws InputError naming the entry for: n < 0, an index outside [0, n), i == j, a value that is
///         NaN, zero or negative, the same directed pair twice, or (Require) two different values of
///         one pair.
/// \note O(m log m). Thread-safe.
inline DistanceGraph make_distance_graph(Index n, const std::vector<Index>& rows, const std::vector<Index>& cols,
                                         const std::vector<double>& vals, bool squared = false,
                                         Symmetry symmetry = Symmetry::Require,
                                         const std::function<std::string(std::size_t)>& where = nullptr,
                                         const std::vector<Index>& ids = {}) {
    const auto name = [&](std::size_t k) {
        return where ? where(k) : "entry " + std::to_string(k);
    };
    const auto robot = [&](Index i) {
        return std::to_string(ids.empty() || i < 0 || i >= static_cast<Index>(ids.size()) ? i : ids[static_cast<std::size_t>(i)]);
    };
    if (n < 0) throw InputError("n must be >= 0, got " + std::to_string(n));
    if (rows.size() != cols.size() || rows.size() != vals.size())
        throw InputError("rows, cols and values must have the same length");
    const char* what = squared ? "squared distance" : "distance";
    struct Entry {
        Index lo, hi;
        double v;
        std::size_t k;
        bool forward;  // given as (lo, hi)
    };
    std::vector<Entry> e;
    e.reserve(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const Index i = rows[k], j = cols[k];
        const double v = vals[k];
        if (i < 0 || i >= n || j < 0 || j >= n)
            throw InputError(name(k) + ": robot index " + std::to_string(i < 0 || i >= n ? i : j) +
                             " out of range [0, " + std::to_string(n) + ")");
        if (std::isinf(v) && v > 0) continue;  // not detected
        if (i == j) throw InputError(name(k) + ": a robot's distance to itself (" + robot(i) + ", " + robot(j) + ") is not a measurement");
        if (!(v > 0.0) || !std::isfinite(v)) {
            char got[32];
            std::snprintf(got, sizeof got, "%.17g", v);
            throw InputError(name(k) + ": " + what + " between robots " + robot(i) + " and " +
                             robot(j) + " must be positive and finite (or inf = not detected), got " + got +
                             (v == 0.0 ? " (coinciding robots have no Voronoi cells)" : ""));
        }
        e.push_back({std::min(i, j), std::max(i, j), v, k, i < j});
    }
    std::sort(e.begin(), e.end(), [](const Entry& x, const Entry& y) {
        return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.k < y.k);
    });
    // Merge the (at most two) entries of each pair.
    std::vector<Index> pi, pj;
    std::vector<double> pv;
    for (std::size_t a = 0; a < e.size();) {
        std::size_t b = a + 1;
        while (b < e.size() && e[b].lo == e[a].lo && e[b].hi == e[a].hi) ++b;
        double v = e[a].v;
        if (b - a > 2 || (b - a == 2 && e[a].forward == e[a + 1].forward)) {
            const Entry& dup = b - a > 2 ? e[a + 2] : e[a + 1];
            throw InputError(name(dup.k) + ": the pair (" + robot(e[a].lo) + ", " + robot(e[a].hi) +
                             ") is given twice in the same direction (first at " + name(e[a].k) + ")");
        }
        if (b - a == 2) {
            const double w = e[a + 1].v;
            if (symmetry == Symmetry::Require && w != v) {
                char msg[96];
                std::snprintf(msg, sizeof msg, "%.17g vs %.17g", v, w);
                throw InputError(name(e[a + 1].k) + ": the two directions of the pair (" + robot(e[a].lo) +
                                 ", " + robot(e[a].hi) + ") differ (" + msg + ", other at " + name(e[a].k) +
                                 "); pass symmetric measurements or average them (symmetrize)");
            }
            v = 0.5 * v + 0.5 * w;
        }
        pi.push_back(e[a].lo);
        pj.push_back(e[a].hi);
        pv.push_back(v);
        a = b;
    }
    DistanceGraph g;
    g.n = n;
    g.squared = squared;
    g.indptr.assign(static_cast<std::size_t>(n) + 1, 0);
    for (std::size_t p = 0; p < pi.size(); ++p) {
        ++g.indptr[static_cast<std::size_t>(pi[p]) + 1];
        ++g.indptr[static_cast<std::size_t>(pj[p]) + 1];
    }
    std::partial_sum(g.indptr.begin(), g.indptr.end(), g.indptr.begin());
    g.indices.resize(2 * pi.size());
    g.values.resize(2 * pi.size());
    std::vector<Index> fill(g.indptr.begin(), g.indptr.end() - 1);
    // Pairs are sorted by (lo, hi), so each row receives its columns < r in order, then its columns > r
    // in order: rows come out ascending. The check below keeps that an invariant, not an assumption.
    for (std::size_t p = 0; p < pi.size(); ++p) {
        auto& fi = fill[static_cast<std::size_t>(pi[p])];
        g.indices[static_cast<std::size_t>(fi)] = pj[p];
        g.values[static_cast<std::size_t>(fi++)] = pv[p];
        auto& fj = fill[static_cast<std::size_t>(pj[p])];
        g.indices[static_cast<std::size_t>(fj)] = pi[p];
        g.values[static_cast<std::size_t>(fj++)] = pv[p];
    }
    std::vector<std::pair<Index, double>> row;
    for (Index r = 0; r < n; ++r) {
        const auto lo = static_cast<std::size_t>(g.indptr[static_cast<std::size_t>(r)]);
        const auto hi = static_cast<std::size_t>(g.indptr[static_cast<std::size_t>(r) + 1]);
        if (std::is_sorted(g.indices.begin() + static_cast<std::ptrdiff_t>(lo), g.indices.begin() + static_cast<std::ptrdiff_t>(hi))) continue;
        row.clear();
        for (std::size_t q = lo; q < hi; ++q) row.emplace_back(g.indices[q], g.values[q]);
        std::sort(row.begin(), row.end());
        for (std::size_t q = lo; q < hi; ++q) {
            g.indices[q] = row[q - lo].first;
            g.values[q] = row[q - lo].second;
        }
    }
    return g;
}

/// The detection graph of known positions: every pair closer than `radius` (strictly), with exact
/// distances rounded to double (`squared = false`) or squared distances (`squared = true`, exact when
/// the coordinates are small integers or dyadic). For tests and simulations. O(n^2).
inline DistanceGraph distances_from_points(const Points& pts, double radius, bool squared = false) {
    ::dvoronoi::detail::require_finite_points(pts, "points");
    const Index n = pts.rows();
    std::vector<Index> r, c;
    std::vector<double> v;
    for (Index i = 0; i < n; ++i)
        for (Index j = i + 1; j < n; ++j) {
            const double dx = pts(i, 0) - pts(j, 0), dy = pts(i, 1) - pts(j, 1);
            const double d2 = dx * dx + dy * dy;
            if (!(d2 < radius * radius)) continue;
            r.push_back(i);
            c.push_back(j);
            v.push_back(squared ? d2 : std::sqrt(d2));
        }
    return make_distance_graph(n, r, c, v, squared);
}

}  // namespace dvoronoi::dist
