// The certified fast path of a heterogeneous team's cells (Method::Auto; docs/spec.md, heterogeneous
// teams): agent c's cell W = power cell (weights R^2) ∩ B(c, r) by incremental clipping of the disk
// with the radical axes' half-planes in floating point, every decision certified by a forward error
// bound. When one is not (ties, three axes through one point, a vertex on the circle, tangent
// circles, over- or underflow) it gives up and the exact clipping (cells/power_cell.hpp) runs.
//
// The steps:
//   1. classify the candidates as power_cell does, from rounded s_j = |a_j|^2 + r^2 - R_j^2 and
//      C4_j = 4 r^2 |a_j|^2 - s_j^2 with their error bounds: no effect, a chord, or a disk outside
//      the half-plane (the cell is empty: stop there, the common way a small disk among big ones
//      ends up empty);
//   2. order the chords by the signed distance s_j / (2 |a_j|) of their axes (most restrictive
//      first) and clip the disk with them, skipping an axis once the cell lies within the ball
//      B(c, s_j / (2 |a_j|)) that its half-plane holds;
//   3. the cell: the surviving chords in counter-clockwise order, meeting at vertices or joined by
//      arcs, so the same pieces as the exact routes; the vertices are the clipper's own when their
//      certified bound is within kVertexAccuracy R_i, else constructed in double-double as every
//      power algorithm does (emit_power_cell, cells/power_chords.hpp).
// What differs from the equal-radius filter (cells/certified_clip.hpp): c need not lie in its
// cell, so a cut may leave nothing (the cell is empty) or only the cap beyond the new chord; the
// right side of a chord comes from s_j, whose bound is taken from |a_j|^2 + r^2 + R_j^2 (cancellation).
//
// Contract: no candidate at c with the same radius (limited_cells checks all pairs first).
#pragma once

#include "dvoronoi/cells/certified_clip.hpp"
#include "dvoronoi/cells/power_chords.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dvoronoi::detail {

/// The fast path's input, loaded from a spatial query, and its scratch (reused across agents).
struct PowerClipWorkspace {
    // Candidate k: position, radius, id; a = p - c, s, and ps = |a|^2 + r^2 + R^2 (bounds |s|'s terms).
    std::vector<double> px, py, pr, ax, ay, s, ps;
    std::vector<Index> id;
    std::vector<int> chords, sorted;  // step 1's chords, step 2's order
    std::vector<double> key;     // d |d| (d = s / (2 |a|), up to a factor): the order of step 2
    Vec2 c = Vec2::Zero();
    double r = 0.0;
    std::size_t m = 0;
    bool empty = false;  // step 1 met a disk outside its half-plane

    std::vector<clip::CellVertex> cur, next;
    std::vector<char> flags;
    // The result, for emit_power_cell.
    std::vector<pred::power::WLine> lines;
    std::vector<Index> ids;
    std::vector<int> cycle;
    std::vector<char> meets;
    std::vector<Vec2> rel;
    std::vector<char> is_arc;
    std::vector<double> span;

    void start(const Vec2& center, double radius) {
        c = center;
        r = radius;
        m = 0;
        empty = false;
    }
    /// Adds a batch as GridIndex::for_each_batch_within_at hands it over; `radius_at(t)` is the
    /// radius of the batch's agent t.
    template <class RadiusAt>
    void add_batch(const double* xs, const double* ys, const Index* idx, const std::uint32_t* sel, std::size_t count,
                   RadiusAt&& radius_at) {
        if (m + count > px.size()) grow(m + count);
        const double r2 = r * r;
        for (std::size_t t = 0; t < count; ++t, ++m) {
            const double x = xs[sel[t]], y = ys[sel[t]], R = radius_at(sel[t]);
            const double dx = x - c.x(), dy = y - c.y(), n2 = dx * dx + dy * dy, R2 = R * R;
            px[m] = x;
            py[m] = y;
            pr[m] = R;
            ax[m] = dx;
            ay[m] = dy;
            s[m] = (n2 + r2) - R2;
            ps[m] = n2 + r2 + R2;
            id[m] = idx[sel[t]];
        }
    }
    /// The same from a candidate list.
    void add(const Vec2& p, double R, Index j) {
        const double x[1] = {p.x()}, y[1] = {p.y()};
        const Index i[1] = {j};
        const std::uint32_t sel[1] = {0};
        add_batch(x, y, i, sel, 1, [&](std::uint32_t) { return R; });
    }

private:
    void grow(std::size_t need) {
        const std::size_t cap = std::max<std::size_t>({64, need, 2 * px.size()});
        for (auto* v : {&px, &py, &pr, &ax, &ay, &s, &ps}) v->resize(cap);
        id.resize(cap);
    }
};

