// The exact Voronoi neighbours of one agent from a Delaunay triangulation of the agent and the agents
// it knows (the "EVT" inner step of Adjust-Sensing-Radius: a small point set, typically 10-50 points).
//
// Algorithm: Bowyer-Watson insertion in a randomized order (fixed seed), with ghost triangles: every
// hull edge (a, b) carries a triangle (a, b, ghost) whose "circumcircle" is the open outer half-plane
// of ab plus the open segment ab. A point p conflicts with a finite triangle when it lies strictly
// inside its circumcircle (incircle > 0), with a ghost triangle when it lies strictly outside the
// hull edge or on its relative interior. The conflict region is then a star-shaped topological disk
// around p whatever the degeneracies (cocircular points stay on circles, never inside, so any
// Delaunay triangulation of them comes out); it is replaced by the fan of p to its boundary. The
// first conflict is found by a visibility walk from the last created triangle. Every decision is an
// exact predicate on the input doubles, orient2d or incircle: a floating-point filter (Shewchuk's
// error bounds, generously widened), then, when the coordinate differences are exact (lattices and
// other exact ties), Shewchuk's expansions on stack buffers (core/stack_expansion.hpp), else the general exact
// predicates of core/predicates.hpp (pred::orient, pred::incircle). Nothing is constructed.
//
// Degenerate inputs: all points on one line (dimension 1) are detected when the seed triangle is
// sought, and answered by the order along the line; 4+ cocircular points (square lattices) get some
// valid triangulation, and the zero-length Voronoi edges it implies (a Delaunay edge whose two
// triangles share their circumcircle) are not neighbours; nearly collinear points are decided by the
// exact predicates like any other.
//
// Complexity for m = 1 + others.rows() points: O(m^2) in the worst case. With the randomized order the
// expected number of triangles created is O(m) (at most 6 per insertion on average, by backward
// analysis); the visibility walks take O(sqrt m) steps each on evenly spread inputs, so about
// O(m^1.5) in total; the walks' orientation tests are about half of the time (timings: the docs'
// performance page).
//
// Thread-safety: delaunay_cell is a pure function (all scratch is local); a detail::Delaunay or
// DelaunayWorkspace object is scratch for one thread at a time.
#pragma once

#include "dvoronoi/cells/bisectors.hpp"
#include "dvoronoi/core/stack_expansion.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dvoronoi {

/// The exact Voronoi cell of an agent, combinatorially: who it shares an edge with and whether it is
/// unbounded.
struct DelaunayCell {
    /// Voronoi neighbours: cells sharing a segment of positive length with the agent's cell, in
    /// counter-clockwise order around it. A hull agent's list runs from the neighbour across its first
    /// (incoming) ray to the neighbour across its last (outgoing) ray, i.e. along its Delaunay path;
    /// an interior agent's cycle starts at its smallest index. For collinear input: the predecessor
    /// then the successor along the line in lexicographic (x, then y) order (one of them at an end).
    std::vector<Index> neighbors;
    /// The Voronoi cell is unbounded: the agent lies on the boundary of the convex hull (vertex or
    /// relative interior of a hull edge), every agent of a collinear input, a lone agent.
    bool on_hull = true;
};

