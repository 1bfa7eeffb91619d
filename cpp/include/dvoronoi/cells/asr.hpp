// The exact (unlimited) Voronoi cell of one agent by Adjust-Sensing-Radius (Cortés, Martínez,
// Karataş & Bullo 2004; Section 1 and 4.1 of the Boundary Scan paper): compute the limited cell with a
// small radius, and double the radius until the cell certifies itself exact, or until every agent is
// in range — then the cell is the intersection of all half-planes, bounded or not.
//
// Schedule: the first cell radius is the nearest-neighbour distance d_1 (agents closer than 2 d_1 are
// used), then it doubles. Certificate: the limited cell V ∩ B(c, R) is a polygon (no arc) whose every
// vertex lies strictly inside the open disk of radius R; an agent not closer than 2R has its bisector
// at distance >= R from c, so it cannot cut such a polygon, and the polygon is the exact cell. Every
// decision (in range, vertex strictly inside the disk, the scans) is an exact predicate.
//
// When every agent is in range and the certificate still fails, the cell is computed without a disk:
// it is unbounded exactly when the directions to the agents leave an angular gap of at least pi
// (the agent is on the convex hull); the boundary is then a chain of edges from one ray to another,
// found by a linear stack scan over the directions after the gap; otherwise the Boundary Scan stack
// scan runs with full lines instead of chords.
#pragma once

#include "dvoronoi/cells/boundary_scan.hpp"
#include "dvoronoi/cells/certified_clip.hpp"
#include "dvoronoi/cells/clip.hpp"
#include "dvoronoi/cells/delaunay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace dvoronoi {

/// One edge of an exact Voronoi cell, counter-clockwise, shared with agent `neighbor`. An edge that
/// comes from (goes to) infinity has `start` (`end`) at the foot of its bisector, a point of its line
/// only; `direction` points along the edge, counter-clockwise around the agent.
struct VoronoiEdge {
    Index neighbor = -1;
    Vec2 start = Vec2::Zero();
    Vec2 end = Vec2::Zero();
    Vec2 direction = Vec2::Zero();  ///< unit vector along the edge, counter-clockwise around the agent
    bool from_infinity = false;     ///< the edge comes in from infinity (a ray ending at `end`)
    bool to_infinity = false;       ///< the edge goes out to infinity (a ray starting at `start`)
};

/// The exact Voronoi cell of an agent.
struct VoronoiCell {
    Vec2 center = Vec2::Zero();
    /// Counter-clockwise edges; for an unbounded cell the first comes from infinity and the last goes
    /// to infinity (a strip between parallel bisectors has two edges, each a full line).
    std::vector<VoronoiEdge> edges;
    bool on_hull = false;        ///< the cell is unbounded (the agent is on the convex hull)
    int radius_steps = 0;        ///< limited cells computed by the radius schedule
    Index agents_used = 0;       ///< agents within the final sensing radius (all of them if uncertified)
    bool is_clipped = false;     ///< `clipped` holds the cell cut to the caller's region
    ClippedCell clipped;         ///< the cell cut to the caller's region (when is_clipped)
    /// Area and centroid of the bounded cell, taken where it was built (from exact positions, to
    /// core/accurate.hpp's accuracy); NaN when unbounded.
    ClippedCell bounded;

    /// Area and centroid: of the clipped cell when clipped, else of the bounded cell; NaN for an
    /// unbounded cell that was not clipped (never an invented boundary).
    double area() const { return measures().area; }
    Vec2 centroid() const { return measures().centroid; }
    ClippedCell measures() const {
        if (is_clipped) return clipped;
        ClippedCell m;
        m.area = std::numeric_limits<double>::quiet_NaN();
        if (on_hull || edges.size() < 3) return m;
        return bounded;
    }

    /// Voronoi neighbours (cells sharing a segment of positive length), ascending.
    std::vector<Index> neighbors() const {
        std::vector<Index> out;
        for (const VoronoiEdge& e : edges) out.push_back(e.neighbor);
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }
};

