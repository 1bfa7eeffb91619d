// Geodesic distance on the free pixels of an occupancy grid, from many sources at once: the length of
// the shortest path through free space (docs/spec.md, "Geodesic cells on maps (coverage)").
//
// Free space is the map's rectangle minus the occupied pixels (closed unit squares) and minus the points
// where two occupied pixels touch only diagonally. A shortest path is a polyline that bends only at
// convex corners of occupied pixels (pixel corners with exactly one occupied pixel around them), so
//   d(q) = min over anchors a that see q of  D(a) + |q - a|,
// anchors being the sources and those corners. This is an any-angle wavefront (a Dijkstra over pixels
// and corners, in a bucket queue): every pixel carries its anchor, the last bend of its path, and
//   - a pixel q takes anchor a when the two pixels its segment to a passes between after leaving q's
//     square (the brackets) both hold a: then q's segment is free, exactly (no occupied unit square
//     fits in the thin triangle between two free segments whose base is one pixel), with no ray walk;
//     directly when a lies in q's closed square; otherwise only after walking the segment exactly
//     (segment_free_traced), which happens along shadow and cell boundaries;
//   - a convex corner v becomes an anchor when a pixel p next to it holds anchor a, a lies in p's
//     quadrant seen from v and the segment v-a is free (walked exactly): D(v) = D(a) + |v - a|; corners
//     also reach the corners along their two wall edges and those within CORNER_WINDOW pixels;
//   - where sight is blocked, a pixel (or corner) tries the settled corners nearby (a shadow thinner
//     than a pixel hides the right bend from every neighbour), and a pixel relays through its
//     neighbour's centre (an 8-connected step), which keeps every reachable pixel reached.
// Every path used is a real path through free space, so no distance is shorter than the true one (up
// to rounding); one can be longer where the best bend is missed. Measured against exact visibility-graph
// shortest paths (tools/bench_geodesic.py --accuracy, docs/geodesic_coverage.md): at most 1.6 % longer
// at pixels more than 3 pixels from the sources, 0.002 % on average.
//
// Coordinates are image pixel units: pixel (r, c) covers [c, c+1] x [r, r+1] (u to the right, w down),
// its centre is (c + 0.5, r + 0.5); corner vertex (i, j) is the point (i, j).
//
// Ties: every pixel goes to the source with the smallest computed distance, ties to the lower index.
// O(P) queue operations for P reached pixels (a walk per pixel only on boundaries). Single-threaded and
// deterministic.
#pragma once

#include "dvoronoi/coverage/grid_segment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace dvoronoi::coverage {

//! The wavefront's result. Anchor ids: [0, n) sources, [n, n + V) corner vertices (V = (rows+1)(cols+1),
//! vertex (i, j) is id n + j (cols + 1) + i), [n + V, n + V + P) pixel centres used as relays.
struct GeodesicField {
    std::int32_t rows = 0, cols = 0, sources = 0;
    std::vector<double> distance;        //!< per pixel (row-major), pixel units; +inf if not reached
    std::vector<std::int32_t> label;     //!< per pixel: nearest source, -1 if not reached
    std::vector<std::int64_t> anchor;    //!< per pixel: last bend point of its path, -1 if not reached
    std::vector<double> vertex_distance; //!< per corner vertex (+inf unless it became an anchor)
    std::vector<std::int64_t> vertex_parent;  //!< per corner vertex: the anchor before it
    std::vector<PixelPoint> points;      //!< the sources

    std::int64_t vertices() const { return std::int64_t(rows + 1) * (cols + 1); }

    //! Position of an anchor (pixel units).
    PixelPoint anchor_point(std::int64_t a) const {
        const std::int64_t n = sources, V = vertices();
        if (a < n) return points[static_cast<std::size_t>(a)];
        if (a < n + V) {
            const std::int64_t v = a - n;
            return {double(v % (cols + 1)), double(v / (cols + 1))};
        }
        const std::int64_t p = a - n - V;
        return {double(p % cols) + 0.5, double(p / cols) + 0.5};
    }

    //! Geodesic distance of an anchor (pixel units).
    double anchor_distance(std::int64_t a) const {
        const std::int64_t n = sources, V = vertices();
        if (a < n) return 0.0;
        if (a < n + V) return vertex_distance[static_cast<std::size_t>(a - n)];
        return distance[static_cast<std::size_t>(a - n - V)];  // a relay: its pixel's own distance
    }