/// How close to the exact vertices (relative to the agent's radius) the fast path's own vertices must
/// be to be handed out as they are (docs/heterogeneous.md).
inline constexpr double kVertexAccuracy = 0x1p-44;

namespace power_clip {

using clip::CellVertex;
using clip::kArcSide;
using clip::kInf;
using clip::kU;
using clip::Vertex;

/// Sign of s_k - 2 a_k . v (> 0: v strictly inside H_k), or 2 when the bound cannot decide. The
/// bound: |a_k|_1 (2 e + 24 u |v|_1) for the vertex's error and the dot product (as
/// clip::side_of), 16 u ps_k for the roundings of a_k and s_k.
inline int side_of(const CellVertex& v, const PowerClipWorkspace& w, std::size_t k) {
    const double f = w.s[k] - 2.0 * (w.ax[k] * v.x + w.ay[k] * v.y);
    const double b = l1(w.ax[k], w.ay[k]) * v.slack + 16.0 * kU * w.ps[k];
    if (f > b) return 1;
    if (f < -b) return -1;
    return 2;
}

/// The meeting of the axes of j and k, by Cramer's rule as core/accurate.hpp's line_vertex, with s in
/// place of |a|^2. Error bound as line_vertex's, with s's error (at most 6 u ps, against line_vertex's
/// 4 u |a|^2) taken from ps: 9 u where line_vertex has 7 u.
inline Vertex line_vertex(const PowerClipWorkspace& w, std::size_t j, std::size_t k) {
    const double ajx = w.ax[j], ajy = w.ay[j], akx = w.ax[k], aky = w.ay[k];
    const double l = ajx * aky, r = ajy * akx;
    const double d = l - r, pd = std::fabs(l) + std::fabs(r);
    const double hj = 0.5 * w.s[j], hk = 0.5 * w.s[k], pj = 0.5 * w.ps[j], pk = 0.5 * w.ps[k];
    const double nx = hj * aky - hk * ajy, ny = ajx * hk - akx * hj;
    const double pn = pj * std::fabs(aky) + pk * std::fabs(ajy) + pk * std::fabs(ajx) + pj * std::fabs(akx);
    const double an = std::fabs(nx) + std::fabs(ny);
    const double inv = 1.0 / d;
    const double x = nx * inv, y = ny * inv;
    if (!(std::fabs(d) > 0x1p-20 * pd)) return {x, y, kInf};
    const double ainv = std::fabs(inv);
    return {x, y, ainv * (9.0 * kU * pn + kU * an * (4.0 * pd * ainv + 5.0))};
}

/// The end e_k^sigma of k's chord: the foot t a_k (t = s_k / (2 |a_k|^2)) plus sigma w perp(a_k) / |a_k|,
/// w = sqrt(r^2 - t^2 |a_k|^2) the half chord. Error bound: the foot's distance h = |t| |a_k| carries
/// (6 u ps_k / (2 |a_k|) + 4 u h); w moves by that times h / w (the conditioning near tangency) plus
/// 3 u r^2 / w; the roundings of the sum add 6 u (h + w); doubled as chord_vertex's.
inline Vertex chord_vertex(const PowerClipWorkspace& w, std::size_t k, int sigma) {
    const double akx = w.ax[k], aky = w.ay[k], r = w.r;
    const double n2 = akx * akx + aky * aky, na = std::sqrt(n2);
    const double t = w.s[k] / (2.0 * n2), h = std::fabs(w.s[k]) / (2.0 * na);
    const double hc = std::sqrt(std::max(0.0, (r - h) * (r + h)));
    const double q = hc / na;
    const double x = t * akx - sigma * q * aky, y = t * aky + sigma * q * akx;
    if (!(hc > 0.0) || !(r - h > 0.0) || !(na > 0.0)) return {x, y, kInf};
    const double eh = 3.0 * kU * w.ps[k] / na + 4.0 * kU * h;
    const double e = eh + (eh * h + 3.0 * kU * r * r) / hc + 6.0 * kU * (h + hc);
    return {x, y, 2.0 * e};
}

/// The cell being clipped: a counter-clockwise cycle of vertices, each starting a side (a chord's
/// candidate index or kArcSide); no vertex at all is the whole disk.
class Clipper {
public:
    /// Room for every cell of m chords: each chord bounds the cell once and an arc may follow it
    /// (2 m vertices), and a cut adds at most two.
    explicit Clipper(PowerClipWorkspace& w) : w_(w) {
        const std::size_t room = 2 * w_.m + 4;
        if (w_.cur.size() < room) {
            w_.cur.resize(room);
            w_.next.resize(room);
            w_.flags.resize(room);
        }
    }