/// The inner step of Adjust-Sensing-Radius: the limited cell by Boundary Scan (ASR+BS), or the
/// exact Voronoi tessellation of the agent and its current neighbours by our incremental Delaunay
/// triangulation (ASR+EVT, cells/delaunay.hpp), the baseline of the Boundary Scan paper. Auto is
/// the all-agents driver's fast path (partition/voronoi_partition.hpp); for one agent (asr_cell and
/// the steps here) it is ASR+BS.
enum class AsrInner { Auto, Scan, Evt };

namespace detail {

/// The vertices (relative to c) and measures of c's bounded cell whose Voronoi neighbours,
/// counter-clockwise, are at nb: to core/accurate.hpp's accuracy, in units of 2^e ~ the farthest
/// neighbour's distance (an exact scaling).
inline void bounded_cell(const Vec2& c, const std::vector<Vec2>& nb, std::vector<Vec2>& local, ClippedCell& m) {
    thread_local Boundary b;
    b.clear();
    const std::size_t s = nb.size();
    double far = 0.0;
    for (const Vec2& p : nb) far = std::max(far, (p - c).cwiseAbs().maxCoeff());
    const int e = far > 0.0 ? std::ilogb(far) : 0;
    const double unit = std::ldexp(1.0, -e), back = std::ldexp(1.0, e);
    for (std::size_t t = 0; t < s; ++t) {
        const Vec2 ai = (nb[(t + s - 1) % s] - c) * unit, aj = (nb[t] - c) * unit;
        b.push(line_vertex(ai.x(), ai.y(), ai.squaredNorm(), aj.x(), aj.y(), aj.squaredNorm()), false, 0.0);
    }
    b.summarize();
    const LocalMeasures lm =
        accurate_measures(b, 0.0, [&](std::size_t k) { return exact_vertex(c, nb[(k + s - 1) % s], nb[k], unit); });
    local.clear();
    for (const BoundaryPoint& q : b) local.push_back(back * q.v);
    m.area = lm.area * back * back;
    m.centroid = c + back * Vec2(lm.cx, lm.cy);
}

/// Direction of L_j, counter-clockwise around c: perp(a_j) normalised.
inline Vec2 edge_direction(const Line& l) { return Vec2(-l.a.y(), l.a.x()).normalized(); }

/// The cell from all agents, with no disk (ws.lines sorted and deduplicated by sorted_bisectors).
inline void unlimited_cell(const Vec2& c, CellWorkspace& ws, VoronoiCell& out) {
    const auto& L = ws.lines;
    const int m = static_cast<int>(L.size());
    const LineGeometry g{c, L, 0.0};
    out.edges.clear();
    out.on_hull = true;
    if (m == 0) return;
    // An angular gap of at least pi between consecutive directions: the cell is unbounded.
    int gap = -1;
    for (int t = 0; t < m && m >= 2; ++t)
        if (g.orient(t, (t + 1) % m) <= 0) {
            gap = t;
            break;
        }
    auto& st = ws.scan;
    st.clear();
    if (m == 1 || gap >= 0) {
        // Linear scan over the directions after the gap (they span at most pi): b_j between b_i and
        // b_k survives when, bounded from below by b_i and from above by b_k, its lower vertex comes
        // first. Antiparallel neighbours do not bound each other.
        for (int s = 0; s < m; ++s) {
            const int k = (gap + 1 + s) % m;
            while (st.size() >= 2) {
                const int j = st.back().line, i = st[st.size() - 2].line;
                if (g.orient(j, i) >= 0 || g.orient(j, k) <= 0 || g.vertex_before(j, i, k)) break;
                st.pop_back();
            }
            st.push_back({k, 0, true});
        }
        for (std::size_t t = 0; t < st.size(); ++t) {
            const Line& j = L[static_cast<std::size_t>(st[t].line)];
            VoronoiEdge e;
            e.neighbor = j.id;
            e.direction = edge_direction(j);
            const bool has_prev = t > 0 && g.orient(st[t - 1].line, st[t].line) > 0;
            const bool has_next = t + 1 < st.size() && g.orient(st[t].line, st[t + 1].line) > 0;
            const Vec2 foot = 0.5 * j.a;
            e.from_infinity = !has_prev;
            e.to_infinity = !has_next;
            e.start = c + (has_prev ? accurate_vertex(c, L[static_cast<std::size_t>(st[t - 1].line)].p, j.p) : foot);
            e.end = c + (has_next ? accurate_vertex(c, j.p, L[static_cast<std::size_t>(st[t + 1].line)].p) : foot);
            out.edges.push_back(e);
        }
        return;
    }
    // Bounded: the Boundary Scan stack scan with full lines (every chord bound holds), closing on the
    // nearest neighbour's bisector, which is always an edge.
    out.on_hull = false;
    st.push_back({0, 0, true});
    for (int step = 1; step <= m; ++step) {
        const int k = step % m;
        while (st.size() >= 2) {
            const ScanEntry& e = st.back();
            const int j = e.line, i = st[st.size() - 2].line;
            const int o = g.orient(j, k);
            bool keep = true;
            if (e.o_prev != 0 && o != 0 && (e.o_prev > 0) != (o > 0))
                keep = e.o_prev < 0 ? g.vertex_before(j, i, k) : g.vertex_before(j, k, i);
            if (keep) break;
            st.pop_back();
        }
        if (k != 0) st.push_back({k, g.orient(k, st.back().line), true});
    }
    const std::size_t s = st.size();
    thread_local std::vector<Vec2> nb, local;
    nb.clear();
    for (std::size_t t = 0; t < s; ++t) nb.push_back(L[static_cast<std::size_t>(st[t].line)].p);
    bounded_cell(c, nb, local, out.bounded);
    for (std::size_t t = 0; t < s; ++t) {
        const Line& j = L[static_cast<std::size_t>(st[t].line)];
        VoronoiEdge e;
        e.neighbor = j.id;
        e.direction = edge_direction(j);
        e.start = c + local[t];
        e.end = c + local[(t + 1) % s];
        out.edges.push_back(e);
    }
}

/// Edges of c's cell from its Voronoi neighbours in counter-clockwise order (an interior cycle, or a
/// hull agent's chain from its incoming to its outgoing ray); `pos(id)` gives a neighbour's position.
template <class Pos>
void edges_from_neighbors(const Vec2& c, const std::vector<Index>& nb, bool unbounded, Pos&& pos,
                          VoronoiCell& out) {
    out.edges.clear();
    const std::size_t s = nb.size();
    const auto a = [&](std::size_t t) -> Vec2 { return pos(nb[t]) - c; };  // a value, not an Eigen expression of a temporary
    thread_local std::vector<Vec2> at, local;
    const bool bounded = !unbounded && s >= 3;
    if (bounded) {
        at.clear();
        for (std::size_t t = 0; t < s; ++t) at.push_back(pos(nb[t]));
        bounded_cell(c, at, local, out.bounded);
    }
    for (std::size_t t = 0; t < s; ++t) {
        const Vec2 aj = a(t);
        VoronoiEdge e;
        e.neighbor = nb[t];
        e.direction = Vec2(-aj.y(), aj.x()).normalized();
        const bool has_prev = (!unbounded || t > 0) && s > 1 && pred::orient(c, pos(nb[(t + s - 1) % s]), pos(nb[t])) > 0;
        const bool has_next = (!unbounded || t + 1 < s) && s > 1 && pred::orient(c, pos(nb[t]), pos(nb[(t + 1) % s])) > 0;
        e.from_infinity = !has_prev;
        e.to_infinity = !has_next;
        if (bounded) {
            e.start = c + local[t];
            e.end = c + local[(t + 1) % s];
        } else {
            e.start = c + (has_prev ? accurate_vertex(c, pos(nb[(t + s - 1) % s]), pos(nb[t])) : Vec2(0.5 * aj));
            e.end = c + (has_next ? accurate_vertex(c, pos(nb[t]), pos(nb[(t + 1) % s])) : Vec2(0.5 * aj));
        }
        out.edges.push_back(e);
    }
    out.on_hull = unbounded;
}

/// The cell of c among all of `cand` (no disk), by the inner step's own means.
inline void candidate_cell(const Vec2& c, std::vector<Candidate>& cand, AsrInner inner, CellWorkspace& ws,
                           DelaunayWorkspace& dws, VoronoiCell& out) {
    // The cell's own agent: measures() works in its frame. (Before, a reused cell kept an earlier
    // center, or the origin: voronoi_cells' areas and centroids of deferred agents were then summed
    // far from the cell, losing every digit at coordinates near 1e7.)
    out.center = c;
    if (inner == AsrInner::Evt) {
        DelaunayCell dc;
        delaunay_star(c, cand, dc, dws);
        const auto pos = [&](Index id) {
            for (const Candidate& q : cand)
                if (q.id == id) return q.p;
            return c;  // not reached: neighbours are candidates
        };
        edges_from_neighbors(c, dc.neighbors, dc.on_hull, pos, out);
        return;
    }
    sorted_bisectors(c, cand, ws);
    unlimited_cell(c, ws, out);
}

/// ASR on its own: only the radius certificate (what one robot can check).
struct NoCertificate {
    static constexpr int kFromStep = std::numeric_limits<int>::max();
    int check(Index, const Vec2&, double, const VoronoiCell&, std::vector<Candidate>&) const { return -1; }
};

/// After an uncertified radius step: ask the certificate (if it applies from this step on),
/// extending the candidates while it finds agents that cut the cell. True when the cell is exact.
template <class Certificate>
bool certify_beyond_radius(Index self, const Vec2& c, double radius, AsrInner inner, const Certificate& cert,
                           CellWorkspace& ws, DelaunayWorkspace& dws, std::vector<Candidate>& cand,
                           VoronoiCell& out) {
    if (out.radius_steps < Certificate::kFromStep) return false;
    for (;;) {
        candidate_cell(c, cand, inner, ws, dws, out);
        const int verdict = cert.check(self, c, radius, out, cand);
        if (verdict > 0) {
            out.agents_used = static_cast<Index>(cand.size());
            return true;
        }
        if (verdict < 0) {
            out.edges.clear();
            out.on_hull = false;
            return false;
        }
    }
}

/// The Voronoi edge of piece t of a certified limited cell (an edge on bisector line l).
inline VoronoiEdge voronoi_edge(const LimitedCell& limited, std::size_t t, const Line& l) {
    VoronoiEdge e;
    e.neighbor = limited.pieces[t].neighbor;
    e.start = limited.pieces[t].start;
    e.end = limited.piece_end(t);
    e.direction = edge_direction(l);
    return e;
}

/// ASR's radii start at the nearest neighbour's distance and double; each is a limited cell's
/// radius, so the start must lie in [kMinRadius, kMaxRadius] (from 0, a radius that underflowed,
/// the doubling would never end). \throws RangeError otherwise.
inline void require_schedule_start(double first_radius) {
    if (first_radius >= kMinRadius && first_radius <= kMaxRadius) return;
    char got[48];
    if (first_radius == 0.0)
        std::snprintf(got, sizeof got, "closer than about 1e-154");  // its square underflowed to 0
    else if (!std::isfinite(first_radius))
        std::snprintf(got, sizeof got, "farther than about 1e154");  // its square overflowed
    else
        std::snprintf(got, sizeof got, "%.3g away", first_radius);
    throw RangeError(std::string("the nearest other agent lies ") + got +
                     ": Adjust-Sensing-Radius starts its radii at that distance, and they must lie between "
                     "1e-150 and 1e150");
}

/// Adjust-Sensing-Radius around agent `self` at c. `query(radius, cand)` fills `cand` with the agents
/// strictly within 2*radius of c (exact); `total` is the number of other agents; `first_radius`
/// starts the schedule (the nearest-neighbour distance). From radius step Certificate::kFromStep on,
/// an uncertified step also asks `cert` (see partition/empty_circle_certificate.hpp): +1 exact, 0 it
/// added candidates (recompute and ask again), -1 widen the radius. Leaves the cell in `out`.
/// `clip`, given only when the agents are pairwise distinct (the all-agents driver checks that), lets
/// the inner Boundary Scan step run through the certified clipping filter (cells/certified_clip.hpp:
/// the same cells, most of them faster).
template <class Query, class Certificate = NoCertificate>
void asr(const Vec2& c, Query&& query, Index total, double first_radius, AsrInner inner,
         CellWorkspace& ws, DelaunayWorkspace& dws, std::vector<Candidate>& cand, LimitedCell& limited,
         VoronoiCell& out, Index self = -1, const Certificate& cert = Certificate{},
         ClipWorkspace* clip = nullptr) {
    out.center = c;
    out.edges.clear();
    out.on_hull = false;
    out.radius_steps = 0;
    out.agents_used = 0;
    if (total == 0) {
        out.on_hull = true;
        return;
    }
    require_schedule_start(first_radius);
    for (double radius = first_radius;; radius *= 2.0) {
        query(radius, cand);
        ++out.radius_steps;
        out.agents_used = static_cast<Index>(cand.size());
        if (cand.empty()) continue;
        if (inner == AsrInner::Evt) {
            // The agent's cell among its current neighbours; exact when bounded with every vertex
            // strictly inside the disk of the current radius.
            DelaunayCell dc;
            delaunay_star(c, cand, dc, dws);
            const auto pos = [&](Index id) {
                for (const Candidate& q : cand)
                    if (q.id == id) return q.p;
                return c;  // not reached: neighbours are candidates
            };
            bool certified = !dc.on_hull && dc.neighbors.size() >= 3;
            for (std::size_t t = 0; certified && t < dc.neighbors.size(); ++t)
                certified = pred::vertex_in_disk(c, pos(dc.neighbors[t]),
                                                 pos(dc.neighbors[(t + 1) % dc.neighbors.size()]), radius) < 0;
            if (certified || static_cast<Index>(cand.size()) == total) {
                if (static_cast<Index>(cand.size()) < total) {
                    edges_from_neighbors(c, dc.neighbors, false, pos, out);
                    return;
                }
                query(std::numeric_limits<double>::infinity(), cand);  // every agent, as the final step
                delaunay_star(c, cand, dc, dws);
                edges_from_neighbors(c, dc.neighbors, dc.on_hull, pos, out);
                out.agents_used = static_cast<Index>(cand.size());
                return;
            }
            if (certify_beyond_radius(self, c, radius, inner, cert, ws, dws, cand, out)) return;
            if (!std::isfinite(radius * 4.0)) break;
            continue;
        }
        if (clip && certified_clip_cell(c, cand, radius, limited, *clip)) {
            if (clip->inside_disk) {  // certified: the limited cell is the whole cell
                for (std::size_t t = 0; t < limited.pieces.size(); ++t)
                    out.edges.push_back(voronoi_edge(limited, t, clip->lines[static_cast<std::size_t>(clip->cycle[t])]));
                out.bounded.area = limited.measures().area;
                out.bounded.centroid = limited.measures().centroid;
                return;
            }
            if (certify_beyond_radius(self, c, radius, inner, cert, ws, dws, cand, out)) return;
            if (static_cast<Index>(cand.size()) == total || !std::isfinite(radius * 4.0)) break;
            continue;
        }
        boundary_scan(c, cand, radius, limited, ws);
        const auto& st = ws.stack;
        const auto& meets = ws.start_is_vertex;
        const LineGeometry g{c, ws.lines, radius};
        bool certified = st.size() >= 3;
        for (std::size_t t = 0; certified && t < st.size(); ++t)
            certified = meets[t] && g.in_disk(st[t], st[(t + 1) % st.size()]) < 0;
        if (certified) {
            for (std::size_t t = 0; t < limited.pieces.size(); ++t)
                out.edges.push_back(voronoi_edge(limited, t, ws.lines[static_cast<std::size_t>(st[t])]));
            out.bounded.area = limited.measures().area;
            out.bounded.centroid = limited.measures().centroid;
            return;
        }
        if (certify_beyond_radius(self, c, radius, inner, cert, ws, dws, cand, out)) return;
        if (static_cast<Index>(cand.size()) == total || !std::isfinite(radius * 4.0)) break;
    }
    // Every agent is in range and the cell did not certify: intersect all half-planes.
    query(std::numeric_limits<double>::infinity(), cand);
    sorted_bisectors(c, cand, ws);
    unlimited_cell(c, ws, out);
    out.agents_used = static_cast<Index>(cand.size());
}

}  // namespace detail