namespace detail {


/// A triangle (v[0], v[1], v[2]) counter-clockwise; nb[i] is the triangle across the edge opposite
/// v[i], i.e. the edge (v[i+1], v[i+2]). The ghost vertex closes the hull: (a, b, ghost) lies across the
/// hull edge b -> a of the finite triangle, outside to the left of a -> b.
struct DTri {
    int v[3];
    int nb[3];
};

/// Bowyer-Watson Delaunay triangulation on exact predicates: a few dozen points per call for the
/// EVT step, or (build with `spatial`) the thousands of agents the all-agents exact-cell driver
/// leaves to it. Buffers are reused across build() calls (one object per thread; not safe to share
/// between threads; star() is const and may be called from several threads at once).
class Delaunay {
public:
    /// Triangulates `pts` (distinct; the caller's order is kept as vertex ids 0..n-1). Returns the
    /// dimension: -1 (no point), 0 (one point), 1 (all collinear: nothing is built, see line_order),
    /// 2 (a triangulation). Throws CoincidentError (with vertex ids) when two points coincide.
    /// `spatial`: insert in biased randomized rounds (BRIO: rounds of doubling size, each sorted
    /// along a Hilbert curve), so each walk starts near its target; for thousands of points.
    int build(const std::vector<Vec2>& pts, bool spatial = false) {
        P_ = &pts;
        n_ = static_cast<int>(pts.size());
        ghost_ = n_;
        tris_.clear();
        state_.clear();
        epoch_ = 0;
        dim_ = n_ <= 0 ? -1 : (n_ == 1 ? 0 : 1);
        if (n_ <= 1) return dim_;
        // Randomized insertion order, fixed seed (xorshift64*): the same input always gives the
        // same triangulation.
        order_.resize(static_cast<std::size_t>(n_));
        for (int i = 0; i < n_; ++i) order_[static_cast<std::size_t>(i)] = i;
        rng_ = 0x9E3779B97F4A7C15ull;
        for (int i = n_ - 1; i > 0; --i)
            std::swap(order_[static_cast<std::size_t>(i)], order_[next_rand() % static_cast<std::uint64_t>(i + 1)]);
        if (spatial) sort_rounds();
        const int i0 = order_[0], i1 = order_[1];
        if (pt(i0) == pt(i1)) throw_coincident(i0, i1);
        std::size_t k = 2;
        while (k < order_.size() && orient(i0, i1, order_[k]) == 0) ++k;
        if (k == order_.size()) return dim_ = 1;
        std::swap(order_[2], order_[k]);
        dim_ = 2;
        seed_triangle(i0, i1, order_[2]);
        for (std::size_t t = 3; t < order_.size(); ++t) insert(order_[t]);
        return dim_;
    }

    int dimension() const { return dim_; }

    /// Dimension 1: the vertex ids sorted lexicographically by (x, y), which is their order along the
    /// line. Throws CoincidentError for equal points.
    const std::vector<int>& line_order() {
        order_.resize(static_cast<std::size_t>(n_));
        for (int i = 0; i < n_; ++i) order_[static_cast<std::size_t>(i)] = i;
        std::sort(order_.begin(), order_.end(), [&](int a, int b) { return lex_less(pt(a), pt(b)); });
        for (std::size_t i = 1; i < order_.size(); ++i)
            if (pt(order_[i - 1]) == pt(order_[i])) throw_coincident(order_[i - 1], order_[i]);
        return order_;
    }

    /// Dimension 2: the Voronoi neighbours of vertex c (positive-length shared edge) in
    /// counter-clockwise order, starting after the hull gap for a hull vertex, and whether c is on the
    /// hull. `nbrs` receives vertex ids.
    bool star(int c, std::vector<int>& nbrs) const {
        nbrs.clear();
        const int t0 = vert_tri_[static_cast<std::size_t>(c)];
        int t = t0;
        int after_gap = -1;  // position in nbrs of the first neighbour after the ghost
        for (std::size_t guard = 0; guard <= tris_.size(); ++guard) {
            const DTri& T = tris_[static_cast<std::size_t>(t)];
            const int k = slot(T, c);
            const int a = T.v[(k + 1) % 3], b = T.v[(k + 2) % 3];
            const int tn = T.nb[(k + 1) % 3];  // across the edge (c, b): the next triangle counter-clockwise
            const DTri& U = tris_[static_cast<std::size_t>(tn)];
            const int d = U.v[(slot(U, c) + 2) % 3];  // U = (c, b, d)
            if (b == ghost_) {
                after_gap = static_cast<int>(nbrs.size());
            } else if (a == ghost_ || d == ghost_ || incircle(c, a, b, d) != 0) {
                // A hull edge carries a ray; otherwise the two circumcentres differ.
                nbrs.push_back(b);
            }
            t = tn;
            if (t == t0) break;
        }
        if (after_gap >= 0) {
            std::rotate(nbrs.begin(), nbrs.begin() + after_gap, nbrs.end());
            return true;
        }
        return false;
    }

private:
    /// BRIO's rounds: the last half of the shuffled order, the quarter before it, ... (the first
    /// 64 points left as they are), each sorted by Hilbert index on a 2^16 grid over the bounding box.
    void sort_rounds() {
        double x0 = pt(0).x(), x1 = x0, y0 = pt(0).y(), y1 = y0;
        for (int i = 1; i < n_; ++i) {
            x0 = std::min(x0, pt(i).x()), x1 = std::max(x1, pt(i).x());
            y0 = std::min(y0, pt(i).y()), y1 = std::max(y1, pt(i).y());
        }
        const double sx = x1 > x0 ? 65535.0 / (x1 - x0) : 0.0, sy = y1 > y0 ? 65535.0 / (y1 - y0) : 0.0;
        std::vector<std::uint32_t> key(static_cast<std::size_t>(n_));
        for (int i = 0; i < n_; ++i) {
            // Finite differences of finite inputs may overflow to inf: clamp (only the order suffers).
            const double fx = std::min(std::max((pt(i).x() - x0) * sx, 0.0), 65535.0);
            const double fy = std::min(std::max((pt(i).y() - y0) * sy, 0.0), 65535.0);
            key[static_cast<std::size_t>(i)] = hilbert(static_cast<std::uint32_t>(fx == fx ? fx : 0.0),
                                                       static_cast<std::uint32_t>(fy == fy ? fy : 0.0));
        }
        const auto by_key = [&](int a, int b) { return key[static_cast<std::size_t>(a)] < key[static_cast<std::size_t>(b)]; };
        for (std::size_t hi = order_.size(); hi > 64;) {
            const std::size_t lo = hi / 2;
            std::sort(order_.begin() + static_cast<std::ptrdiff_t>(lo), order_.begin() + static_cast<std::ptrdiff_t>(hi), by_key);
            hi = lo;
        }
    }

