// A floating-point filter in front of Boundary Scan for the all-agents drivers: the limited cell by
// incremental clipping of the disk with the bisector half-planes, nearest agents first, where every
// decision (is a vertex strictly inside a half-plane, which arc a new chord cuts) is certified by a
// forward error bound; when any decision is uncertain — ties, concurrent bisectors, a vertex on the
// circle, tangent chords, over- or underflow — it gives up and Boundary Scan runs instead.
//
// Why: Boundary Scan sorts all m bisectors of the agents within 2R (about 30 in a uniform swarm) to
// find the ~6 that bound the cell. Clipping the nearest few first shrinks the cell so fast that every
// other agent is discarded by one comparison (|a_k| / 2 beyond the cell's farthest point), which
// halves the time per cell. The result is exactly Boundary Scan's: the surviving bisectors, in
// counter-clockwise order from the nearest neighbour's, with the same vertex/arc labels, go through
// the same emit_cell, so pieces, coordinates and measures are bit-identical (tested).
//
// Contract: candidates strictly within 2R of c, pairwise distinct and distinct from c (the
// all-agents drivers check this for all agents at once; the one-agent call keeps plain Boundary
// Scan, whose errors name coinciding agents).
#pragma once

#include "dvoronoi/cells/boundary_scan.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dvoronoi::detail {

namespace clip {

inline constexpr int kArcSide = -1;
inline constexpr double kU = 1.1102230246251565e-16;  // unit roundoff
inline constexpr double kInf = std::numeric_limits<double>::infinity();
/// About how many nearest candidates are clipped before the farther ones are screened by distance.
inline constexpr std::size_t kNearFirst = 8;

/// A vertex relative to c with a bound on its distance to the exact vertex (of the exact p - c);
/// line_vertex and chord_vertex (core/accurate.hpp) construct them.
using Vertex = BoundedPoint;

/// A vertex of the cell being clipped: position, error bound, the side that starts there
/// (candidate index or kArcSide), and `slack` = 2 e + 24 u |v|_1, so that the certified test
/// against a half-plane costs six flops (see side_of).
struct CellVertex {
    double x, y, e, slack;
    int side;
};

inline CellVertex cell_vertex(const Vertex& v, int side) {
    return {v.x, v.y, v.e, 2.0 * v.e + 24.0 * kU * l1(v.x, v.y), side};
}

/// Sign of n2_k - 2 a_k . v (> 0: v strictly inside the half-plane H_k of c), or 2 when the bound
/// cannot decide. The bound: |a_k| e for the vertex's error, 8 u (n2_k + 3 |a_k|_1 |v|_1) for
/// the roundings of a_k, n2_k and the dot product; `na` = |a_k|_1, `nb` = 8 u n2_k.
inline int side_of(const CellVertex& v, double akx, double aky, double n2k, double na, double nb) {
    const double f = n2k - 2.0 * (akx * v.x + aky * v.y);
    const double b = na * v.slack + nb;  // infinite when v.e is: then neither test passes
    if (f > b) return 1;
    if (f < -b) return -1;
    return 2;
}

/// Sign of cross(u, w) = u.x w.y - u.y w.x for two bounded points, or 2.
inline int cross_sign(const Vertex& u, const Vertex& w) {
    if (!(u.e < kInf && w.e < kInf)) return 2;
    const double l = u.x * w.y, r = u.y * w.x;
    const double f = l - r;
    const double b = l1(w.x, w.y) * u.e + l1(u.x, u.y) * w.e + u.e * w.e + 4.0 * kU * (std::fabs(l) + std::fabs(r));
    if (f > b) return 1;
    if (f < -b) return -1;
    return 2;
}

}  // namespace clip

