// One robot's Voronoi neighbours from inter-robot distances only: VORONOI-NEIGHBORS of Elwin, Freeman
// & Lynch (RA-L 2017, Algorithms 1-3) with CLOSEST-ROBOT, MIN-RADIUS, MIN-SIGNED-RADIUS,
// IN-HALF-PLANE and NEXT-NEIGHBOR, iterative (FIND-VORONOI's tail recursion is a loop, so a robot with
// thousands of neighbours cannot overflow the stack). Every decision is an exact sign given the input
// values (distances/distance_predicates.hpp).
//
// Input: a LocalTable — the robot's m detected robots, its distances to them, and the distances among
// them (+inf where two of them do not detect each other). Output: the neighbours in Delaunay-path
// order (consecutive entries are mutual Voronoi neighbours; for an interior robot the path is a cycle,
// for a hull robot its two ends are the hull neighbours) and the Hull/Interior flag.
//
// Degenerate inputs (the paper assumes no three robots collinear and no four cocircular). With exact
// inputs we return the answer of docs/spec.md: neighbours are robots whose cells share an edge of positive
// length. Collinear robots are outside the open half-planes of Theorem 3 (S = 0). When several robots
// tie for MIN-RADIUS or MIN-SIGNED-RADIUS they are cocircular with i and j; of these only the one
// adjacent to i on their common circle shares a positive-length edge with i, and we pick it (the
// angular extreme seen from i, decided with S). The path then steps over cocircular diagonals, so two
// consecutive entries of a degenerate path lie on a common empty circle with i but need not be
// neighbours of each other. If every other detected robot is collinear with i and its closest robot j,
// the answer is j and the closest robot on the other side of i (if any), flagged Hull.
//
// Missing distances. The paper needs (Section IV-B) every Voronoi neighbour detected and robots
// opposite a shared Delaunay edge measuring each other. We need less for the second: when d_kl is
// missing, l's side of the line ij is taken from any robot whose side is known and which l measured
// (an exact sign too), so one chain of measurements suffices; a candidate l is skipped only when
// d_jl is missing or no chain reaches it. With a detection radius R the answer of robot i is exact
// when R >= 2 x the longest edge of i's Delaunay star (edges i-j and j-k of the Delaunay triangles at
// i); the tests check that, and that every answer names only detected robots.
#pragma once

#include "dvoronoi/distances/distance_predicates.hpp"
#include "dvoronoi/distances/distance_graph.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dvoronoi::dist {

/// What robot i knows: m detected robots (local indices 0 .. m-1), its distance to each (`center`) and
/// the m x m table of distances among them (`pair`, row-major, +inf = not measured; the diagonal is
/// unused). Values are squared distances when `squared`.
struct LocalTable {
    int m = 0;
    bool squared = false;
    std::vector<double> center;
    std::vector<double> pair;

    double d(int a, int b) const { return pair[static_cast<std::size_t>(a) * static_cast<std::size_t>(m) + static_cast<std::size_t>(b)]; }
    bool known(int a, int b) const { return std::isfinite(d(a, b)); }

    void resize(int count, bool sq) {
        m = count;
        squared = sq;
        center.assign(static_cast<std::size_t>(m), 0.0);
        pair.assign(static_cast<std::size_t>(m) * static_cast<std::size_t>(m), std::numeric_limits<double>::infinity());
    }
};

/// One robot's answer, in local indices.
struct NeighborPath {
    std::vector<int> order;  ///< Voronoi neighbours in Delaunay-path order
    bool hull = false;       ///< o = Hull: robot i lies on the convex hull (its cell is unbounded)
};

/// Scratch space reused across calls (one per thread).
struct NeighborWorkspace {
    std::vector<char> in_w;    // confirmed neighbours W
    std::vector<int> first, second;
};

namespace detail {

/// The predicates of Section III on local indices; the centre robot i is implicit.
class DistanceGeometry {
public:
    explicit DistanceGeometry(const LocalTable& t) : t_(t) {}

    /// CLOSEST-ROBOT(i, I): the detected robot closest to i (lowest local index on ties).
    int closest_robot() const {
        int best = -1;
        for (int c = 0; c < t_.m; ++c)
            if (best < 0 || t_.center[static_cast<std::size_t>(c)] < t_.center[static_cast<std::size_t>(best)]) best = c;
        return best;
    }