    enum Result { kCut, kEmpty, kUnsure };

    /// Farthest distance from c of the cell (the exact cell lies within it): r while an arc remains.
    double reach() const {
        double v2 = 0.0, e = 0.0;
        for (std::size_t t = 0; t < n_; ++t) {
            const CellVertex& v = w_.cur[t];
            if (v.side == kArcSide) return w_.r;
            v2 = std::max(v2, v.x * v.x + v.y * v.y);
            e = std::max(e, v.e);
        }
        return n_ == 0 ? w_.r : std::sqrt(v2) * (1.0 + 4.0 * kU) + e;
    }

    /// Cuts the cell with H_k.
    Result cut(std::size_t k) {
        const std::size_t s = n_;
        if (s == 0) return to_cap(k);  // the whole disk: the cap on H_k's side of the chord
        char* flag = w_.flags.data();
        std::size_t outside = 0;
        for (std::size_t t = 0; t < s; ++t) {
            const int g = side_of(w_.cur[t], w_, k);
            if (g == 2) return kUnsure;
            flag[t] = g < 0;
            outside += g < 0;
        }
        if (outside == 0) return cut_arc(k);
        if (outside < s) return cut_run(k, s, outside);
        // Every vertex outside: what is left in H_k lies along an arc and is k's whole cap, which the
        // cell holds exactly when it holds both of k's chord ends (else the cell meets H_k in no area).
        if (!has_arc()) return kEmpty;
        for (int sigma : {-1, +1}) {
            const CellVertex e = clip::cell_vertex(chord_vertex(w_, k, sigma), 0);
            if (!(e.e < kInf)) return kUnsure;
            for (std::size_t t = 0; t < s; ++t) {
                const int sd = w_.cur[t].side;
                if (sd == kArcSide) continue;
                const int g = side_of(e, w_, static_cast<std::size_t>(sd));
                if (g == 2) return kUnsure;
                if (g < 0) return kEmpty;
            }
        }
        return to_cap(k);
    }

    std::size_t size() const { return n_; }
    const CellVertex& vertex(std::size_t t) const { return w_.cur[t]; }

private:
    Result commit(std::size_t n) {
        w_.cur.swap(w_.next);
        n_ = n;
        return kCut;
    }

    Result to_cap(std::size_t k) {
        const Vertex a = chord_vertex(w_, k, -1), b = chord_vertex(w_, k, +1);
        if (!(a.e < kInf && b.e < kInf)) return kUnsure;
        w_.next[0] = clip::cell_vertex(a, static_cast<int>(k));
        w_.next[1] = clip::cell_vertex(b, kArcSide);
        return commit(2);
    }