    //! The anchor before anchor `a` on its path (-1 for a source).
    std::int64_t anchor_parent(std::int64_t a) const {
        const std::int64_t n = sources, V = vertices();
        if (a < n) return -1;
        if (a < n + V) return vertex_parent[static_cast<std::size_t>(a - n)];
        return anchor[static_cast<std::size_t>(a - n - V)];
    }
};

namespace detail {

struct WaveEntry {
    double d;
    std::int32_t label;
    std::int64_t node;  // pixel id, or P + vertex id
};

// A bucket queue: entries are taken by distance in steps of WIDTH (first in, first out within a step),
// a fraction of the smallest step of the wavefront, so the order is Dijkstra's up to that step; an entry
// that later improves is taken again (label correcting), so what is taken out of order is corrected.
// O(1) per entry, against O(log n) for a binary heap.
class BucketQueue {
public:
    static constexpr double WIDTH = 0.25;
    void push(const WaveEntry& e) {
        auto k = static_cast<std::size_t>(e.d / WIDTH);
        if (k < current_) k = current_;
        if (k >= buckets_.size()) buckets_.resize(k + 1);
        buckets_[k].push_back(e);
        ++size_;
    }
    bool empty() const { return size_ == 0; }
    void clear() {
        for (auto& b : buckets_) b.clear();
        current_ = at_ = size_ = 0;
    }
    //! The next entry (call only when not empty).
    WaveEntry pop() {
        while (at_ >= buckets_[current_].size()) {
            buckets_[current_].clear();
            at_ = 0;
            ++current_;
        }
        --size_;
        return buckets_[current_][at_++];
    }

private:
    std::vector<std::vector<WaveEntry>> buckets_;
    std::size_t current_ = 0, at_ = 0, size_ = 0;
};

inline double dist2d(double x, double y) { return std::sqrt(x * x + y * y); }

inline bool better(double d, std::int32_t l, double d0, std::int32_t l0) {
    return d < d0 || (d == d0 && l < l0);
}

}  // namespace detail

//! Buffers of geodesic_field kept between calls on the same map (a Lloyd run calls it every step): the
//! map's convex corners and clearance, and the per-pixel and per-corner state, so no call allocates.
class GeodesicWorkspace {
public:
    // The wavefront's state of a pixel, 16 bytes (it is touched in random order: one cache miss).
    struct PixelState {
        double d = std::numeric_limits<double>::infinity();
        std::int32_t anchor = -1;
        std::int32_t label : 31;
        std::uint32_t done : 1;
        PixelState() : label(-1), done(0) {}
    };

    GeodesicWorkspace(const std::uint8_t* occ, std::int32_t rows, std::int32_t cols) : occ_(occ), rows_(rows), cols_(cols) {
        const OccupancyView grid{occ, rows, cols};
        const std::int64_t V = std::int64_t(rows + 1) * (cols + 1);
        // A convex corner: exactly one of the four pixels around vertex (i, j) is occupied.
        corner.assign(static_cast<std::size_t>(V), 0);
        for (std::int64_t j = 0; j <= rows; ++j)
            for (std::int64_t i = 0; i <= cols; ++i)
                corner[j * (cols + 1) + i] =
                    (grid.blocked(j - 1, i - 1) + grid.blocked(j - 1, i) + grid.blocked(j, i - 1) + grid.blocked(j, i)) == 1;
        clear = chessboard_clearance(grid, 255);
    }
    bool same_map(const std::uint8_t* occ, std::int32_t rows, std::int32_t cols) const {
        return occ == occ_ && rows == rows_ && cols == cols_;
    }

    std::vector<std::uint8_t> corner, clear, vdone;
    std::vector<PixelState> st;
    std::vector<std::int32_t> vertex_label;
    detail::BucketQueue queue;

private:
    const std::uint8_t* occ_;
    std::int32_t rows_, cols_;
};

/*! Multi-source geodesic distance, range-limited to `limit` pixel units (+inf: no limit).
    `occ` is rows x cols, row-major, nonzero = occupied. Every source must lie in a free pixel (the pixel
    floor(u), floor(w)); the caller checks it. Pixels farther than `limit` stay unreached. `workspace`
    (optional) must have been made for this map; it saves the allocations between calls. */