    /// The index of (x, y) along the Hilbert curve through the 2^16 x 2^16 grid.
    static std::uint32_t hilbert(std::uint32_t x, std::uint32_t y) {
        std::uint32_t d = 0;
        for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
            const std::uint32_t rx = (x & s) ? 1u : 0u, ry = (y & s) ? 1u : 0u;
            d += s * s * ((3u * rx) ^ ry);
            if (ry == 0) {  // rotate the quadrant
                if (rx == 1) {
                    x = 65535u - x;
                    y = 65535u - y;
                }
                std::swap(x, y);
            }
        }
        return d;
    }

    // ---- predicates on vertex ids (never the ghost): floating-point filter, exact fallback ----

    const Vec2& pt(int i) const { return (*P_)[static_cast<std::size_t>(i)]; }

    /// orient2d(a, b, c): +1 when c lies strictly left of a -> b.
    int orient(int ia, int ib, int ic) const {
        const Vec2 &a = pt(ia), &b = pt(ib), &c = pt(ic);
        const double l = (a.x() - c.x()) * (b.y() - c.y()), r = (a.y() - c.y()) * (b.x() - c.x());
        const int s = fast_sign(l - r, std::fabs(l) + std::fabs(r), 16);
        if (s != 2) return s;
        double d[4];
        if (!exact_diffs(a, c, d) || !exact_diffs(b, c, d + 2) || !xp::exact_range<480>(d, 4)) return pred::orient(c, a, b);
        return xp::orient_exact(d[0], d[1], d[2], d[3]);
    }

    /// incircle(a, b, c, d): +1 when d lies strictly inside the circle of the counter-clockwise a, b, c.
    int incircle(int ia, int ib, int ic, int id) const {
        const Vec2 &a = pt(ia), &b = pt(ib), &c = pt(ic), &d = pt(id);
        const double adx = a.x() - d.x(), ady = a.y() - d.y();
        const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
        const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
        const double bc1 = bdx * cdy, bc2 = cdx * bdy, ca1 = cdx * ady, ca2 = adx * cdy;
        const double ab1 = adx * bdy, ab2 = bdx * ady;
        const double al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy, cl = cdx * cdx + cdy * cdy;
        const double det = al * (bc1 - bc2) + bl * (ca1 - ca2) + cl * (ab1 - ab2);
        const double perm = al * (std::fabs(bc1) + std::fabs(bc2)) + bl * (std::fabs(ca1) + std::fabs(ca2)) +
                            cl * (std::fabs(ab1) + std::fabs(ab2));
        const int s = fast_sign(det, perm, 64);
        if (s != 2) return s;
        double e[6];
        if (!exact_diffs(a, d, e) || !exact_diffs(b, d, e + 2) || !exact_diffs(c, d, e + 4) ||
            !xp::exact_range<200>(e, 6))
            return pred::incircle(a, b, c, d);  // checked for over- and underflow
        return xp::incircle_exact(e[0], e[1], e[2], e[3], e[4], e[5]);
    }

