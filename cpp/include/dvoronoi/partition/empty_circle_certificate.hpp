// A second certificate for the exact cell of one agent when every agent's position is at hand (the
// all-agents driver): a candidate cell U, computed from a candidate set that holds every agent
// strictly within 2R, is the exact Voronoi cell when
//   - every vertex of U lies strictly inside the disk of radius R (ASR's own certificate), or its
//     circle (through the agent and the two neighbours that meet there) holds no agent strictly
//     inside — checked with a grid query over the part of the circle that meets the agents and the
//     exact incircle predicate;
//   - U is bounded, or the agent lies on the global convex hull and the candidates hold its
//     neighbours along the hull boundary (and one agent off the line when it lies inside a hull
//     edge): they generate the cone, seen from the agent, that holds every agent, so no agent can
//     cut U at infinity.
// Why it is enough: an agent q cuts U exactly when the open half-plane of points closer to q meets
// U; on U = conv(vertices) + recession cone, the distance difference is affine and does not decrease
// along the cone's directions (q lies in the cone above), so it is smallest at a vertex.
//
// Why: agents near the hull have cells with very far vertices (huge Delaunay circles), so ASR's
// doubling radius would sweep most of the agents for each of them (O(n^1.5) at 1e6 uniform agents);
// an empty circle that only grazes the point set is checked in a few grid columns instead.
#pragma once

#include "dvoronoi/cells/asr.hpp"
#include "dvoronoi/core/convex_hull.hpp"
#include "dvoronoi/core/grid_index.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace dvoronoi::detail {

class EmptyCircleCertificate {
public:
    /// Radius steps ASR takes on its own before this certificate is tried.
    static constexpr int kFromStep = 3;
    /// More agents than this inside the vertex circles: give up on this step and widen the radius.
    static constexpr std::size_t kMaxAdded = 32;

    EmptyCircleCertificate(const Points& pts, const GridIndex& index, const ConvexHull& hull)
        : pts_(pts), index_(index), hull_(hull) {}

    enum Verdict { kExact = 1, kExtended = 0, kWiden = -1 };

    /// Checks `cell` (agent i at c, from `cand`, which holds every agent strictly within 2*radius).
    /// kExact: the cell is exact. kExtended: agents that cut the cell (or that the hull certificate
    /// needs) were appended to `cand`; recompute and ask again. kWiden: undecided here (an interior
    /// agent with an unbounded candidate cell, or a vertex too ill-conditioned to locate); widen
    /// the radius.
    Verdict check(Index i, const Vec2& c, double radius, const VoronoiCell& cell,
                  std::vector<Candidate>& cand) const {
        const std::size_t before = cand.size();
        if (cell.on_hull && !hull_.on_boundary(i)) {
            // An interior agent whose candidate cell is still open: the hull corners farthest in the
            // open directions cut it at infinity (one that does not only means a wider radius).
            if (cell.edges.empty()) return kWiden;
            const VoronoiEdge& first = cell.edges.front();
            const VoronoiEdge& last = cell.edges.back();
            const Vec2 d1 = -first.direction, d2 = last.direction;
            Vec2 mid = d1 + d2;
            if (!(mid.squaredNorm() > 1e-6)) mid = c - at(first.neighbor);
            for (const Vec2& d : {d1, d2, mid}) {
                const Index q = hull_.extreme(d, pts_);
                if (q != i && d.dot(at(q) - c) > 0.0) require(q, cand);
            }
            return cand.size() != before ? kExtended : kWiden;
        }
        if (cell.on_hull) {
            require(hull_.prev(i), cand);
            require(hull_.next(i), cand);
            const Vec2 pp = at(hull_.prev(i)), pn = at(hull_.next(i));
            if (hull_.prev(i) != hull_.next(i) && pred::orient(pp, c, pn) == 0)
                for (Index w : hull_.witnesses())
                    if (pred::orient(pp, pn, at(w)) != 0) {
                        require(w, cand);
                        break;
                    }
            if (cand.size() != before) return kExtended;
        }
        const std::size_t s = cell.edges.size();
        for (std::size_t t = 0; t < s; ++t) {
            const VoronoiEdge& e = cell.edges[t];
            if (e.to_infinity || (cell.on_hull && t + 1 == s)) continue;
            const Vec2 pj = at(e.neighbor), pk = at(cell.edges[(t + 1) % s].neighbor);
            if (pred::vertex_in_disk(c, pj, pk, radius) < 0) continue;  // every agent that matters is in cand
            Vec2 center;
            double rho;
            if (!circle(c, pj, pk, center, rho)) return kWiden;
            const int o = pred::orient(c, pj, pk);
            const bool complete = index_.for_each_in_disk(center, rho, [&](const Vec2& q, Index id) {
                if (id != i && o * pred::incircle(c, pj, pk, q) > 0) cand.push_back({q, id});
                return cand.size() - before <= kMaxAdded;
            });
            // Many agents inside: the candidates are far from the cell (a vertex pushed out by a gap
            // in the candidates, not a real far vertex); the next radius step is cheaper.
            if (!complete) {
                cand.resize(before);
                return kWiden;
            }
        }
        if (cand.size() == before) return kExact;
        dedupe(cand, before);
        return kExtended;
    }

private:
    Vec2 at(Index j) const { return Vec2(pts_(j, 0), pts_(j, 1)); }

    void require(Index j, std::vector<Candidate>& cand) const {
        for (const Candidate& q : cand)
            if (q.id == j) return;
        cand.push_back({at(j), j});
    }

    /// Several vertex circles may report the same agent; keep one copy of each new candidate.
    static void dedupe(std::vector<Candidate>& cand, std::size_t from) {
        std::sort(cand.begin() + static_cast<std::ptrdiff_t>(from), cand.end(),
                  [](const Candidate& a, const Candidate& b) { return a.id < b.id; });
        cand.erase(std::unique(cand.begin() + static_cast<std::ptrdiff_t>(from), cand.end(),
                               [](const Candidate& a, const Candidate& b) { return a.id == b.id; }),
                   cand.end());
    }

    /// A disk that contains the circle through c, pj, pk (their circumcircle computed in doubles,
    /// enlarged by a bound on its rounding error). False when the bound is not small against the
    /// radius (nearly collinear points), so the caller falls back on the radius schedule.
    static bool circle(const Vec2& c, const Vec2& pj, const Vec2& pk, Vec2& center, double& rho) {
        const Vec2 a = pj - c, b = pk - c;
        const double d = a.x() * b.y() - a.y() * b.x();
        const double la = a.norm(), lb = b.norm();
        const Vec2 v = vertex(a, b);
        const double r = v.norm();
        // First-order forward error of v = (|a|^2 perp(b) - |b|^2 perp(a)) / (2 cross(a, b)) with a and
        // b rounded: |dv| <= 4u (|a|^2|b| + |b|^2|a|) / |D| + 6u |v| |a||b| / |D| (u = 2^-53); taken
        // 16 times over; plus the rounding of c + v.
        const double u = std::ldexp(1.0, -53);
        const double err = 16.0 * u * (4.0 * (la * la * lb + lb * lb * la) + 6.0 * r * la * lb) / std::abs(d) +
                           4.0 * u * (std::abs(c.x()) + std::abs(c.y()) + r);
        if (!(err <= 1e-3 * r) || !std::isfinite(r)) return false;
        center = c + v;
        rho = (r + 2.0 * err) * (1.0 + 1e-12);
        return true;
    }

    const Points& pts_;
    const GridIndex& index_;
    const ConvexHull& hull_;
};

}  // namespace dvoronoi::detail