    /// Triangle (i, j, c) is proper (not collinear, lengths consistent) and d_jc is measured.
    bool proper(int j, int c) const {
        return t_.known(j, c) && triangle_sign(ci(j), ci(c), t_.d(j, c), t_.squared) > 0;
    }

    /// MIN-RADIUS(i, j, I): the robot k minimising r(d_ij, d_jk, d_ik) among proper triangles; -1 if none.
    int min_radius(int j) const {
        int best = -1;
        for (int c = 0; c < t_.m; ++c) {
            if (c == j || !proper(j, c)) continue;
            if (best < 0 || compare_radius(ci(j), ci(c), t_.d(j, c), ci(best), t_.d(j, best), t_.squared) < 0) best = c;
        }
        return best;
    }

    /// IN-HALF-PLANE(i, j, k, l): l lies strictly on the other side of the line ij than k (S_ijkl < 0).
    /// False when d_jl or d_kl is not measured.
    bool in_half_plane(int j, int k, int l) const {
        if (!t_.known(j, l) || !t_.known(k, l) || !t_.known(j, k)) return false;
        return opposite_sides(ci(j), ci(k), t_.d(j, k), ci(l), t_.d(j, l), t_.d(k, l), t_.squared) < 0;
    }

    /// sign(r̂(i, j, a) - r̂(i, j, b)) (MIN-SIGNED-RADIUS order). A degenerate triangle (noise) has
    /// the limit of r̂ as its area goes to 0: -inf when the angle at its apex is obtuse, +inf otherwise;
    /// two such limits compare equal.
    int compare_signed(int j, int a, int b) const {
        const int ka = key_class(j, a), kb = key_class(j, b);
        if (ka != kb) return ka < kb ? -1 : 1;
        if (ka != 0) return 0;
        return compare_signed_radius(ci(j), ci(a), t_.d(j, a), ci(b), t_.d(j, b), t_.squared);
    }

    /// NEXT-NEIGHBOR(i, j, k, W ∪ I): the robot of H(i, j, k) with the smallest signed circumradius
    /// on the edge ij; among exact ties (cocircular robots) the one adjacent to i on their circle.
    /// -1 (the paper's δ) when H(i, j, k) holds no detected robot.
    int next_neighbor(int j, int k) const {
        int best = -1;
        SignedKey best_key;
        bool tie = false;
        const HalfPlane h(*this, j, k, side_);
        for (int l = 0; l < t_.m; ++l) {
            if (l == j || l == k || !h.contains(l)) continue;
            const SignedKey key = signed_key(j, l);
            if (best < 0) {
                best = l;
                best_key = key;
                continue;
            }
            const int cmp = compare_keys(j, key, l, best_key, best);
            if (cmp < 0) {
                best = l;
                best_key = key;
                tie = false;
            } else if (cmp == 0 && key.cls == 0) {
                tie = true;
            }
        }
        if (!tie) return best;
        return adjacent_on_circle(j, best, [&](int l) {
            return l != j && l != k && l != best && h.contains(l) && compare_signed(j, l, best) == 0;
        });
    }

    /// Among `start` and the robots `tied(l)` on the same circle through i and j (all on one side of
    /// the line ij), the one adjacent to i on the circle: the angular extreme seen from i, away from j.
    template <class Tied>
    int adjacent_on_circle(int j, int start, Tied&& tied) const {
        int c = start;
        for (int l = 0; l < t_.m; ++l) {
            if (!tied(l) || !t_.known(c, l) || !t_.known(c, j) || !t_.known(j, l)) continue;
            // l lies beyond c when l and j are on opposite sides of the line through i and c.
            if (opposite_sides(ci(c), ci(j), t_.d(c, j), ci(l), t_.d(c, l), t_.d(j, l), t_.squared) < 0) c = l;
        }
        return c;
    }

    /// The start triangle (Theorem 1): k = MIN-RADIUS, moved to the robot adjacent to i among those
    /// cocircular with i, j, k on k's side (the empty circle is the same; only the adjacent one shares
    /// a positive-length edge with i).
    int start_k(int j) const {
        const int k = min_radius(j);
        if (k < 0) return k;
        bool tie = false;
        for (int l = 0; l < t_.m && !tie; ++l)
            tie = l != j && l != k && same_side(j, k, l) && compare_signed(j, l, k) == 0;
        if (!tie) return k;
        return adjacent_on_circle(j, k, [&](int l) {
            return l != j && l != k && same_side(j, k, l) && compare_signed(j, l, k) == 0;
        });
    }