    bool has_arc() const {
        for (std::size_t t = 0; t < n_; ++t)
            if (w_.cur[t].side == kArcSide) return true;
        return false;
    }

    /// Where the boundary enters (sigma = -1) or leaves (+1) H_k along side `sd`.
    Vertex crossing(int sd, std::size_t k, int sigma) const {
        if (sd == kArcSide) return chord_vertex(w_, k, sigma);
        return line_vertex(w_, static_cast<std::size_t>(sd), k);
    }

    /// Some vertices strictly outside H_k, not all: they form one run t0..t1 (convexity); k's edge
    /// joins the crossing on the side ending at t0 to the one on the side starting at t1.
    Result cut_run(std::size_t k, std::size_t s, std::size_t outside) {
        const char* flag = w_.flags.data();
        std::size_t t0 = s;
        for (std::size_t t = 0; t < s; ++t)
            if (flag[t] && !flag[t == 0 ? s - 1 : t - 1]) {
                if (t0 != s) return kUnsure;  // two runs: inconsistent, give up
                t0 = t;
            }
        if (t0 == s) return kUnsure;
        const std::size_t t1 = (t0 + outside - 1) % s;
        const int enter = w_.cur[t0 == 0 ? s - 1 : t0 - 1].side, leave = w_.cur[t1].side;
        const Vertex vin = crossing(enter, k, -1), vout = crossing(leave, k, +1);
        if (!(vin.e < kInf && vout.e < kInf)) return kUnsure;
        CellVertex* out = w_.next.data();
        std::size_t n = 0;
        for (std::size_t t = t1 + 1 == s ? 0 : t1 + 1; t != t0; t = t + 1 == s ? 0 : t + 1) out[n++] = w_.cur[t];
        out[n++] = clip::cell_vertex(vin, static_cast<int>(k));
        out[n++] = clip::cell_vertex(vout, leave);
        return commit(n);
    }

    /// No vertex outside H_k: k cuts the cell only through an arc, and then that arc holds q, the
    /// circle's point in the direction of a_k (the middle of the cap H_k cuts off).
    Result cut_arc(std::size_t k) {
        const std::size_t s = n_;
        if (!has_arc()) return kCut;
        const double akx = w_.ax[k], aky = w_.ay[k];
        const double na = std::sqrt(akx * akx + aky * aky);
        const Vertex qv{w_.r * (akx / na), w_.r * (aky / na), 8.0 * kU * w_.r};
        const CellVertex q = clip::cell_vertex(qv, kArcSide);
        for (std::size_t t = 0; t < s; ++t) {
            const int sd = w_.cur[t].side;
            if (sd == kArcSide) continue;
            const int g = side_of(q, w_, static_cast<std::size_t>(sd));
            if (g == 2) return kUnsure;
            if (g < 0) return kCut;  // q is outside the cell: k cuts nothing
        }
        std::size_t hit = s;  // the arc whose sector from c holds q
        for (std::size_t t = 0; t < s; ++t) {
            if (w_.cur[t].side != kArcSide) continue;
            const CellVertex &cu = w_.cur[t], &cv = w_.cur[t + 1 == s ? 0 : t + 1];
            const Vertex u{cu.x, cu.y, cu.e}, v{cv.x, cv.y, cv.e};
            bool in;
            if (s == 1) {
                in = true;
            } else {
                const int sp = clip::cross_sign(u, v);
                if (sp == 2) return kUnsure;
                const int a = sp > 0 ? clip::cross_sign(u, qv) : clip::cross_sign(v, qv);
                const int b = sp > 0 ? clip::cross_sign(qv, v) : clip::cross_sign(qv, u);
                if (a == 2 || b == 2) return kUnsure;
                in = sp > 0 ? (a > 0 && b > 0) : !(a > 0 && b > 0);
            }
            if (in) {
                if (hit != s) return kUnsure;
                hit = t;
            }
        }
        if (hit == s) return kUnsure;
        const Vertex sk = chord_vertex(w_, k, -1), ek = chord_vertex(w_, k, +1);
        if (!(sk.e < kInf && ek.e < kInf)) return kUnsure;
        CellVertex* out = w_.next.data();
        std::size_t n = 0;
        for (std::size_t t = 0; t < s; ++t) {
            out[n++] = w_.cur[t];
            if (t == hit) {  // arc (u .. s_k), k's chord (s_k .. e_k), arc (e_k .. v)
                out[n++] = clip::cell_vertex(sk, static_cast<int>(k));
                out[n++] = clip::cell_vertex(ek, kArcSide);
            }
        }
        return commit(n);
    }