/// The clipping filter's input, loaded agent by agent straight from a spatial query (no candidate
/// list is built unless the filter gives up), and its scratch buffers (reused across agents: no
/// allocation per cell).
struct ClipWorkspace {
    // Loaded: candidate k at (px, py) with id; a = p - c (rounded) and |a|^2 (rounded).
    std::vector<double> px, py, ax, ay, n2;
    std::vector<Index> id;
    std::vector<int> order, far;  // the near candidates, the far ones
    Vec2 c = Vec2::Zero();
    double near2 = 0.0, lo = 0.0, lo2 = 0.0, hi = 0.0;
    /// After a successful clip: the cell has no arc and every vertex is certainly strictly inside
    /// the disk, so it is the agent's whole (unlimited) Voronoi cell (what ASR certifies).
    bool inside_disk = false;
    int nn = 0;
    std::size_t m = 0, near = 0, nfar = 0;

    std::vector<clip::CellVertex> cur, next;  // the cell being clipped, and the next one
    std::vector<char> flags;                  // vertex strictly outside the half-plane being cut
    std::vector<Line> lines;                  // the result, for emit_cell
    std::vector<int> cycle;
    std::vector<char> meets;

    /// Starts loading the candidates of the agent at c. `near2`: squared distance below which a
    /// candidate is clipped early (about the kNearFirst nearest; only the speed depends on it).
    void start(const Vec2& center, double near_sq) {
        c = center;
        near2 = near_sq;
        lo = lo2 = clip::kInf;
        hi = 0.0;
        nn = 0;
        m = near = nfar = 0;
    }
    /// Adds a candidate (strictly within 2R of c, distinct from c and the others).
    void add(const Vec2& p, Index j) {
        if (m == cap_) grow();
        put(m, p.x(), p.y(), j);
        ++m;
    }
    /// Adds a batch of candidates as a spatial query hands them over (core/grid_index.hpp:
    /// for_each_batch_within_at): candidate t < count at (xs[sel[t]], ys[sel[t]]) with index
    /// ids[sel[t]]. The count stays in a register through the batch (see summarize()).
    void add_batch(const double* xs, const double* ys, const Index* ids, const std::uint32_t* sel, std::size_t count) {
        while (m + count > cap_) grow();
        std::size_t k = m;
        for (std::size_t t = 0; t < count; ++t, ++k) put(k, xs[sel[t]], ys[sel[t]], ids[sel[t]]);
        m = k;
    }
    /// After the last add: the nearest candidate (nn, lo), the second distance (lo2), the farthest
    /// (hi), and the near/far lists. Why a pass of its own, on locals: kept up to date in add(),
    /// these running values went through memory at every candidate (a store through px may alias
    /// them), a chain of store-to-load latencies.
    void summarize() {
        double l = clip::kInf, l2 = clip::kInf, h = 0.0;
        int best = 0;
        std::size_t nr = 0, nf = 0;
        const double cut = near2;
        for (std::size_t k = 0; k < m; ++k) {
            const double d = n2p_[k];
            l2 = std::min(l2, std::max(l, d));
            best = d < l ? static_cast<int>(k) : best;
            l = std::min(l, d);
            h = std::max(h, d);
            const bool is_near = d <= cut;
            orderp_[nr] = static_cast<int>(k);
            farp_[nf] = static_cast<int>(k);
            nr += is_near;
            nf += !is_near;
        }
        lo = l;
        lo2 = l2;
        hi = h;
        nn = best;
        near = nr;
        nfar = nf;
    }
    /// Appends, after the m candidates (not counted in m), four phantom agents at c + (+-2R, 0),
    /// (0, +-2R): their bisectors bound the square of half-side R around c, the start of an
    /// unlimited cell's clipping (Clipper::start_square). Their id is -1.
    void add_square(double radius) {
        while (m + 4 > cap_) grow();
        const double r2 = 2.0 * radius, n = r2 * r2;
        const double dx[4] = {r2, 0.0, -r2, 0.0}, dy[4] = {0.0, r2, 0.0, -r2};
        for (std::size_t t = 0; t < 4; ++t) {
            px[m + t] = c.x() + dx[t];
            py[m + t] = c.y() + dy[t];
            ax[m + t] = dx[t];
            ay[m + t] = dy[t];
            n2[m + t] = n;
            id[m + t] = -1;
        }
    }
    /// The loaded candidates as a list (for Boundary Scan when the filter gives up).
    void candidates(std::vector<Candidate>& out) const {
        out.resize(m);
        for (std::size_t k = 0; k < m; ++k) out[k] = {Vec2(px[k], py[k]), id[k]};
    }

private:
    void put(std::size_t k, double x, double y, Index j) {
        const double dx = x - c.x(), dy = y - c.y();
        pxp_[k] = x;
        pyp_[k] = y;
        axp_[k] = dx;
        ayp_[k] = dy;
        n2p_[k] = dx * dx + dy * dy;
        idp_[k] = j;
    }
    void grow() {
        cap_ = std::max<std::size_t>(64, 2 * px.size());
        for (auto* v : {&px, &py, &ax, &ay, &n2}) v->resize(cap_);
        id.resize(cap_);
        order.resize(cap_);
        far.resize(cap_);
        pxp_ = px.data(), pyp_ = py.data(), axp_ = ax.data(), ayp_ = ay.data(), n2p_ = n2.data();
        idp_ = id.data(), orderp_ = order.data(), farp_ = far.data();
    }
    // The vectors' storage, for put() and summarize().
    std::size_t cap_ = 0;
    double *pxp_ = nullptr, *pyp_ = nullptr, *axp_ = nullptr, *ayp_ = nullptr, *n2p_ = nullptr;
    Index* idp_ = nullptr;
    int *orderp_ = nullptr, *farp_ = nullptr;
};