    /// Fallback when every detected robot is collinear with i and j: the closest robot on the other
    /// side of i from j (angle j-i-c obtuse), or -1.
    int opposite_on_line(int j) const {
        int best = -1;
        for (int c = 0; c < t_.m; ++c) {
            if (c == j || !t_.known(j, c)) continue;
            if (angle_sign(t_.d(j, c), ci(j), ci(c), t_.squared) >= 0) continue;  // angle at i not obtuse
            if (best < 0 || ci(c) < ci(best)) best = c;
        }
        return best;
    }

private:
    double ci(int a) const { return t_.center[static_cast<std::size_t>(a)]; }

    /// IN-HALF-PLANE(i, j, k, .) for a fixed pivot (j, k), for every candidate at once. The part of
    /// S_ijkl that does not depend on l is computed once (filtered); per l,
    /// S = C + a (b_l + c_l) - 2 a d_kl^2 - (b_l - c_l) D_k with C = a (b_k + c_k - a), D_k = b_k - c_k;
    /// an undecided filter falls back to the exact predicate.
    /// Beyond the paper: when d_kl was not measured, l's side is taken from a robot m whose side is
    /// known and which l did measure (S_ijml > 0: same side as m) — exact too — so a missing
    /// measurement between opposite robots (Section IV-B's requirement) costs nothing as long as some
    /// chain of measurements links them. Robots that no chain reaches are left out, as in the paper.
    class HalfPlane {
    public:
        using E = ::dvoronoi::detail::ErrDouble;
        HalfPlane(const DistanceGeometry& g, int j, int k, std::vector<signed char>& side) : g_(g), side_(side) {
            const LocalTable& t = g.t_;
            const bool sq = t.squared;
            const E a = dist::detail::sq<E>(g.ci(j), sq);
            const E bk = dist::detail::sq<E>(g.ci(k), sq), ck = dist::detail::sq<E>(t.d(j, k), sq);
            const E c0 = a * (bk + ck - a), dk = bk - ck, two_a = E::from(2.0) * a;
            side.assign(static_cast<std::size_t>(t.m), kUnknown);
            bool missing = false;
            for (int l = 0; l < t.m; ++l) {
                if (l == j || l == k || !t.known(j, l)) continue;
                if (!t.known(k, l)) {
                    missing = true;
                    continue;
                }
                const E bl = dist::detail::sq<E>(g.ci(l), sq), cl = dist::detail::sq<E>(t.d(j, l), sq);
                const E e = dist::detail::sq<E>(t.d(k, l), sq);
                int sg = (c0 + a * (bl + cl) - two_a * e - (bl - cl) * dk).sign();
                if (sg == 2) sg = opposite_sides(g.ci(j), g.ci(k), t.d(j, k), g.ci(l), t.d(j, l), t.d(k, l), sq);
                side[static_cast<std::size_t>(l)] = static_cast<signed char>(sg);
            }
            // Propagate sides to robots without a measurement to k (rare: a few sweeps at most).
            for (bool changed = missing; changed;) {
                changed = false;
                for (int l = 0; l < t.m; ++l) {
                    if (side[static_cast<std::size_t>(l)] != kUnknown || l == j || l == k || !t.known(j, l)) continue;
                    for (int r = 0; r < t.m; ++r) {
                        const signed char sr = side[static_cast<std::size_t>(r)];
                        if (sr == kUnknown || sr == 0 || r == l || !t.known(l, r)) continue;
                        const int sg = opposite_sides(g.ci(j), g.ci(r), t.d(j, r), g.ci(l), t.d(j, l), t.d(r, l), sq);
                        side[static_cast<std::size_t>(l)] = static_cast<signed char>(sg * sr);
                        changed = true;
                        break;
                    }
                }
            }
        }
        /// l lies strictly on the other side of the line ij than k.
        bool contains(int l) const { return side_[static_cast<std::size_t>(l)] == -1; }

    private:
        static constexpr signed char kUnknown = 2;
        const DistanceGeometry& g_;
        std::vector<signed char>& side_;
    };