    /// out = p - q when both differences are exact (ties on lattices and other exactly representable
    /// configurations: the stack-based exact stage below then decides without the general expansions).
    static bool exact_diffs(const Vec2& p, const Vec2& q, double* out) {
        double t0, t1;
        two_sum(p.x(), -q.x(), out[0], t0);
        two_sum(p.y(), -q.y(), out[1], t1);
        return t0 == 0.0 && t1 == 0.0;
    }

    static bool lex_less(const Vec2& a, const Vec2& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    }

    // ---- the triangulation ----

    std::uint64_t next_rand() {
        rng_ ^= rng_ >> 12;
        rng_ ^= rng_ << 25;
        rng_ ^= rng_ >> 27;
        return (rng_ * 0x2545F4914F6CDD1Dull) >> 11;
    }

    const DTri& tri(int t) const { return tris_[static_cast<std::size_t>(t)]; }
    static int slot(const DTri& T, int v) { return T.v[0] == v ? 0 : (T.v[1] == v ? 1 : 2); }
    bool is_ghost(const DTri& T) const { return T.v[0] == ghost_ || T.v[1] == ghost_ || T.v[2] == ghost_; }

    [[noreturn]] static void throw_coincident(int a, int b) {
        const int lo = std::min(a, b), hi = std::max(a, b);
        throw CoincidentError(
            "points " + std::to_string(lo) + " and " + std::to_string(hi) + " of the triangulation coincide", lo, hi);
    }

    int new_tri(int a, int b, int c) {
        tris_.push_back({{a, b, c}, {-1, -1, -1}});
        state_.push_back(0);
        return static_cast<int>(tris_.size()) - 1;
    }

    /// The first triangle (non-degenerate) and its three ghosts, linked edge by edge.
    void seed_triangle(int a, int b, int c) {
        if (orient(a, b, c) < 0) std::swap(b, c);
        vert_tri_.assign(static_cast<std::size_t>(n_) + 1, -1);
        start_at_.assign(static_cast<std::size_t>(n_) + 1, -1);
        end_at_.assign(static_cast<std::size_t>(n_) + 1, -1);
        new_tri(a, b, c);
        new_tri(c, b, ghost_);  // across b -> c
        new_tri(a, c, ghost_);  // across c -> a
        new_tri(b, a, ghost_);  // across a -> b
        for (std::size_t t = 0; t < 4; ++t)
            for (int i = 0; i < 3; ++i) {
                const int u = tris_[t].v[(i + 1) % 3], w = tris_[t].v[(i + 2) % 3];
                for (std::size_t s = 0; s < 4; ++s)
                    for (int j = 0; j < 3; ++j)
                        if (tris_[s].v[(j + 1) % 3] == w && tris_[s].v[(j + 2) % 3] == u)
                            tris_[t].nb[i] = static_cast<int>(s);
            }
        vert_tri_[static_cast<std::size_t>(a)] = vert_tri_[static_cast<std::size_t>(b)] =
            vert_tri_[static_cast<std::size_t>(c)] = 0;
        last_ = 0;
    }

    /// Does p conflict with triangle t (strictly inside its circumcircle; for a ghost: strictly
    /// outside its hull edge or inside the open edge)?
    bool conflict(int t, int p) const {
        const DTri& T = tris_[static_cast<std::size_t>(t)];
        if (!is_ghost(T)) return incircle(T.v[0], T.v[1], T.v[2], p) > 0;
        const int k = slot(T, ghost_);
        const int a = T.v[(k + 1) % 3], b = T.v[(k + 2) % 3];
        const int o = orient(a, b, p);
        if (o != 0) return o > 0;
        const Vec2 &pa = pt(a), &pb = pt(b), &pp = pt(p);
        return lex_less(pa, pb) ? (lex_less(pa, pp) && lex_less(pp, pb))
                                : (lex_less(pb, pp) && lex_less(pp, pa));
    }