namespace clip {

/// The cell being clipped: a counter-clockwise cycle of vertices, each starting a side.
class Clipper {
public:
    /// Room for m candidates: a cell has at most m edges, each followed by at most one arc (2 m
    /// vertices; m + 4 from the square), and a cut adds at most two. (m + 8 was too little for a
    /// ring of nine or more agents near 2R, an arc after every edge.)
    Clipper(ClipWorkspace& w, double radius, std::size_t m) : w_(w), radius_(radius), cap_(radius) {
        const std::size_t room = 2 * m + 8;
        if (w_.cur.size() < room) {
            w_.cur.resize(room);
            w_.next.resize(room);
            w_.flags.resize(room);
        }
    }

    /// Starts from the square of the four phantom agents w.add_square(radius) put after the m
    /// candidates, instead of the disk: the cell is then a polygon throughout (no arcs) and may
    /// reach the square's corners, R sqrt(2) from c.
    void start_square() {
        const std::size_t m = w_.m;
        for (std::size_t t = 0; t < 4; ++t) {
            const std::size_t j = m + (t + 3) % 4, k = m + t;  // side k starts where j ends
            w_.cur[t] = cell_vertex(line_vertex(w_.ax[j], w_.ay[j], w_.n2[j], w_.ax[k], w_.ay[k], w_.n2[k]),
                                    static_cast<int>(k));
        }
        n_ = 4;
        dirty_ = true;
        cap_ = kInf;
        square_ = true;
    }

    /// Farthest distance from c of the cell (the exact cell lies within it), R while an arc remains.
    double reach() {
        if (!dirty_) return reach_;
        dirty_ = false;
        double v2 = 0.0, e = 0.0;
        for (std::size_t t = 0; t < n_; ++t) {
            const CellVertex& v = w_.cur[t];
            if (v.side == kArcSide) return reach_ = radius_;
            v2 = std::max(v2, v.x * v.x + v.y * v.y);
            e = std::max(e, v.e);
        }
        return reach_ = std::min(cap_, std::sqrt(v2) * (1.0 + 4.0 * kU) + e);
    }