    /// The MIN-SIGNED-RADIUS key of apex l on the edge ij, computed once per candidate: its class
    /// (-1: r̂ = -inf, 0: finite, +1: +inf, see compare_signed), the sign of s_l and the filtered values
    /// of s_l and H_l, so that comparing two candidates costs three products (exact fallback when the
    /// filter cannot decide).
    struct SignedKey {
        int cls = 0, ssign = 0;
        ::dvoronoi::detail::ErrDouble s, h;
    };

    SignedKey signed_key(int j, int l) const {
        using E = ::dvoronoi::detail::ErrDouble;
        const E a = dist::detail::sq<E>(ci(j), t_.squared), b = dist::detail::sq<E>(ci(l), t_.squared);
        const E c = dist::detail::sq<E>(t_.d(j, l), t_.squared);
        SignedKey k;
        k.h = dist::detail::heron(a, b, c);
        k.s = b + c - a;
        int hs = k.h.sign();
        if (hs == 2) hs = triangle_sign(ci(j), ci(l), t_.d(j, l), t_.squared);
        k.ssign = k.s.sign();
        if (k.ssign == 2) k.ssign = angle_sign(ci(j), ci(l), t_.d(j, l), t_.squared);
        k.cls = hs > 0 ? 0 : (k.ssign < 0 ? -1 : 1);
        return k;
    }

    /// sign(r̂(i, j, a) - r̂(i, j, b)) from their keys (same order as compare_signed).
    int compare_keys(int j, const SignedKey& ka, int a, const SignedKey& kb, int b) const {
        if (ka.cls != kb.cls) return ka.cls < kb.cls ? -1 : 1;
        if (ka.cls != 0) return 0;
        if (ka.ssign != kb.ssign) return ka.ssign < kb.ssign ? -1 : 1;
        if (ka.ssign == 0) return 0;
        const int mag = (ka.s * ka.s * kb.h - kb.s * kb.s * ka.h).sign();
        if (mag == 2) return compare_signed_radius(ci(j), ci(a), t_.d(j, a), ci(b), t_.d(j, b), t_.squared);
        return ka.ssign > 0 ? mag : -mag;
    }

    bool same_side(int j, int k, int l) const {
        if (!t_.known(j, l) || !t_.known(k, l)) return false;
        return opposite_sides(ci(j), ci(k), t_.d(j, k), ci(l), t_.d(j, l), t_.d(k, l), t_.squared) > 0;
    }

    /// -1: r̂ = -inf, 0: finite, +1: +inf (see compare_signed).
    int key_class(int j, int a) const {
        if (triangle_sign(ci(j), ci(a), t_.d(j, a), t_.squared) > 0) return 0;
        return angle_sign(ci(j), ci(a), t_.d(j, a), t_.squared) < 0 ? -1 : 1;
    }

    const LocalTable& t_;
    mutable std::vector<signed char> side_;  // HalfPlane's per-candidate sides (reused across steps)
};

/// FIND-VORONOI(i, j, k, W, I) as a loop: walks the Delaunay path from j away from k, appending the
/// neighbours found to `found`; returns true for Hull (an end of the path), false for Interior (the
/// walk met a confirmed neighbour). Terminates: every step confirms one more robot.
inline bool find_voronoi(const DistanceGeometry& g, int j, int k, std::vector<char>& in_w, std::vector<int>& found) {
    while (true) {
        const int x = g.next_neighbor(j, k);
        if (x < 0) return true;
        if (in_w[static_cast<std::size_t>(x)]) return false;
        in_w[static_cast<std::size_t>(x)] = 1;
        found.push_back(x);
        k = j;
        j = x;
    }
}

}  // namespace detail

