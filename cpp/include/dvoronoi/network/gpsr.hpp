// GPSR (Karp & Kung 2000): greedy forwarding on the communication graph, perimeter (face) routing on
// its Gabriel subgraph where greedy is stuck, delivering a packet addressed to a point to the node
// nearest that point (GHT's "home node": when the perimeter walk completes a tour of the face that
// contains the point, the packet goes to the node of that face nearest the point). Addressed to a
// node's own position, the packet reaches that node whenever the planar graph is connected.
//
// Angular order around a node (the right-hand rule) and edge crossings use exact orientation signs.
// Distances to the target are compared in floating point: a probed target is itself a rounded
// Voronoi vertex, equidistant from three nodes up to rounding, so an exact comparison would decide
// nothing more (and would fall back to slow exact arithmetic at nearly every probe); the face-change
// test compares the constructed crossing point with the previous one in floating point too.
#pragma once

#include "dvoronoi/network/network.hpp"

#include <algorithm>
#include <vector>

namespace dvoronoi::network {

class Gpsr {
public:
    explicit Gpsr(const Network& net) : net_(net), planar_(gabriel_graph(net)) {
        Index directed = 0;
        for (const auto& a : planar_) directed += static_cast<Index>(a.size());
        hop_limit_ = 4 * directed + 4 * net.size() + 16;
        // Each node's planar neighbours in counter-clockwise order (exact angular comparison), so
        // the right-hand rule's next edge is a lookup.
        ring_.resize(planar_.size());
        for (std::size_t c = 0; c < planar_.size(); ++c) {
            auto& r = ring_[c];
            r = planar_[c];
            if (r.size() < 2) continue;
            const Vec2 pc = pos(static_cast<Index>(c));
            const Vec2 ref = pos(r[0]);
            std::sort(r.begin(), r.end(), [&](Index a, Index b) {
                const int sa = sector(pc, ref, pos(a), true), sb = sector(pc, ref, pos(b), true);
                if (sa != sb) return sa < sb;
                return (sa == 1 || sa == 3) && pred::orient(pc, pos(a), pos(b)) > 0;
            });
        }
    }

    const std::vector<std::vector<Index>>& planar() const { return planar_; }

    /// Routes from `source` towards the point `target`. `path` receives the nodes visited (source
    /// first, the receiver last; consecutive nodes are linked). Returns false when the hop limit was
    /// hit (possible only on non-planar graphs, i.e. with obstacles); the packet is then lost.
    bool route(Index source, const Vec2& target, std::vector<Index>& path) const {
        path.assign(1, source);
        Index cur = source, prev = -1;
        bool greedy = true;
        Vec2 lp = Vec2::Zero(), lf = Vec2::Zero();
        Index lp_node = -1, best = -1, e0_from = -1, e0_to = -1;
        for (Index hops = 0; hops < hop_limit_; ++hops) {
            if (pos(cur) == target) return true;
            Index nxt = -1;
            if (greedy) {
                double dbest = dist2(cur, target);
                for (Index w : net_.adj[static_cast<std::size_t>(cur)]) {
                    const double d = dist2(w, target);
                    if (d < dbest) nxt = w, dbest = d;
                }
                if (nxt < 0) {
                    // Local minimum: perimeter mode, starting on the face the ray cur -> target enters.
                    if (planar_[static_cast<std::size_t>(cur)].empty()) return true;
                    greedy = false;
                    lp_node = cur;
                    lp = lf = pos(cur);
                    best = cur;
                    nxt = next_ccw(cur, target, true);
                    bool changed = false;
                    nxt = face_change(cur, nxt, lp, target, lf, changed);
                    e0_from = cur, e0_to = nxt;
                }
            } else {
                // The next edge counter-clockwise from the one the packet came in on.
                nxt = next_after(cur, prev);
                bool changed = false;
                nxt = face_change(cur, nxt, lp, target, lf, changed);
                if (changed) {
                    e0_from = cur, e0_to = nxt;
                    best = cur;
                } else if (cur == e0_from && nxt == e0_to) {
                    // A full tour of the face that holds the target: deliver to the face's node nearest
                    // the target, walking on along the same face.
                    for (Index guard = 0; cur != best && guard < hop_limit_; ++guard) {
                        path.push_back(nxt);
                        prev = cur;
                        cur = nxt;
                        nxt = next_after(cur, prev);
                    }
                    return cur == best;
                }
            }
            path.push_back(nxt);
            prev = cur;
            cur = nxt;
            if (!greedy) {
                if (closer(cur, best, target)) best = cur;
                if (dist2(cur, target) < dist2(lp_node, target)) greedy = true;
            }
        }
        return false;
    }

private:
    Vec2 pos(Index i) const { return net_.pos(i); }