    /// Cuts the cell with H_k; false when uncertain.
    bool cut(int k) {
        const auto kk = static_cast<std::size_t>(k);
        const double akx = w_.ax[kk], aky = w_.ay[kk], n2k = w_.n2[kk];
        const std::size_t s = n_;
        if (s == 0) {  // the whole disk: the chord of k and the rest of the circle
            CellVertex* out = w_.next.data();
            out[0] = cell_vertex(chord_vertex(akx, aky, radius_, -1), k);
            out[1] = cell_vertex(chord_vertex(akx, aky, radius_, +1), kArcSide);
            return commit(2);
        }
        // Classify the vertices; the outside ones must form one cyclic run.
        const double na = l1(akx, aky), nb = 8.0 * kU * n2k;
        std::size_t outside = 0;
        char* flag = w_.flags.data();
        for (std::size_t t = 0; t < s; ++t) {
            const int g = side_of(w_.cur[t], akx, aky, n2k, na, nb);
            if (g == 2) return false;
            flag[t] = g < 0;
            outside += g < 0;
        }
#ifdef CLIP_STAT_CUT
        CLIP_STAT_CUT(s, outside);
#endif
        if (outside == 0) return square_ || cut_arc(k);  // a square's cell has no arc to cut
        return cut_run(k, s, outside);
    }

    /// Cuts the cell with every loaded candidate's half-plane; false when a cut was uncertain.
    /// Order: the nearest agent, the near ones (they shrink the cell to about its final size;
    /// sorting them by distance costs more than it saves), then the far ones, which mostly fail the
    /// screen: H_k holds the disk of radius |a_k| / 2, which holds the cell when that is beyond the
    /// cell's reach (with room for the rounding of n2).
    bool cut_loaded() {
        const int nn = w_.nn;
        if (!cut(nn)) return false;
        const auto screened = [&](int k) {
            const double r = reach();
            return w_.n2[static_cast<std::size_t>(k)] * (1.0 - 8.0 * kU) > 4.0 * r * r * (1.0 + 8.0 * kU);
        };
        for (std::size_t t = 0; t < w_.near; ++t) {
            const int k = w_.order[t];
            if (k != nn && !screened(k) && !cut(k)) return false;
        }
        for (std::size_t t = 0; t < w_.nfar; ++t) {
            const int k = w_.far[t];
            if (k != nn && !screened(k) && !cut(k)) return false;
        }
        return true;
    }

    std::size_t size() const { return n_; }
    const CellVertex& vertex(std::size_t t) const { return w_.cur[t]; }

private:
    bool commit(std::size_t n) {
        w_.cur.swap(w_.next);
        n_ = n;
        dirty_ = true;
        return true;
    }

    static Vertex as_vertex(const CellVertex& v) { return {v.x, v.y, v.e}; }

    /// The vertex where the boundary enters (sigma = -1) or leaves (+1) H_k along side `sd`.
    Vertex crossing(int sd, int k, int sigma) const {
        const auto kk = static_cast<std::size_t>(k);
        if (sd == kArcSide) return chord_vertex(w_.ax[kk], w_.ay[kk], radius_, sigma);
        const auto j = static_cast<std::size_t>(sd);
        return line_vertex(w_.ax[j], w_.ay[j], w_.n2[j], w_.ax[kk], w_.ay[kk], w_.n2[kk]);
    }

    bool has_arc() const {
        for (std::size_t t = 0; t < n_; ++t)
            if (w_.cur[t].side == kArcSide) return true;
        return false;
    }