/// VORONOI-NEIGHBORS(i, I) on robot i's local table (Algorithm 3).
///
/// No detected robot: no neighbours, Hull. One: that robot, Hull.
/// \note O(|V_i| m) predicate evaluations for m detected robots. Thread-safe (one workspace per thread).
inline void voronoi_neighbors(const LocalTable& t, NeighborPath& out, NeighborWorkspace& ws) {
    out.order.clear();
    out.hull = true;
    if (t.m == 0) return;
    const detail::DistanceGeometry g(t);
    const int j = g.closest_robot();
    const int k = g.start_k(j);
    if (k < 0) {  // everything collinear with i and j (or unmeasured)
        out.order.push_back(j);
        const int o = g.opposite_on_line(j);
        if (o >= 0) out.order.push_back(o);
        return;
    }
    ws.in_w.assign(static_cast<std::size_t>(t.m), 0);
    ws.first.clear();
    ws.second.clear();
    ws.in_w[static_cast<std::size_t>(j)] = ws.in_w[static_cast<std::size_t>(k)] = 1;
    const bool hull1 = detail::find_voronoi(g, j, k, ws.in_w, ws.first);
    if (!hull1) {  // a cycle: k, j, x1, x2, ... (and back to k)
        out.hull = false;
        out.order.push_back(k);
        out.order.push_back(j);
        out.order.insert(out.order.end(), ws.first.begin(), ws.first.end());
        return;
    }
    // Hull: walk the other way from k; the path is x_p .. x_1, j, k, y_1 .. y_q.
    out.hull = detail::find_voronoi(g, k, j, ws.in_w, ws.second);
    out.order.assign(ws.first.rbegin(), ws.first.rend());
    out.order.push_back(j);
    out.order.push_back(k);
    out.order.insert(out.order.end(), ws.second.begin(), ws.second.end());
}

/// Convenience overload: returns the path.
inline NeighborPath voronoi_neighbors(const LocalTable& t) {
    NeighborPath out;
    NeighborWorkspace ws;
    voronoi_neighbors(t, out, ws);
    return out;
}

/// Robot i's local table from CSR rows (ptr, idx, val): local index q is the q-th entry of row i.
/// `slot` is scratch with one entry per robot, all -1 (restored before returning), mapping robot
/// indices to local ones. O(sum of the detected robots' degrees). Rows need not be sorted.
inline void local_table(const Index* ptr, const Index* idx, const double* val, Index i, bool squared, LocalTable& t,
                        std::vector<int>& slot) {
    const auto lo = static_cast<std::size_t>(ptr[i]), hi = static_cast<std::size_t>(ptr[i + 1]);
    t.resize(static_cast<int>(hi - lo), squared);
    for (std::size_t q = lo; q < hi; ++q) {
        slot[static_cast<std::size_t>(idx[q])] = static_cast<int>(q - lo);
        t.center[q - lo] = val[q];
    }
    for (std::size_t q = lo; q < hi; ++q) {
        const Index a = idx[q];
        double* row = t.pair.data() + (q - lo) * static_cast<std::size_t>(t.m);
        for (auto r = static_cast<std::size_t>(ptr[a]), e = static_cast<std::size_t>(ptr[a + 1]); r < e; ++r) {
            const int b = slot[static_cast<std::size_t>(idx[r])];
            if (b >= 0) row[b] = val[r];
        }
    }
    for (std::size_t q = lo; q < hi; ++q) slot[static_cast<std::size_t>(idx[q])] = -1;
}

/// Robot i's local table from the detection graph (see above).
inline void local_table(const DistanceGraph& g, Index i, LocalTable& t, std::vector<int>& slot) {
    local_table(g.indptr.data(), g.indices.data(), g.values.data(), i, g.squared, t, slot);
}

/// One robot's answer in global indices.
struct RobotNeighbors {
    std::vector<Index> order;  ///< Voronoi neighbours in Delaunay-path order
    bool hull = false;
};

/// One robot's Voronoi neighbours (global indices, Delaunay-path order) and hull flag from the graph.
/// \throws InputError for an index out of range. O(sum of the detected robots' degrees + |V_i| m).
inline RobotNeighbors voronoi_neighbors(const DistanceGraph& g, Index i) {
    g.check_index(i);
    thread_local std::vector<int> slot;  // all -1 between calls (local_table restores it)
    if (slot.size() < static_cast<std::size_t>(g.n)) slot.assign(static_cast<std::size_t>(g.n), -1);
    LocalTable t;
    local_table(g, i, t, slot);
    const NeighborPath p = voronoi_neighbors(t);
    RobotNeighbors out;
    out.hull = p.hull;
    const Index base = g.indptr[static_cast<std::size_t>(i)];
    for (int v : p.order) out.order.push_back(g.indices[static_cast<std::size_t>(base + v)]);
    return out;
}

}  // namespace dvoronoi::dist