    double dist2(Index a, const Vec2& t) const { return (net_.points.row(a).transpose() - t).squaredNorm(); }
    /// Nearer to t, ties to the lower index.
    bool closer(Index a, Index b, const Vec2& t) const {
        const double da = dist2(a, t), db = dist2(b, t);
        return da < db || (da == db && a < b);
    }

    /// Sector of the direction c -> a, counter-clockwise from the direction c -> r: 0 on the ray
    /// itself (or 4 when `zero_first` is false: the edge we came in on is taken last), 1 left of it,
    /// 2 opposite, 3 right.
    static int sector(const Vec2& c, const Vec2& r, const Vec2& a, bool zero_first) {
        const int o = pred::orient(c, r, a);
        if (o > 0) return 1;
        if (o < 0) return 3;
        return pred::dot_sign(c, r, a) > 0 ? (zero_first ? 0 : 4) : 2;
    }

    /// The planar neighbour of c next counter-clockwise after its neighbour `from` (from itself when
    /// it is the only one).
    Index next_after(Index c, Index from) const {
        const auto& r = ring_[static_cast<std::size_t>(c)];
        const std::size_t k = static_cast<std::size_t>(std::find(r.begin(), r.end(), from) - r.begin());
        return r[(k + 1) % r.size()];
    }

    /// The planar neighbour of c first counter-clockwise from the direction c -> r.
    Index next_ccw(Index c, const Vec2& r, bool zero_first) const {
        const Vec2 pc = pos(c);
        Index best = -1;
        int best_s = 5;
        for (Index w : planar_[static_cast<std::size_t>(c)]) {
            const int s = sector(pc, r, pos(w), zero_first);
            if (best < 0 || s < best_s || (s == best_s && (s == 1 || s == 3) && pred::orient(pc, pos(best), pos(w)) < 0)) {
                best = w;
                best_s = s;
            }
        }
        return best;
    }

    /// GPSR's face change: while the edge c -> nxt crosses the segment lp -> target at a point closer
    /// to the target than lf, move lf there and take the next edge counter-clockwise about c.
    Index face_change(Index c, Index nxt, const Vec2& lp, const Vec2& target, Vec2& lf, bool& changed) const {
        const std::size_t deg = planar_[static_cast<std::size_t>(c)].size();
        for (std::size_t guard = 0; guard < deg; ++guard) {
            const Vec2 a = pos(c), b = pos(nxt);
            // Disjoint bounding boxes: no crossing (spares the orientation tests on most hops).
            if (std::max(a.x(), b.x()) < std::min(lp.x(), target.x()) || std::min(a.x(), b.x()) > std::max(lp.x(), target.x()) ||
                std::max(a.y(), b.y()) < std::min(lp.y(), target.y()) || std::min(a.y(), b.y()) > std::max(lp.y(), target.y()))
                break;
            const int o1 = pred::orient(lp, target, a), o2 = pred::orient(lp, target, b);
            const int o3 = pred::orient(a, b, lp), o4 = pred::orient(a, b, target);
            if (!(o1 * o2 < 0 && o3 * o4 < 0)) break;
            // Proper crossing: the crossing point, in floating point.
            const Vec2 d = b - a, e = target - lp;
            const double den = d.x() * e.y() - d.y() * e.x();
            const double t = ((lp.x() - a.x()) * e.y() - (lp.y() - a.y()) * e.x()) / den;
            const Vec2 x = a + t * d;
            if (!((x - target).squaredNorm() < (lf - target).squaredNorm())) break;
            lf = x;
            changed = true;
            nxt = next_after(c, nxt);
        }
        return nxt;
    }

    const Network& net_;
    std::vector<std::vector<Index>> planar_;
    std::vector<std::vector<Index>> ring_;
    Index hop_limit_ = 0;
};

}  // namespace dvoronoi::network