    /// A triangle in conflict with p: visibility walk from the last created triangle to the
    /// triangle whose closure holds p (p strictly inside its circumcircle unless p is one of its
    /// vertices: then p is a duplicate), or to a ghost across a hull edge that sees p strictly.
    int locate(int p) {
        int t = last_;
        if (is_ghost(tri(t))) t = tri(t).nb[slot(tri(t), ghost_)];
        int prev = -1;
        // The walk terminates on Delaunay triangulations; the cap and the scan below are a safety net.
        const std::size_t cap = 4 * tris_.size() + 16;
        for (std::size_t step = 0; step < cap; ++step) {
            const DTri& T = tri(t);
            const int r = static_cast<int>(next_rand() % 3u);  // stochastic walk: vary the first edge tried
            int next = -1;
            for (int e = 0; e < 3 && next < 0; ++e) {
                const int i = (r + e) % 3;
                if (T.nb[i] == prev) continue;  // p is strictly inside that edge: we came from there
                if (orient(T.v[(i + 1) % 3], T.v[(i + 2) % 3], p) < 0) next = T.nb[i];
            }
            if (next < 0) {
                for (int i = 0; i < 3; ++i)
                    if (pt(T.v[i]) == pt(p)) throw_coincident(T.v[i], p);
                return t;
            }
            prev = t;
            t = next;
            if (is_ghost(tri(t))) return t;
        }
        for (std::size_t s = 0; s < tris_.size(); ++s)  // fallback (not expected to run)
            if (conflict(static_cast<int>(s), p)) return static_cast<int>(s);
        for (int v = 0; v < n_; ++v)
            if (v != p && pt(v) == pt(p)) throw_coincident(v, p);
        throw Error("delaunay: no conflict triangle found (internal error)");
    }

    struct BoundaryEdge {
        int u, w;   // the edge u -> w as the cavity triangle sees it (the cavity to its left)
        int outer;  // the triangle across it, outside the cavity
        int j;      // the slot of that edge in `outer`
    };

    /// Bowyer-Watson step: the conflict region of p, replaced by the fan of p to its boundary.
    void insert(int p) {
        const int t0 = locate(p);
        ++epoch_;
        const int in = 2 * epoch_, out = 2 * epoch_ + 1;  // state_ stamps for this insertion
        cavity_.clear();
        boundary_.clear();
        stack_.clear();
        stack_.push_back(t0);
        state_[static_cast<std::size_t>(t0)] = in;
        while (!stack_.empty()) {
            const int t = stack_.back();
            stack_.pop_back();
            cavity_.push_back(t);
            for (int i = 0; i < 3; ++i) {
                const int nb = tris_[static_cast<std::size_t>(t)].nb[i];
                int& st = state_[static_cast<std::size_t>(nb)];
                if (st == in) continue;
                if (st != out) {
                    if (conflict(nb, p)) {
                        st = in;
                        stack_.push_back(nb);
                        continue;
                    }
                    st = out;
                }
                const DTri& N = tris_[static_cast<std::size_t>(nb)];
                const int j = N.nb[0] == t ? 0 : (N.nb[1] == t ? 1 : 2);
                const DTri& T = tris_[static_cast<std::size_t>(t)];
                boundary_.push_back({T.v[(i + 1) % 3], T.v[(i + 2) % 3], nb, j});
            }
        }
        // The fan: one triangle (p, u, w) per boundary edge, in the cavity's slots first. There are
        // two more boundary edges than cavity triangles.
        std::size_t reuse = 0;
        for (BoundaryEdge& e : boundary_) {
            int t;
            if (reuse < cavity_.size()) {
                t = cavity_[reuse++];
                tris_[static_cast<std::size_t>(t)] = {{p, e.u, e.w}, {e.outer, -1, -1}};
            } else {
                t = new_tri(p, e.u, e.w);
                tris_[static_cast<std::size_t>(t)].nb[0] = e.outer;
            }
            tris_[static_cast<std::size_t>(e.outer)].nb[e.j] = t;
            start_at_[static_cast<std::size_t>(e.u)] = t;
            end_at_[static_cast<std::size_t>(e.w)] = t;
            vert_tri_[static_cast<std::size_t>(e.u)] = t;
            vert_tri_[static_cast<std::size_t>(e.w)] = t;
            e.outer = t;  // now: the new triangle
        }
        for (const BoundaryEdge& e : boundary_) {
            DTri& T = tris_[static_cast<std::size_t>(e.outer)];
            T.nb[1] = start_at_[static_cast<std::size_t>(e.w)];  // across w -> p
            T.nb[2] = end_at_[static_cast<std::size_t>(e.u)];    // across p -> u
            if (e.u != ghost_ && e.w != ghost_) last_ = e.outer;
        }
        vert_tri_[static_cast<std::size_t>(p)] = boundary_.front().outer;
    }