    /// Some vertices strictly outside H_k: they form one run t0..t1; the boundary enters H_k on the
    /// side ending at t0 and leaves it on the side starting at t1, and k's edge joins the two.
    bool cut_run(int k, std::size_t s, std::size_t outside) {
        const auto kk = static_cast<std::size_t>(k);
        CellVertex* out = w_.next.data();
        if (outside == s) {
            // Every vertex outside: the part of the cell in H_k (c is in it) lies along one arc and
            // is bounded by k's chord; without an arc the decisions were inconsistent.
            if (!has_arc()) return false;
            out[0] = cell_vertex(chord_vertex(w_.ax[kk], w_.ay[kk], radius_, -1), k);
            out[1] = cell_vertex(chord_vertex(w_.ax[kk], w_.ay[kk], radius_, +1), kArcSide);
            return commit(2);
        }
        const char* flag = w_.flags.data();
        std::size_t t0 = s;
        for (std::size_t t = 0; t < s; ++t)
            if (flag[t] && !flag[t == 0 ? s - 1 : t - 1]) {
                if (t0 != s) return false;  // two runs: inconsistent, give up
                t0 = t;
            }
        if (t0 == s) return false;
        const std::size_t t1 = (t0 + outside - 1) % s;
        const int enter = w_.cur[t0 == 0 ? s - 1 : t0 - 1].side;
        const int leave = w_.cur[t1].side;
        const Vertex vin = crossing(enter, k, -1), vout = crossing(leave, k, +1);
        if (!(vin.e < kInf && vout.e < kInf)) return false;
        // The inside vertices from t1 + 1 round to t0 - 1, then k's two vertices.
        std::size_t n = 0;
        for (std::size_t t = t1 + 1 == s ? 0 : t1 + 1; t != t0; t = t + 1 == s ? 0 : t + 1) out[n++] = w_.cur[t];
        out[n++] = cell_vertex(vin, k);
        out[n++] = cell_vertex(vout, leave);
        return commit(n);
    }

    /// No vertex outside H_k: k cuts the cell only if it cuts an arc, i.e. if the circle's point q in
    /// the direction of a_k (the middle of the cap that H_k cuts off) lies in the cell.
    bool cut_arc(int k) {
        const std::size_t s = n_;
        if (!has_arc()) return true;  // nothing to do
        const auto kk = static_cast<std::size_t>(k);
        const double akx = w_.ax[kk], aky = w_.ay[kk];
        const double na = std::sqrt(w_.n2[kk]);
        const Vertex qv{radius_ * (akx / na), radius_ * (aky / na), 8.0 * kU * radius_};
        const CellVertex q = cell_vertex(qv, kArcSide);
        for (std::size_t t = 0; t < s; ++t) {
            const int sd = w_.cur[t].side;
            if (sd == kArcSide) continue;
            const auto j = static_cast<std::size_t>(sd);
            const int g = side_of(q, w_.ax[j], w_.ay[j], w_.n2[j], l1(w_.ax[j], w_.ay[j]), 8.0 * kU * w_.n2[j]);
            if (g == 2) return false;
            if (g < 0) return true;  // q is outside the cell: k cuts nothing
        }
        // q lies on an arc: find which (its angular sector from c contains q).
        std::size_t hit = s;
        for (std::size_t t = 0; t < s; ++t) {
            if (w_.cur[t].side != kArcSide) continue;
            const Vertex u = as_vertex(w_.cur[t]), v = as_vertex(w_.cur[t + 1 == s ? 0 : t + 1]);
            bool in;
            if (s == 1) {
                in = true;
            } else {
                const int span = cross_sign(u, v);
                if (span == 2) return false;
                const int a = span > 0 ? cross_sign(u, qv) : cross_sign(v, qv);
                const int b = span > 0 ? cross_sign(qv, v) : cross_sign(qv, u);
                if (a == 2 || b == 2) return false;
                in = span > 0 ? (a > 0 && b > 0) : !(a > 0 && b > 0);
            }
            if (in) {
                if (hit != s) return false;
                hit = t;
            }
        }
        if (hit == s) return false;
        // Split that arc: arc (u .. s_k), k's chord (s_k .. e_k), arc (e_k .. v).
        const Vertex sk = chord_vertex(akx, aky, radius_, -1), ek = chord_vertex(akx, aky, radius_, +1);
        if (!(sk.e < kInf && ek.e < kInf)) return false;
        CellVertex* out = w_.next.data();
        std::size_t n = 0;
        for (std::size_t t = 0; t < s; ++t) {
            out[n++] = w_.cur[t];
            if (t == hit) {
                out[n++] = cell_vertex(sk, k);
                out[n++] = cell_vertex(ek, kArcSide);
            }
        }
        return commit(n);
    }

    ClipWorkspace& w_;
    double radius_;
    double cap_;  // the cell lies within this distance of c: R (inside the disk), or none (square)
    bool square_ = false;  // started from the square: a polygon throughout
    std::size_t n_ = 0;
    double reach_ = 0.0;
    bool dirty_ = true;
};

}  // namespace clip

