// DV-Hop localisation (Niculescu & Nath 2003), as the Boundary Scan paper pairs it with distributed
// cells (Section 4.2): anchors (nodes that know their position) flood their position with a hop count,
// each anchor turns the counts to the other anchors into an average hop size and floods it (a node
// passes on the first one it receives and uses the one of its nearest anchor), and every other node
// estimates its distances to the anchors as hops x hop size and its position by linear least squares
// (multilateration: the circle equations minus the last one; Eigen's column-pivoting QR, rank 2).
//
// How the floods run (DvHopOptions):
// - synchronous (default): breadth-first rounds; every node forwards each anchor's flood once, the
//   first time it hears it, which in rounds carries its minimum hop count. One broadcast per node per
//   anchor: at most n x anchors flood transmissions.
// - asynchronous: messages arrive in a seeded random order; a node keeps the smallest count per
//   anchor and passes on every improvement (many more broadcasts, the same final counts).
// - anchors_relay: whether anchors forward other anchors' floods. The Boundary Scan paper: "anchor
//   nodes will broadcast their information twice in the DV-Hop algorithm" (their position and their
//   hop size), i.e. they relay nothing; off by default. Hop counts are then the fewest hops over paths
//   whose inner nodes are normal nodes. Anchors never relay hop sizes (they use their own).
// Every broadcast is one transmission and one link delivery per neighbour (docs/spec.md).
#pragma once

#include "dvoronoi/network/network.hpp"
#include "dvoronoi/network/simulator.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <vector>