inline void geodesic_field(const std::uint8_t* occ, std::int32_t rows, std::int32_t cols,
                           const std::vector<PixelPoint>& sources, double limit, GeodesicField& f,
                           GeodesicWorkspace& ws) {
    if (!ws.same_map(occ, rows, cols)) throw std::invalid_argument("geodesic_field: the workspace is for another map");
    using detail::better;
    using detail::dist2d;
    constexpr double inf = std::numeric_limits<double>::infinity();
    const OccupancyView grid{occ, rows, cols};
    f.rows = rows;
    f.cols = cols;
    f.sources = static_cast<std::int32_t>(sources.size());
    f.points = sources;
    const std::int64_t P = std::int64_t(rows) * cols, V = f.vertices(), n = f.sources;
    if (n + V + P >= (std::int64_t(1) << 31) || n >= (std::int64_t(1) << 30))
        throw std::invalid_argument("geodesic_field: the map is too large (more than 2^31 pixels and corners)");
    auto& st = ws.st;
    st.assign(static_cast<std::size_t>(P), GeodesicWorkspace::PixelState());
    f.vertex_distance.assign(static_cast<std::size_t>(V), inf);
    f.vertex_parent.assign(static_cast<std::size_t>(V), -1);
    auto& vertex_label = ws.vertex_label;
    vertex_label.assign(static_cast<std::size_t>(V), -1);
    auto& vdone = ws.vdone;
    vdone.assign(static_cast<std::size_t>(V), 0);
    detail::BucketQueue& heap = ws.queue;
    heap.clear();
    auto offer_pixel = [&](std::int64_t q, double d, std::int32_t l, std::int64_t a) {
        if (!(d <= limit) || !better(d, l, st[q].d, st[q].label)) return;
        st[q].d = d;
        st[q].label = l;
        st[q].anchor = static_cast<std::int32_t>(a);
        st[q].done = 0;
        heap.push({d, l, q});
    };
    const auto& corner = ws.corner;
    auto convex = [&](std::int64_t i, std::int64_t j) { return corner[j * (cols + 1) + i] != 0; };

    // Each source starts in its pixel and in the pixels around it that see it: a pixel holds one
    // label, so a source whose own pixel goes to another source there (two agents in one pixel)
    // would otherwise never spread, and get no cell.
    for (std::int32_t k = 0; k < n; ++k) {
        const auto& s = sources[static_cast<std::size_t>(k)];
        const auto c = static_cast<std::int64_t>(std::floor(s.u)), r = static_cast<std::int64_t>(std::floor(s.w));
        if (grid.blocked(r, c)) continue;  // the caller rejects this; never start inside a wall
        for (std::int64_t qr = r - 1; qr <= r + 1; ++qr)
            for (std::int64_t qc = c - 1; qc <= c + 1; ++qc) {
                if (grid.blocked(qr, qc)) continue;  // the outside included
                const PixelPoint cq{qc + 0.5, qr + 0.5};
                if ((qr != r || qc != c) && !segment_free(grid, cq, s)) continue;
                offer_pixel(qr * cols + qc, dist2d(cq.u - s.u, cq.w - s.w), k, k);
            }
    }

    // Where the segment from pixel q's centre towards point A leaves q's square: -2 if A lies in q's
    // closed square (direct sight), -1 if it leaves into an occupied pixel or through a pinch point,
    // else the neighbouring pixel it enters.
    auto back_trace = [&](std::int64_t qr, std::int64_t qc, const PixelPoint& A) -> std::int64_t {
        const double du = A.u - (qc + 0.5), dw = A.w - (qr + 0.5);
        const double au = std::fabs(du), aw = std::fabs(dw);
        if (au <= 0.5 && aw <= 0.5) return -2;
        const std::int64_t su = du > 0 ? 1 : -1, sw = dw > 0 ? 1 : -1;
        std::int64_t nr = qr, nc = qc;
        if (au > aw) {
            nc += su;
        } else if (aw > au) {
            nr += sw;
        } else {  // through q's corner: into the diagonal pixel, unless the corner is a pinch point
            if (grid.blocked(qr + sw, qc) && grid.blocked(qr, qc + su)) return -1;
            nr += sw;
            nc += su;
        }
        return grid.blocked(nr, nc) ? -1 : nr * cols + nc;
    };

    auto offer_vertex = [&](std::int64_t i, std::int64_t j, double d, std::int32_t l, std::int64_t parent) {
        const std::int64_t v = j * (cols + 1) + i;
        if (vdone[v] || !(d <= limit) || !better(d, l, f.vertex_distance[v], vertex_label[v])) return;
        f.vertex_distance[v] = d;
        vertex_label[v] = l;
        f.vertex_parent[v] = parent;
        heap.push({d, l, P + v});
    };

    // The local test (the segment leaves q into a pixel holding the anchor) is necessary, not sufficient:
    // a chain of such pixels can bend around a wall that q's own segment crosses. So every segment an
    // anchor is offered along is then walked exactly (segment_free_traced: long strides through open
    // space, pixel by pixel only next to walls).
    const auto& clear = ws.clear;
    auto sight_free = [&](const PixelPoint& cq, const PixelPoint& A) { return segment_free_traced(grid, clear, cq, A); };
    // Where sight to the anchor is blocked, the path bends at a corner nearby, which may belong to no
    // neighbour (a shadow thinner than a pixel): try the settled corners within RESCUE pixels, exactly.
    constexpr std::int64_t RESCUE = 4, CORNER_WINDOW = 6;
    auto rescue = [&](std::int64_t qr, std::int64_t qc) {
        const std::int64_t q = qr * cols + qc;
        const PixelPoint cq{qc + 0.5, qr + 0.5};
        for (std::int64_t j = std::max<std::int64_t>(0, qr + 1 - RESCUE); j <= std::min<std::int64_t>(rows, qr + RESCUE); ++j)
            for (std::int64_t i = std::max<std::int64_t>(0, qc + 1 - RESCUE); i <= std::min<std::int64_t>(cols, qc + RESCUE); ++i) {
                const std::int64_t v = j * (cols + 1) + i;
                if (!vdone[v]) continue;
                const double d = f.vertex_distance[v] + dist2d(cq.u - double(i), cq.w - double(j));
                if (!(d <= limit) || !better(d, vertex_label[v], st[q].d, st[q].label)) continue;
                if (segment_free(grid, cq, {double(i), double(j)})) offer_pixel(q, d, vertex_label[v], n + v);
            }
    };

    // The pixel diagonal to q towards A: with the exit pixel, the two pixels q's segment passes between
    // after leaving q's square (-1 when the segment runs along an axis or through q's corner, where the
    // exit pixel alone carries it; -3 when that pixel is occupied).
    auto side_bracket = [&](std::int64_t qr, std::int64_t qc, const PixelPoint& A) -> std::int64_t {
        const double du = A.u - (qc + 0.5), dw = A.w - (qr + 0.5);
        if (du == 0 || dw == 0 || std::fabs(du) == std::fabs(dw)) return -1;
        const std::int64_t r = qr + (dw > 0 ? 1 : -1), c = qc + (du > 0 ? 1 : -1);
        return grid.blocked(r, c) ? -3 : r * cols + c;
    };

    // A convex corner next to a pixel that sees the anchor while the corner does not (the anchor's shadow
    // edge passes between them): its path bends at a settled corner that may lie farther than any
    // window, so the settled corners within VERTEX_RESCUE pixels are tried, nearest path first, exactly.
    constexpr std::int64_t VERTEX_RESCUE = 16;
    std::vector<std::pair<double, std::int64_t>> found;
    auto vertex_rescue = [&](std::int64_t i, std::int64_t j) {
        const std::int64_t v = j * (cols + 1) + i;
        if (vdone[v]) return;
        found.clear();
        for (std::int64_t wj = std::max<std::int64_t>(0, j - VERTEX_RESCUE); wj <= std::min<std::int64_t>(rows, j + VERTEX_RESCUE); ++wj)
            for (std::int64_t wi = std::max<std::int64_t>(0, i - VERTEX_RESCUE); wi <= std::min<std::int64_t>(cols, i + VERTEX_RESCUE); ++wi) {
                const std::int64_t w = wj * (cols + 1) + wi;
                if (!vdone[w] || w == v) continue;
                const double d = f.vertex_distance[w] + dist2d(double(wi - i), double(wj - j));
                if (d <= limit && better(d, vertex_label[w], f.vertex_distance[v], vertex_label[v])) found.emplace_back(d, w);
            }
        std::sort(found.begin(), found.end());
        for (const auto& [d, w] : found) {
            const std::int64_t wi = w % (cols + 1), wj = w / (cols + 1);
            if (segment_free_traced(grid, clear, {double(i), double(j)}, {double(wi), double(wj)})) {
                offer_vertex(i, j, d, vertex_label[w], n + w);
                return;
            }
        }
    };

    static constexpr int DR[8] = {-1, 1, 0, 0, -1, -1, 1, 1};
    static constexpr int DC[8] = {0, 0, -1, 1, -1, 1, -1, 1};

    auto relay = [&](std::int64_t p, std::int64_t q, bool diagonal) {
        offer_pixel(q, st[p].d + (diagonal ? 1.4142135623730951 : 1.0), st[p].label, n + V + p);
    };

    while (!heap.empty()) {
        const detail::WaveEntry e = heap.pop();
        if (e.node >= P) {  // a corner vertex: its three free pixels see it
            const std::int64_t v = e.node - P;
            if (vdone[v] || e.d != f.vertex_distance[v] || e.label != vertex_label[v]) continue;
            vdone[v] = 1;
            const std::int64_t i = v % (cols + 1), j = v / (cols + 1);
            for (int k = 0; k < 4; ++k) {
                const std::int64_t r = j - 1 + (k >> 1), c = i - 1 + (k & 1);
                if (!grid.blocked(r, c)) offer_pixel(r * cols + c, e.d + 0.7071067811865476, e.label, n + v);
            }
            // Corners that v sees but whose pixels see v only through a sliver (a path grazing a
            // wall): those along the two wall edges at v, and those within CORNER_WINDOW pixels,
            // checked exactly (corners are few: this costs little).
            for (int k = 0; k < 4; ++k) {
                const std::int64_t di = k == 0 ? 1 : k == 1 ? -1 : 0, dj = k == 2 ? 1 : k == 3 ? -1 : 0;
                std::int64_t wi = i, wj = j;
                int side = -1;
                for (;;) {  // along the grid line while the same one side is occupied (no pinch point)
                    const bool s1 = di ? grid.blocked(wj - 1, di > 0 ? wi : wi - 1) : grid.blocked(dj > 0 ? wj : wj - 1, wi - 1);
                    const bool s2 = di ? grid.blocked(wj, di > 0 ? wi : wi - 1) : grid.blocked(dj > 0 ? wj : wj - 1, wi);
                    if (s1 == s2 || (side >= 0 && side != int(s1))) break;
                    side = int(s1);
                    wi += di;
                    wj += dj;
                    if (convex(wi, wj)) {
                        offer_vertex(wi, wj, e.d + double(std::abs(wi - i) + std::abs(wj - j)), e.label, n + v);
                        break;
                    }
                }
            }
            for (std::int64_t wj = std::max<std::int64_t>(0, j - CORNER_WINDOW); wj <= std::min<std::int64_t>(rows, j + CORNER_WINDOW); ++wj)
                for (std::int64_t wi = std::max<std::int64_t>(0, i - CORNER_WINDOW); wi <= std::min<std::int64_t>(cols, i + CORNER_WINDOW); ++wi) {
                    if ((wi == i && wj == j) || !convex(wi, wj)) continue;
                    const double d = e.d + dist2d(double(wi - i), double(wj - j));
                    const std::int64_t w = wj * (cols + 1) + wi;
                    if (vdone[w] || !(d <= limit) || !better(d, e.label, f.vertex_distance[w], vertex_label[w])) continue;
                    if (segment_free(grid, {double(i), double(j)}, {double(wi), double(wj)})) offer_vertex(wi, wj, d, e.label, n + v);
                }
            continue;
        }
        const std::int64_t p = e.node;
        if (st[p].done || e.d != st[p].d || e.label != st[p].label) continue;
        st[p].done = 1;
        const std::int64_t a = st[p].anchor;
        const PixelPoint A = f.anchor_point(a);
        // a relay's distance is its pixel's (it relayed when it was taken, at that distance)
        const double Da = a >= n + V ? st[a - n - V].d : f.anchor_distance(a);
        const std::int64_t pr = p / cols, pc = p % cols;
        // First the neighbours whose line of sight to the anchor runs through p (or that hold the
        // anchor in their square), then the others: their back-trace pixel has the anchor already
        // (it offered it), or it holds another anchor or none, and then the segment is walked exactly
        // (this happens only along shadow and cell boundaries), with a relay through p if it is blocked.
        std::int64_t later[8];
        int nlater = 0;
        for (int k = 0; k < 8; ++k) {
            const std::int64_t qr = pr + DR[k], qc = pc + DC[k];
            if (grid.blocked(qr, qc)) continue;
            const bool diagonal = k >= 4;
            if (diagonal && grid.blocked(qr, pc) && grid.blocked(pr, qc)) continue;  // pinch point
            const std::int64_t q = qr * cols + qc;
            if (st[q].done && st[q].d <= e.d) continue;  // settled before p: p cannot improve it
            const std::int64_t nb = back_trace(qr, qc, A);
            if (nb == -2) {  // the anchor is in q's closed square
                offer_pixel(q, Da + dist2d(qc + 0.5 - A.u, qr + 0.5 - A.w), e.label, a);
                continue;
            }
            if (nb == -1) {
                rescue(qr, qc);
                relay(p, q, diagonal);
                continue;
            }
            const std::int64_t n2 = side_bracket(qr, qc, A);
            if (p == nb || p == n2) {
                // Both brackets see the anchor: then so does q, exactly (module comment).
                const std::int64_t other = p == nb ? n2 : nb;
                if (n2 == -1 || (other >= 0 && st[other].anchor == a)) {
                    offer_pixel(q, Da + dist2d(qc + 0.5 - A.u, qr + 0.5 - A.w), e.label, a);
                    continue;
                }
            }
            later[nlater++] = (std::int64_t(k) << 40) | nb;
        }
        for (int t = 0; t < nlater; ++t) {
            const int k = static_cast<int>(later[t] >> 40);
            const std::int64_t nb = later[t] & ((std::int64_t(1) << 40) - 1);
            if (nb != p && st[nb].anchor == a) continue;  // the exit pixel holds A: it decides when taken
            const std::int64_t qr = pr + DR[k], qc = pc + DC[k], q = qr * cols + qc;
            const PixelPoint cq{qc + 0.5, qr + 0.5};
            const double d = Da + dist2d(cq.u - A.u, cq.w - A.w);
            // a relay through p is never shorter than the straight segment: nothing to offer
            if (!(d <= limit) || !better(d, e.label, st[q].d, st[q].label)) continue;
            if (sight_free(cq, A)) {
                offer_pixel(q, d, e.label, a);
            } else {
                rescue(qr, qc);
                relay(p, q, k >= 4);
            }
        }
        // Convex corners of p that see the anchor through p become anchors.
        for (int k = 0; k < 4; ++k) {
            const std::int64_t i = pc + (k & 1), j = pr + (k >> 1);
            const std::int64_t v = j * (cols + 1) + i;
            if (vdone[v] || !convex(i, j)) continue;
            const double sx = (pc + 0.5) - double(i), sy = (pr + 0.5) - double(j);
            if ((A.u - double(i)) * sx < 0 || (A.w - double(j)) * sy < 0) continue;
            if (!sight_free({double(i), double(j)}, A)) {
                vertex_rescue(i, j);
                continue;
            }
            offer_vertex(i, j, Da + dist2d(A.u - double(i), A.w - double(j)), e.label, a);
        }
    }
    f.distance.resize(static_cast<std::size_t>(P));
    f.label.resize(static_cast<std::size_t>(P));
    f.anchor.resize(static_cast<std::size_t>(P));
    for (std::size_t q = 0; q < st.size(); ++q) {
        f.distance[q] = st[q].d;
        f.label[q] = st[q].label;
        f.anchor[q] = st[q].anchor;
    }
}

//! geodesic_field with a workspace of its own.
inline GeodesicField geodesic_field(const std::uint8_t* occ, std::int32_t rows, std::int32_t cols,
                                    const std::vector<PixelPoint>& sources,
                                    double limit = std::numeric_limits<double>::infinity()) {
    GeodesicWorkspace ws(occ, rows, cols);
    GeodesicField f;
    geodesic_field(occ, rows, cols, sources, limit, f, ws);
    return f;
}

}  // namespace dvoronoi::coverage