/// The limited cell of w.c among the loaded candidates by certified clipping (see the file
/// comment); false when it gave up (then `out` is unspecified and Boundary Scan must run).
inline bool certified_clip_loaded(double radius, LimitedCell& out, ClipWorkspace& w) {
    using namespace clip;
    w.summarize();
    const std::size_t m = w.m;
    if (m == 0) return false;  // Boundary Scan's full disk costs nothing
    const int nn = w.nn;
    const double r2 = radius * radius;
    // Products of up to three squared lengths must neither underflow nor overflow.
    if (!(w.lo > 1e-90 && w.hi < 1e90 && r2 > 1e-90 && r2 < 1e90)) return false;
    // The nearest neighbour, certified unique (else Boundary Scan breaks the tie exactly).
    if (m > 1 && !(w.lo2 - w.lo > 8.0 * kU * w.lo2)) return false;
    Clipper clipper(w, radius, m);
    if (!clipper.cut_loaded()) return false;
    // The cycle of boundary bisectors from the nearest neighbour's, and the vertex/arc labels.
    const std::size_t s = clipper.size();
    std::size_t start = s;
    for (std::size_t t = 0; t < s; ++t)
        if (clipper.vertex(t).side == nn) start = t;
    if (start == s) return false;  // Lemma 1 says it is there; give up rather than guess
    w.inside_disk = s >= 3;
    for (std::size_t t = 0; w.inside_disk && t < s; ++t) {
        const CellVertex& v = clipper.vertex(t);
        const double r = std::sqrt(v.x * v.x + v.y * v.y) * (1.0 + 4.0 * kU) + v.e;
        w.inside_disk = v.side != kArcSide && r < radius * (1.0 - 4.0 * kU);
    }
    w.lines.clear();
    w.meets.clear();
    w.cycle.clear();
    for (std::size_t r = 0; r < s; ++r) {
        const int k = clipper.vertex((start + r) % s).side;
        if (k == kArcSide) {
            if (!w.meets.empty()) w.meets.back() = 0;
            continue;
        }
        const auto kk = static_cast<std::size_t>(k);
        w.cycle.push_back(static_cast<int>(w.lines.size()));
        w.lines.push_back({Vec2(w.px[kk], w.py[kk]), Vec2(w.ax[kk], w.ay[kk]), w.n2[kk], w.id[kk], 0.0, 0});
        w.meets.push_back(1);
    }
    out.candidates = static_cast<Index>(m);
    out.chords_after_check = -1;
    emit_cell(w.c, radius, w.lines, w.cycle, w.meets, out);
    return true;
}

/// The squared distance within which about kNearFirst of m candidates lie (local density
/// m / (4 R^2)).
inline double near_first_sq(double radius, std::size_t m) {
    return 4.0 * radius * radius * static_cast<double>(clip::kNearFirst) / static_cast<double>(std::max<std::size_t>(m, 1));
}

/// The same from a candidate list (strictly within 2R of c, pairwise distinct, distinct from c).
inline bool certified_clip_cell(const Vec2& c, const std::vector<Candidate>& cand, double radius,
                                LimitedCell& out, ClipWorkspace& w) {
    w.start(c, near_first_sq(radius, cand.size()));
    for (const Candidate& q : cand) w.add(q.p, q.id);
    return certified_clip_loaded(radius, out, w);
}

/// Boundary Scan's cell, by the certified clipping filter when it decides, else by Boundary Scan.
/// Candidates as for certified_clip_cell (distinct, strictly within 2R).
inline void filtered_boundary_scan(const Vec2& c, const std::vector<Candidate>& cand, double radius,
                                   LimitedCell& out, CellWorkspace& ws, ClipWorkspace& cw) {
    if (!certified_clip_cell(c, cand, radius, out, cw)) boundary_scan(c, cand, radius, out, ws);
}

}  // namespace dvoronoi::detail