namespace dvoronoi::network {

struct DvHopOptions {
    bool synchronous = true;      ///< breadth-first rounds, each node forwards each anchor once
    bool anchors_relay = false;   ///< anchors forward other anchors' floods (the paper: they do not)
};

struct DvHopResult {
    Points estimates;                 ///< anchors: true position; others: estimate (NaN if not localised)
    std::vector<char> localized;      ///< has a position (anchors always)
    std::vector<double> hop_size;     ///< the hop size each node used (anchors: their own)
    std::vector<Index> anchors;
    TransmissionCounts counts;        ///< message types: anchor_flood, hop_size
};

/// Runs DV-Hop. Nodes with fewer than 3 reachable anchors, anchors on one line, or no hop size stay
/// unlocalised (NaN estimate, localized = 0).
///
/// \throws InputError for an anchor index out of range or repeated.
inline DvHopResult run_dv_hop(const Network& net, const std::vector<Index>& anchors, const RunOptions& run,
                              const DvHopOptions& opt = {}) {
    const Index n = net.size();
    const auto A = anchors.size();
    std::vector<Index> anchor_of(static_cast<std::size_t>(n), -1);
    for (std::size_t k = 0; k < A; ++k) {
        const Index a = anchors[k];
        if (a < 0 || a >= n) throw InputError("anchors[" + std::to_string(k) + "] = " + std::to_string(a) + " is not a node index");
        if (anchor_of[static_cast<std::size_t>(a)] >= 0) throw InputError("anchors: node " + std::to_string(a) + " is listed twice");
        anchor_of[static_cast<std::size_t>(a)] = static_cast<Index>(k);
    }
    enum : std::size_t { kFlood = 0, kHopSize = 1 };
    struct Msg {
        Index to, anchor;  // anchor: index into `anchors`
        Index hops;        // flood: hop count at the receiver
        double size;       // hop size
        std::size_t kind;
    };
    Simulator<Msg> sim(n, {"anchor_flood", "hop_size"}, run);
    constexpr Index kInf = std::numeric_limits<Index>::max();
    std::vector<Index> hops(static_cast<std::size_t>(n) * A, kInf);
    const auto H = [&](Index i, std::size_t k) -> Index& { return hops[static_cast<std::size_t>(i) * A + k]; };
    const auto broadcast = [&](Index s, const Msg& proto) {
        sim.broadcast(s, net.adj[static_cast<std::size_t>(s)], proto.kind, [&](Index t) {
            Msg m = proto;
            m.to = t;
            return m;
        });
    };
    // Does node u pass on anchor k's flood?
    const auto relays = [&](Index u, std::size_t k) {
        return opt.anchors_relay || anchor_of[static_cast<std::size_t>(u)] < 0 || anchors[k] == u;
    };
    // Phase 1: anchor positions with hop counts.
    if (opt.synchronous) {
        std::vector<Index> frontier, next;
        for (std::size_t k = 0; k < A; ++k) {
            H(anchors[k], k) = 0;
            frontier.assign(1, anchors[k]);
            while (!frontier.empty()) {  // one round: the nodes that first heard the flood last round
                next.clear();
                for (Index u : frontier) {
                    if (!relays(u, k)) continue;
                    sim.count_broadcast(u, net.adj[static_cast<std::size_t>(u)], kFlood);
                    for (Index t : net.adj[static_cast<std::size_t>(u)])
                        if (H(t, k) == kInf) {
                            H(t, k) = H(u, k) + 1;
                            next.push_back(t);
                        }
                }
                frontier.swap(next);
            }
        }
    } else {
        for (std::size_t k = 0; k < A; ++k) {
            H(anchors[k], k) = 0;
            broadcast(anchors[k], Msg{-1, static_cast<Index>(k), 1, 0.0, kFlood});
        }
        sim.run([&](const Msg& m) {
            Index& h = H(m.to, static_cast<std::size_t>(m.anchor));
            if (m.hops >= h) return;
            h = m.hops;
            if (relays(m.to, static_cast<std::size_t>(m.anchor))) broadcast(m.to, Msg{-1, m.anchor, m.hops + 1, 0.0, kFlood});
        });
    }
    // Phase 2: each anchor's average hop size, flooded; a node passes on the first one only.
    DvHopResult res;
    res.anchors = anchors;
    res.hop_size.assign(static_cast<std::size_t>(n), std::nan(""));
    std::vector<Index> size_from(static_cast<std::size_t>(n), -1);
    for (std::size_t k = 0; k < A; ++k) {
        const Index a = anchors[k];
        double dist = 0.0;
        Index h = 0;
        for (std::size_t l = 0; l < A; ++l)
            if (l != k && H(a, l) != kInf) {
                dist += (net.pos(a) - net.pos(anchors[l])).norm();
                h += H(a, l);
            }
        if (h == 0) continue;
        const double size = dist / static_cast<double>(h);
        res.hop_size[static_cast<std::size_t>(a)] = size;
        size_from[static_cast<std::size_t>(a)] = static_cast<Index>(k);
        broadcast(a, Msg{-1, static_cast<Index>(k), 0, size, kHopSize});
    }
    std::vector<char> forwarded(static_cast<std::size_t>(n), 0);
    // A normal node takes the hop size of the nearest anchor heard from (fewest hops, then lowest
    // index); returns whether it hears one for the first time (it then passes one on, once).
    const auto hear = [&](const Msg& m) {
        const auto t = static_cast<std::size_t>(m.to);
        if (anchor_of[t] >= 0) return false;
        const Index cur = size_from[t];
        const auto k = static_cast<std::size_t>(m.anchor);
        if (cur < 0 || H(m.to, k) < H(m.to, static_cast<std::size_t>(cur)) ||
            (H(m.to, k) == H(m.to, static_cast<std::size_t>(cur)) && m.anchor < cur)) {
            size_from[t] = m.anchor;
            res.hop_size[t] = m.size;
        }
        if (forwarded[t]) return false;
        forwarded[t] = 1;
        return true;
    };
    if (opt.synchronous) {
        // Rounds: the broadcasts of one round are delivered, then the nodes that first heard a hop
        // size pass on the one they hold (the same one as in the asynchronous case when one anchor is
        // nearest; ties within a round go to the lowest anchor index).
        std::vector<Msg> round;
        sim.run([&](const Msg& m) { round.push_back(m); });  // the anchors' own broadcasts
        while (!round.empty()) {
            std::vector<Index> first;
            for (const Msg& m : round)
                if (hear(m)) first.push_back(m.to);
            round.clear();
            for (Index u : first) {
                const auto uu = static_cast<std::size_t>(u);
                broadcast(u, Msg{-1, size_from[uu], 0, res.hop_size[uu], kHopSize});
            }
            sim.run([&](const Msg& m) { round.push_back(m); });
        }
    } else {
        sim.run([&](const Msg& m) {
            if (hear(m)) broadcast(m.to, Msg{-1, m.anchor, 0, m.size, kHopSize});
        });
    }
    // Multilateration.
    res.estimates = Points::Constant(n, 2, std::nan(""));
    res.localized.assign(static_cast<std::size_t>(n), 0);
    for (Index i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        if (anchor_of[ii] >= 0) {
            res.estimates.row(i) = net.points.row(i);
            res.localized[ii] = 1;
            continue;
        }
        if (!(res.hop_size[ii] > 0.0)) continue;
        std::vector<std::size_t> use;
        for (std::size_t k = 0; k < A; ++k)
            if (H(i, k) != kInf) use.push_back(k);
        if (use.size() < 3) continue;
        const std::size_t m = use.size() - 1;
        const Vec2 last = net.pos(anchors[use[m]]);
        const double dl = res.hop_size[ii] * static_cast<double>(H(i, use[m]));
        Eigen::MatrixXd M(static_cast<Eigen::Index>(m), 2);
        Eigen::VectorXd b(static_cast<Eigen::Index>(m));
        for (std::size_t r = 0; r < m; ++r) {
            const Vec2 a = net.pos(anchors[use[r]]);
            const double d = res.hop_size[ii] * static_cast<double>(H(i, use[r]));
            const auto row = static_cast<Eigen::Index>(r);
            M(row, 0) = 2.0 * (last.x() - a.x());
            M(row, 1) = 2.0 * (last.y() - a.y());
            b(row) = d * d - dl * dl - a.squaredNorm() + last.squaredNorm();
        }
        const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(M);
        if (qr.rank() < 2) continue;
        const Eigen::Vector2d x = qr.solve(b);
        if (!std::isfinite(x.x()) || !std::isfinite(x.y())) continue;
        res.estimates.row(i) = x.transpose();
        res.localized[ii] = 1;
    }
    res.counts = sim.counts();
    return res;
}

}  // namespace dvoronoi::network