    PowerClipWorkspace& w_;
    std::size_t n_ = 0;
};

}  // namespace power_clip

/// The cell straight from the clipper's vertices when each is certainly within kVertexAccuracy r of
/// the exact one and every arc certainly spans more than its ends' errors (so its span keeps the
/// right branch); false otherwise (then emit_power_cell constructs them in double-double).
inline bool emit_from_clipper(const power_clip::Clipper& clipper, LimitedCell& out, PowerClipWorkspace& w) {
    const std::size_t s = clipper.size();
    const double tight = kVertexAccuracy * w.r;
    for (std::size_t t = 0; t < s; ++t) {
        const clip::CellVertex& v = clipper.vertex(t);
        if (!(v.e <= tight)) return false;
        if (v.side == clip::kArcSide) {
            const clip::CellVertex& u = clipper.vertex(t + 1 == s ? 0 : t + 1);
            if (!(std::fabs(u.x - v.x) + std::fabs(u.y - v.y) > 4.0 * (u.e + v.e))) return false;
        }
    }
    out.pieces.clear();
    w.rel.clear();
    w.is_arc.clear();
    w.span.clear();
    for (std::size_t t = 0; t < s; ++t) {
        const clip::CellVertex& v = clipper.vertex(t);
        const Vec2 rel(v.x, v.y);
        Piece p;
        p.start = w.c + rel;
        double a = 0.0;
        if (v.side == clip::kArcSide) {
            const clip::CellVertex& u = clipper.vertex(t + 1 == s ? 0 : t + 1);
            a = std::atan2(v.x * u.y - v.y * u.x, v.x * u.x + v.y * u.y);
            if (a <= 0.0) a += 2.0 * kPowerPi;
            p.arc_span = a;
        } else {
            p.neighbor = w.id[static_cast<std::size_t>(v.side)];
        }
        out.pieces.push_back(p);
        w.rel.push_back(rel);
        w.is_arc.push_back(v.side == clip::kArcSide);
        w.span.push_back(a);
    }
    CellMeasures m = power_measures(w.rel, w.is_arc, w.span, w.r);
    m.centroid += w.c;
    out.measures_ = m;
    return true;
}