    const std::vector<Vec2>* P_ = nullptr;
    int n_ = 0, ghost_ = 0, dim_ = -1, epoch_ = 0, last_ = 0;
    std::uint64_t rng_ = 0;
    std::vector<DTri> tris_;
    std::vector<int> state_;  // per triangle: 2 * epoch (in this insertion's cavity), 2 * epoch + 1 (not)
    std::vector<int> order_, vert_tri_, start_at_, end_at_, cavity_, stack_;
    std::vector<BoundaryEdge> boundary_;
};

/// Scratch reused across the agents a thread processes.
struct DelaunayWorkspace {
    Delaunay dt;
    std::vector<Vec2> pts;
    std::vector<int> nbrs;
};

/// The Voronoi neighbours (candidate ids) and hull flag of c among the candidates (all of them are
/// used; none may coincide with c or with each other: CoincidentError, naming candidate ids, or -1
/// for c).
inline void delaunay_star(const Vec2& c, const std::vector<Candidate>& cand, DelaunayCell& out,
                          DelaunayWorkspace& ws) {
    out.neighbors.clear();
    out.on_hull = true;
    auto& P = ws.pts;
    P.clear();
    P.push_back(c);
    for (const Candidate& q : cand) P.push_back(q.p);
    const auto id = [&](int v) { return v == 0 ? Index{-1} : cand[static_cast<std::size_t>(v - 1)].id; };
    try {
        const int dim = ws.dt.build(P);
        if (dim == 1) {
            const std::vector<int>& line = ws.dt.line_order();
            const auto at = static_cast<std::size_t>(std::find(line.begin(), line.end(), 0) - line.begin());
            if (at > 0) out.neighbors.push_back(id(line[at - 1]));
            if (at + 1 < line.size()) out.neighbors.push_back(id(line[at + 1]));
        } else if (dim == 2) {
            out.on_hull = ws.dt.star(0, ws.nbrs);
            for (int v : ws.nbrs) out.neighbors.push_back(id(v));
            if (!out.on_hull && !out.neighbors.empty())
                std::rotate(out.neighbors.begin(), std::min_element(out.neighbors.begin(), out.neighbors.end()),
                            out.neighbors.end());
        }
    } catch (const CoincidentError& e) {
        const Index a = id(static_cast<int>(e.first())), b = id(static_cast<int>(e.second()));
        const Index lo = std::min(a, b), hi = std::max(a, b);
        if (lo < 0)
            throw CoincidentError(
                "others[" + std::to_string(hi) + "] coincides with center; its Voronoi cell is undefined", hi, hi);
        throw CoincidentError("others[" + std::to_string(lo) + "] and others[" + std::to_string(hi) +
                                  "] coincide; their Voronoi cells are undefined",
                              lo, hi);
    }
}

}  // namespace detail

/// The exact Voronoi neighbours of the agent at `center` among the agents `others` (all of them are
/// taken into account), as row indices of `others`, and whether its Voronoi cell is unbounded. See
/// DelaunayCell for the order. Every decision is an exact predicate (orient2d, incircle).
///
/// \throws InputError if a coordinate is NaN or inf.
/// \throws CoincidentError if an agent of `others` lies at `center` or two agents of `others`
///         coincide (the pair found first by the triangulation, not necessarily the smallest).
/// \note Thread-safe (pure function; its scratch is local). Complexity for m = others.rows(): O(m^2)
///       worst case, about O(m^1.5) expected (randomized insertion, fixed seed; walking point
///       location). For many calls on one thread, detail::delaunay_star reuses its buffers.
inline DelaunayCell delaunay_cell(const Vec2& center, PointsRef others) {
    detail::require_finite_point(center, "center");
    detail::require_finite_points(others, "others");
    std::vector<detail::Candidate> cand;
    cand.reserve(static_cast<std::size_t>(others.rows()));
    for (Eigen::Index j = 0; j < others.rows(); ++j)
        cand.push_back({others.row(j).transpose(), static_cast<Index>(j)});
    DelaunayCell out;
    detail::DelaunayWorkspace ws;
    detail::delaunay_star(center, cand, out, ws);
    return out;
}

}  // namespace dvoronoi