/// The exact Voronoi cell of `center` among `others` by Adjust-Sensing-Radius with the Boundary Scan
/// limited cell (ASR+BS, default) or the exact tessellation of the current neighbours (ASR+EVT) as
/// its inner step. Edge neighbours are rows of `others`. With `bounds` (not empty), the cell is also
/// clipped to that convex region (`clipped`, and area() / centroid() measure the clipped cell).
///
/// \throws InputError for non-finite coordinates; CoincidentError when an agent of `others` lies at
///         `center` or two agents in range coincide.
/// \note Thread-safe (pure function). Each radius step is O(m_k log m_k) for the m_k agents in range
///       (selected in O(m) per step); a bounded cell needs O(log(rho / d_1)) steps, rho its farthest
///       vertex; an unbounded one ends with all m agents.
inline VoronoiCell asr_cell(const Vec2& center, PointsRef others, AsrInner inner = AsrInner::Auto,
                           const ConvexRegion& bounds = ConvexRegion()) {
    detail::require_finite_point(center, "center");
    detail::require_finite_points(others, "others");
    const Index n = others.rows();
    std::vector<detail::Candidate> all;
    all.reserve(static_cast<std::size_t>(n));
    double nearest2 = 0.0;
    for (Index j = 0; j < n; ++j) {
        const Vec2 p = others.row(j).transpose();
        if (p == center)
            throw CoincidentError("others[" + std::to_string(j) +
                                      "] coincides with center; its Voronoi cell is undefined",
                                  j, j);
        const double d2 = (p - center).squaredNorm();
        if (all.empty() || d2 < nearest2) nearest2 = d2;
        all.push_back({p, j});
    }
    const auto query = [&](double radius, std::vector<detail::Candidate>& cand) {
        cand.clear();
        for (const detail::Candidate& q : all)
            if (!(radius < std::numeric_limits<double>::infinity()) || pred::within_2r(center, q.p, radius) > 0)
                cand.push_back(q);
    };
    VoronoiCell out;
    detail::CellWorkspace ws;
    detail::DelaunayWorkspace dws;
    std::vector<detail::Candidate> cand;
    LimitedCell limited;
    detail::asr(center, query, n, std::sqrt(nearest2), inner, ws, dws, cand, limited, out);
    if (!bounds.empty()) {
        std::vector<Vec2> pos;
        std::vector<Index> ids;
        for (const VoronoiEdge& e : out.edges) {
            pos.push_back(others.row(e.neighbor).transpose());
            ids.push_back(e.neighbor);
        }
        out.clipped = clip_cell(center, pos, ids, bounds);
        out.is_clipped = true;
    }
    return out;
}

}  // namespace dvoronoi