/// The cell of w.c (radius w.r) among the loaded candidates by the certified clipping; false when it
/// gave up (then `out` is unspecified and the exact route must run).
inline bool certified_power_clip_loaded(LimitedCell& out, PowerClipWorkspace& w) {
    using namespace power_clip;
    const double r = w.r, r2 = r * r;
    power_empty_cell(w.c, r, static_cast<Index>(w.m), out);
    if (!(r2 > 1e-90 && r2 < 1e90)) return false;
    // Step 1: classify (C4 = 4 r^2 |a|^2 - s^2, its terms bounded by 4 r^2 |a|^2 + ps^2).
    auto& chords = w.chords;
    auto& key = w.key;
    // Branch-free: which way a candidate goes is hard to predict, so every candidate is classified
    // and the chords' indices written in one pass, and the verdicts combined after it.
    if (chords.size() < w.m) chords.resize(w.m);
    std::size_t nc = 0;
    bool out_of_range = false, empty = false, unsure = false;
    for (std::size_t k = 0; k < w.m; ++k) {
        const double n2 = w.ax[k] * w.ax[k] + w.ay[k] * w.ay[k], sk = w.s[k], pk = w.ps[k];
        out_of_range |= !(pk > 1e-90 && pk < 1e90);
        const double fr = 4.0 * r2 * n2, c4 = fr - sk * sk, bc = 32.0 * kU * (fr + pk * pk);
        const double bs = 12.0 * kU * pk;
        const bool misses = c4 < -bc, cuts = c4 > bc && n2 > 0.0;
        empty |= misses & (sk < -bs);                        // the disk lies outside H_k
        unsure |= !misses & !cuts;                           // tangent, or too close to call
        unsure |= misses & !(sk < -bs) & !(sk > bs);
        chords[nc] = static_cast<int>(k);
        nc += cuts;
    }
    if (out_of_range) return false;
    if (empty) return true;  // out is the empty cell, whatever the others
    if (unsure) return false;
    chords.resize(nc);
    key.resize(nc);
    for (std::size_t t = 0; t < nc; ++t) {
        const auto k = static_cast<std::size_t>(chords[t]);
        key[t] = w.s[k] * std::fabs(w.s[k]) / (w.ax[k] * w.ax[k] + w.ay[k] * w.ay[k]);
    }
    if (chords.empty()) {
        power_full_disk(w.c, r, out);
        return true;
    }
    // Step 2: most restrictive first, roughly: a counting sort into kBuckets by d |d| / r^2 in (-1, 1)
    // (a full sort of the ~30 chords cost more than the cuts it saves; only the speed depends on it).
    constexpr std::size_t kBuckets = 8;
    std::size_t count[kBuckets + 1] = {};
    const auto bucket = [&](double kv) {
        const double b = (kv / (4.0 * r2) + 1.0) * (0.5 * kBuckets);
        return b <= 0.0 ? std::size_t{0} : std::min(kBuckets - 1, static_cast<std::size_t>(b));
    };
    for (const double kv : key) ++count[bucket(kv) + 1];
    for (std::size_t b = 1; b <= kBuckets; ++b) count[b] += count[b - 1];
    auto& sorted = w.sorted;
    sorted.resize(chords.size());
    for (std::size_t t = 0; t < chords.size(); ++t) sorted[count[bucket(key[t])]++] = chords[t];
    Clipper clipper(w);
    for (const int kk : sorted) {
        const auto k = static_cast<std::size_t>(kk);
        // H_k holds the ball B(c, s_k / (2 |a_k|)): skip k when that ball holds the cell.
        const double sk = w.s[k] - 8.0 * kU * w.ps[k], rr = clipper.reach();
        if (sk > 0.0 && sk * sk > 4.0 * rr * rr * (w.ax[k] * w.ax[k] + w.ay[k] * w.ay[k]) * (1.0 + 16.0 * kU)) continue;
        const Clipper::Result res = clipper.cut(k);
        if (res == Clipper::kUnsure) return false;
        if (res == Clipper::kEmpty) return true;
    }
    // Step 3: the surviving chords in counter-clockwise order, meeting at vertices or joined by arcs.
    const std::size_t s = clipper.size();
    w.lines.clear();
    w.ids.clear();
    w.cycle.clear();
    w.meets.clear();
    for (std::size_t t = 0; t < s; ++t) {
        const int k = clipper.vertex(t).side;
        if (k == kArcSide) continue;
        const auto kk = static_cast<std::size_t>(k);
        pred::power::WLine l;
        l.p = Vec2(w.px[kk], w.py[kk]);
        l.R = w.pr[kk];
        w.cycle.push_back(static_cast<int>(w.lines.size()));
        w.lines.push_back(l);
        w.ids.push_back(w.id[kk]);
        w.meets.push_back(clipper.vertex(t + 1 == s ? 0 : t + 1).side != kArcSide);  // else an arc follows
    }
    if (w.cycle.empty()) return false;  // a clipped cell has a chord; give up rather than guess
    if (!emit_from_clipper(clipper, out, w))
        emit_power_cell(pred::power::Frame{w.c, r}, w.lines, w.ids, w.cycle, w.meets, out, w.rel, w.is_arc, w.span);
    return true;
}

}  // namespace dvoronoi::detail
