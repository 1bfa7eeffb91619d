// Coverage control on limited cells (Cortés, Martínez & Bullo, "Spatially-distributed coverage
// optimization and control with limited-range interactions", ESAIM COCV 11, 2005).
//
// Cost (minimised; the negative of the paper's H_{R} with performance f(x) = -min(x, R)^2):
//     H(P) = ∫_Q min(min_i |q - p_i|^2, R^2) φ(q) dq
//          = Σ_i ∫_{W_i} |q - p_i|^2 φ  +  R^2 Φ(Q \ ∪_i B(p_i, R)),     W_i = V_i ∩ B(p_i, R) ∩ Q,
// and since the W_i tile Q ∩ ∪ B(p_i, R):  H(P) = R^2 Φ(Q) + Σ_i (J_i - R^2 M_i), with M_i = ∫_{W_i} φ
// and J_i = ∫_{W_i} |q - p_i|^2 φ. Its gradient is ∂H/∂p_i = 2 M_i (p_i - C_i), C_i the centroid of
// W_i. The discrete law p_i <- p_i + g (C_i - p_i), 0 < g <= 1, never increases H: with the cells W
// fixed, Σ ∫_{W_i} |q - p_i|^2 φ = Σ (∫_{W_i} |q - C_i|^2 φ + M_i |p_i - C_i|^2) drops (|p_i' - C_i|
// = (1 - g)|p_i - C_i|), and re-assigning each q to its nearest agent (capped at R^2) can only lower it
// further. Without an environment (Q = the plane) the constant R^2 Φ(Q) is left out: the reported
// cost is Σ_i (J_i - R^2 M_i) <= 0 (each term at most half the size of R^2 M_i: nothing cancels).
//
// With an environment the cost is summed as H = Σ_i J_i + R^2 Φ(U), U = Q \ ∪ B(p_i, R) the uncovered
// part, never as the difference of R^2 Φ(Q) and Σ R^2 M_i: those agree to ~1e-16 R^2 Φ(Q), which at
// R = 1e6 in a unit square is 100 times H itself. U is empty exactly when no clipped cell reaches its
// circle (an arc of W_i inside Q borders U; U's boundary inside Q is made of such arcs), always once R
// exceeds Q's diameter: then H = Σ J_i, positive terms. Otherwise Φ(U) = Φ(Q) - Σ M_i (compensated
// sum), whose rounding of ~1e-16 R^2 Φ(Q) is small against H since some point of Q is then R away
// from every agent: for uniform density H >= R^4 |Q| / (16 D^2), D the diameter of Q, so the
// relative error stays below ~1e-14 (D/R)^2, and near 1e-16 wherever most of Q is uncovered.
//
// Agents stay in Q: W_i ⊂ Q is convex and so contains C_i, and Q contains the segment from p_i to
// C_i. A move that rounding puts a hair outside Q is shortened (halved until inside, exactly tested).
//
// Heterogeneous teams (a sensing radius R_i per agent; Pimenta, Kumar, Mesquita & Pereira, "Sensing
// and coverage for a network of heterogeneous robots", CDC 2008): the cells are the power cells
// (weights R_i^2) clipped to the disks and to Q, W_i = {q in B(p_i, R_i) ∩ Q : pow_i(q) <= pow_j(q)
// for all j}, pow_i(q) = |q - p_i|^2 - R_i^2 (docs/spec.md), and the cost is Pimenta et al.'s power
// cost Σ_i ∫ pow_i φ over the power cells, limited to the disks as above (a point no disk covers
// costs as much as one on the rim of the largest disk), with R̄ = max R_i:
//     H(P) = ∫_Q min(min_i pow_i(q), 0) φ(q) dq + R̄^2 Φ(Q)
//          = Σ_i (J_i + (R̄^2 - R_i^2) M_i) + R̄^2 Φ(U)            (every term >= 0; plane: Σ_i (J_i - R_i^2 M_i)).
// Equal radii give the cost above exactly (and the same cells: the Boundary Scan path is kept then).
// The gradient is still ∂H/∂p_i = 2 M_i (p_i - C_i): moving p_i moves the boundaries of W_i, but the
// integrand is continuous across each of them (pow_i = pow_j on a power edge, pow_i = 0 = the
// uncovered value on an arc), so their terms cancel and only ∫_{W_i} 2 (p_i - q) φ remains. The same
// step never increases H: with the cells fixed, Σ ∫_{W_i} (|q - p_i|^2 - R_i^2) φ drops by M_i (1 -
// (1-g)^2) |p_i - C_i|^2 per agent, and for any partition (W_i and the rest) that sum plus the rest at
// 0 is at least ∫ min(min_i pow_i, 0) φ at the new positions. C_i lies in the convex W_i ⊂ Q even when
// p_i does not (a larger disk's power can win at p_i), so agents still stay in Q.
#pragma once

#include "dvoronoi/cells/boundary_scan.hpp"
#include "dvoronoi/cells/power_cell.hpp"
#include "dvoronoi/coverage/cell_moments.hpp"
#include "dvoronoi/coverage/clip.hpp"
#include "dvoronoi/coverage/environment.hpp"
#include "dvoronoi/partition/limited_partition.hpp"
#include "dvoronoi/partition/swarm.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace dvoronoi {

namespace detail {

/// Per-thread scratch of the coverage computations.
struct CoverageWorkspace {
    std::vector<Candidate> cand, edges;
    std::vector<Index> same;
    LimitedCell cell;
    CellWorkspace ws;
    PowerWorkspace power;
    std::vector<double> cand_r, shift;
    std::vector<Piece> local, clipped, scratch;
    double radius = 0.0;  ///< the radius of the agent whose cell `clipped` is
};

}  // namespace detail

/// Per-agent sensing radii of a swarm (heterogeneous teams, docs/spec.md); empty (equal()) when every
/// agent has the swarm's radius. With unequal radii the swarm's radius is the largest, R̄, so that
/// Swarm::within (agents closer than 2 R̄) returns every agent that can shape a cell (closer than
/// R_i + R_j). Radii are looked up by row and, for the candidates Swarm::within returns, by id.
class AgentRadii {
public:
    AgentRadii() = default;

    /// `radii[k]` for the swarm's row k. Radii all equal to the swarm's radius give equal().
    /// \throws InputError naming `radius` for a wrong length, a bad radius or one above the swarm's.
    AgentRadii(const Swarm& swarm, std::vector<double> radii) {
        const Index n = swarm.size();
        if (static_cast<Index>(radii.size()) != n)
            throw InputError("radius must have one radius per agent: got " + std::to_string(radii.size()) +
                             " radii for " + std::to_string(n) + " agents");
        bool equal = true;
        for (std::size_t k = 0; k < radii.size(); ++k) {
            const double R = radii[k];
            detail::require_finite_radius(R, ("radius[" + std::to_string(k) + "]").c_str());
            if (R > swarm.radius())
                throw InputError("radius[" + std::to_string(k) + "] exceeds the swarm's largest radius " +
                                 std::to_string(swarm.radius()));
            equal &= R == swarm.radius();
        }
        if (equal) return;
        by_row_ = std::move(radii);
        const std::vector<Index>& ids = swarm.ids();
        identity_ = true;
        for (Index k = 0; k < n; ++k) identity_ &= ids[static_cast<std::size_t>(k)] == k;
        if (identity_) return;
        for (Index k = 0; k < n; ++k) by_id_.push_back({ids[static_cast<std::size_t>(k)], by_row_[static_cast<std::size_t>(k)]});
        std::sort(by_id_.begin(), by_id_.end());
    }

    bool equal() const noexcept { return by_row_.empty(); }
    /// Radii by row (empty when equal()).
    const std::vector<double>& by_row() const noexcept { return by_row_; }
    double of_row(const Swarm& swarm, Index k) const {
        return equal() ? swarm.radius() : by_row_[static_cast<std::size_t>(k)];
    }
    double of_id(const Swarm& swarm, Index id) const {
        if (equal()) return swarm.radius();
        if (identity_) return by_row_[static_cast<std::size_t>(id)];
        const auto it = std::lower_bound(by_id_.begin(), by_id_.end(), std::pair<Index, double>{id, -1.0});
        return it->second;
    }

private:
    std::vector<double> by_row_;
    std::vector<std::pair<Index, double>> by_id_;  // (id, radius) sorted, when ids are not the rows
    bool identity_ = true;
};

namespace detail {

/// Agent i's cell W_i relative to its position, into w.clipped (its radius into w.radius). Throws
/// CoincidentError (global ids) when another agent sits at the same position (with unequal radii:
/// at the same position with the same radius; the larger disk holds a shared position).
inline void clipped_local_cell(const Swarm& swarm, const AgentRadii& radii, Index i, const ConvexPolygon* env,
                               CoverageWorkspace& w) {
    w.same.clear();
    swarm.within(i, w.cand, &w.same);
    const Index id = swarm.ids()[static_cast<std::size_t>(i)];
    const Vec2 c = swarm.point(i);
    if (radii.equal()) {
        if (!w.same.empty()) {
            const Index j = *std::min_element(w.same.begin(), w.same.end());
            const Index a = std::min(id, j), b = std::max(id, j);
            throw CoincidentError("points[" + std::to_string(a) + "] and points[" + std::to_string(b) +
                                      "] coincide; their Voronoi cells are undefined",
                                  a, b);
        }
        w.radius = swarm.radius();
        boundary_scan(c, w.cand, w.radius, w.cell, w.ws);
    } else {
        // The power cell from the agents closer than R_i + R_j (the grid returns those within 2 R̄;
        // the margin keeps every one that can matter, and the exact classification in power_cell
        // drops the extras). Agents at p_i join them (the larger disk holds a shared position); the
        // candidates stay sorted by id.
        w.radius = radii.of_row(swarm, i);
        std::size_t kept = 0;
        w.cand_r.clear();
        for (const Candidate& q : w.cand) {
            const double Rj = radii.of_id(swarm, q.id), reach = (w.radius + Rj) * (1.0 + 0x1p-40);
            if ((q.p - c).squaredNorm() >= reach * reach) continue;
            w.cand[kept++] = q;
            w.cand_r.push_back(Rj);
        }
        w.cand.resize(kept);
        for (const Index j : w.same) {  // in id order, as the rest
            const auto at = std::lower_bound(w.cand.begin(), w.cand.end(), j,
                                             [](const Candidate& a, Index want) { return a.id < want; });
            w.cand_r.insert(w.cand_r.begin() + (at - w.cand.begin()), radii.of_id(swarm, j));
            w.cand.insert(at, {c, j});
        }
        power_cell(c, w.radius, w.cand, w.cand_r, w.cell, w.power, id);
    }
    const double R = w.radius;
    if (env && disk_holds(*env, c, R)) {
        // The disk holds Q, so W_i = (power) cell ∩ Q: Q cut by the edge neighbours' bisectors (radical
        // axes), without the arcs far outside Q (R may be 1e9 |Q|) that cutting the cell would construct.
        w.edges.clear();
        w.shift.clear();
        if (w.cell.pieces.empty()) {  // an empty power cell: the power of a larger disk wins everywhere
            w.clipped.clear();
            return;
        }
        for (const Piece& p : w.cell.pieces) {
            if (p.neighbor < 0) continue;
            const auto it = std::lower_bound(w.cand.begin(), w.cand.end(), p.neighbor,
                                             [](const Candidate& a, Index want) { return a.id < want; });
            w.edges.push_back({it->p - c, p.neighbor});  // candidates are sorted by id (Swarm::within)
            if (!radii.equal()) w.shift.push_back(R * R - w.cand_r[static_cast<std::size_t>(it - w.cand.begin())]);
        }
        clip_environment(*env, c, w.edges, w.clipped, w.scratch, radii.equal() ? nullptr : &w.shift);
        return;
    }
    w.local = w.cell.pieces;
    for (Piece& p : w.local) p.start -= c;
    if (env)
        clip_cell(w.local, c, R, *env, w.clipped, w.scratch);
    else
        w.clipped.swap(w.local);
}

/// The cost's polar moments grow as R^4 (a lone agent's is pi R^4 / 2): \throws RangeError unless
/// 1e-75 <= radius <= 1e75, where R^4 is a normal double.
inline void require_moment_radius(double radius) {
    require_radius_range(radius, 1e-75, 1e75, "radius", "coverage: the cells' polar moments, ~R^4, must be normal doubles");
}

/// Runs f(i, workspace) for agents 0..count-1 on an OpenMP team; results must be written per agent
/// (so they do not depend on the team). The first failure in agent order is rethrown after the loop.
template <class F>
void for_each_agent(Index count, int threads, const ProgressFn& progress, F&& f) {
    const int team = thread_team(threads, block_count(count));
    ProgressTracker tracker(progress, count);
    for_each_block(
        count, team, tracker, [](int) { return CoverageWorkspace(); }, [&](CoverageWorkspace& w, Index i) { f(i, w); },
        [](Index i) { return i; });
    tracker.report_all();
}

}  // namespace detail

/// Does the clipped cell reach its circle inside the environment (has it an arc)? Then the disks
/// leave part of Q uncovered (see the top of this file).
inline bool reaches_circle(const std::vector<Piece>& clipped) {
    for (const Piece& p : clipped)
        if (p.neighbor == kArc) return true;
    return false;
}

/// The cost H (top of this file) from per-agent moments M_i (`mass`), J_i (`polar`) and whether W_i
/// reaches its circle (`open`), summed without cancellation: `total` = Φ(Q), or nullptr for the plane
/// (then Σ_i (J_i - R_i^2 M_i)). With an environment H = Σ (J_i + (R̄^2 - R_i^2) M_i) + R̄^2 Φ(U): Φ(U)
/// = 0 when there are agents and no cell is open, else Φ(Q) - Σ M_i by a compensated sum (at least 0).
/// `radius` is R̄ (every agent's radius when `radii` is null or empty), `radii` R_i per agent.
inline double coverage_cost(const std::vector<double>& mass, const std::vector<double>& polar,
                            const std::vector<char>& open, double radius, const double* total,
                            const std::vector<double>* radii = nullptr) {
    const double r2 = radius * radius;
    const bool each = radii && !radii->empty();
    const auto ri2 = [&](std::size_t i) { return each ? (*radii)[i] * (*radii)[i] : r2; };
    double s = 0.0;
    if (!total) {
        for (std::size_t i = 0; i < mass.size(); ++i) s += polar[i] - ri2(i) * mass[i];
        return s;
    }
    if (each)
        for (std::size_t i = 0; i < mass.size(); ++i) s += polar[i] + (r2 - ri2(i)) * mass[i];
    else
        for (const double j : polar) s += j;
    // No agent: nothing is covered. Else U is empty exactly when no cell is open.
    if (!mass.empty() && std::find(open.begin(), open.end(), char{1}) == open.end()) return s;
    // Φ(Q) - Σ M_i, Neumaier's compensated sum: one rounding of the result, not one per agent.
    double u = *total, comp = 0.0;
    for (const double m : mass) {
        const double t = u - m;
        comp += std::fabs(u) >= m ? (u - t) - m : (-m - t) + u;
        u = t;
    }
    return s + r2 * std::max(u + comp, 0.0);
}

/// Uniform-density moments of the clipped cells of agents 0..owned-1 of `swarm`.
struct CoverageMoments {
    std::vector<double> mass;   ///< M_i (area of W_i)
    Points centroid;            ///< C_i (the agent itself when W_i is empty)
    std::vector<double> polar;  ///< J_i = ∫_{W_i} |q - p_i|^2
    std::vector<char> open;     ///< W_i reaches its circle (reaches_circle)
    std::vector<double> radii;  ///< R_i (heterogeneous teams; empty: every agent has the swarm's radius)

    /// H at these moments (coverage_cost); `radius` = R̄, `total` = Φ(Q), nullptr for the plane.
    double cost(double radius, const double* total) const {
        return coverage_cost(mass, polar, open, radius, total, &radii);
    }
};

/// \param radii the agents' radii (AgentRadii{}: every agent has the swarm's radius).
/// \param owned the first `owned` agents get cells (the rest only shape them: an MPI halo); -1 = all.
/// \param env the environment Q, or nullptr for the plane.
/// \throws CoincidentError naming global ids. \note Thread-safe; O(owned m log m).
inline CoverageMoments coverage_moments(const Swarm& swarm, const AgentRadii& radii, const ConvexPolygon* env,
                                        Index owned = -1, int threads = 0, const ProgressFn& progress = nullptr) {
    detail::require_moment_radius(swarm.radius());
    const Index n = owned < 0 ? swarm.size() : std::min(owned, swarm.size());
    CoverageMoments out;
    if (!radii.equal()) out.radii.assign(radii.by_row().begin(), radii.by_row().begin() + n);
    out.mass.assign(static_cast<std::size_t>(n), 0.0);
    out.polar.assign(static_cast<std::size_t>(n), 0.0);
    out.open.assign(static_cast<std::size_t>(n), 0);
    out.centroid.resize(n, 2);
    detail::for_each_agent(n, threads, progress, [&](Index i, detail::CoverageWorkspace& w) {
        detail::clipped_local_cell(swarm, radii, i, env, w);
        const Moments m = uniform_moments(w.clipped, w.radius);
        const auto ii = static_cast<std::size_t>(i);
        out.mass[ii] = m.mass;
        out.polar[ii] = m.polar;
        out.open[ii] = reaches_circle(w.clipped);
        out.centroid.row(i) = m.centroid(swarm.point(i)).transpose();
    });
    return out;
}

/// coverage_moments with every agent at the swarm's radius.
inline CoverageMoments coverage_moments(const Swarm& swarm, const ConvexPolygon* env, Index owned = -1,
                                        int threads = 0, const ProgressFn& progress = nullptr) {
    return coverage_moments(swarm, AgentRadii{}, env, owned, threads, progress);
}

/// The clipped cells W_i of agents 0..owned-1 as a LimitedPartition (pieces in the caller's frame;
/// walls have neighbor kWall and span 0; edge neighbours and the CSR relation use the swarm's ids;
/// areas, centroids and perimeters are those of W_i). Its flat arrays and io::write_svg handle walls;
/// LimitedPartition::cell(i) and the JSON/GeoJSON writers know only edges and arcs (they would read a
/// wall as an arc), so clipped cells are exported by dvoronoi.coverage.CoverageCells instead.
/// With unequal `radii`, `radius` is R̄ and `radii` holds R_i (LimitedPartition::radius_of).
inline LimitedPartition coverage_cells(const Swarm& swarm, const AgentRadii& radii, const ConvexPolygon* env,
                                       Index owned = -1, int threads = 0) {
    const Index n = owned < 0 ? swarm.size() : std::min(owned, swarm.size());
    std::vector<std::vector<Piece>> cells(static_cast<std::size_t>(n));
    std::vector<Moments> mom(static_cast<std::size_t>(n));
    detail::for_each_agent(n, threads, nullptr, [&](Index i, detail::CoverageWorkspace& w) {
        detail::clipped_local_cell(swarm, radii, i, env, w);
        mom[static_cast<std::size_t>(i)] = uniform_moments(w.clipped, w.radius);
        cells[static_cast<std::size_t>(i)] = w.clipped;
    });
    LimitedPartition out;
    out.radius = swarm.radius();
    if (!radii.equal()) out.radii.assign(radii.by_row().begin(), radii.by_row().begin() + n);
    out.points = swarm.points().topRows(n);
    out.areas.resize(static_cast<std::size_t>(n));
    out.perimeters.resize(static_cast<std::size_t>(n));
    out.centroids.resize(n, 2);
    out.candidates.assign(static_cast<std::size_t>(n), 0);
    for (Index i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const Vec2 c = swarm.point(i);
        std::vector<Index> nb;
        for (const Piece& p : cells[ii]) {
            out.piece_neighbor.push_back(p.neighbor);
            out.piece_x.push_back(p.start.x() + c.x());
            out.piece_y.push_back(p.start.y() + c.y());
            out.piece_span.push_back(p.arc_span);
            if (p.neighbor >= 0) nb.push_back(p.neighbor);
        }
        std::sort(nb.begin(), nb.end());
        nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
        out.indices.insert(out.indices.end(), nb.begin(), nb.end());
        out.indptr.push_back(static_cast<Index>(out.indices.size()));
        out.piece_ptr.push_back(static_cast<Index>(out.piece_x.size()));
        out.areas[ii] = mom[ii].mass;
        out.perimeters[ii] = mom[ii].perimeter;
        out.centroids.row(i) = mom[ii].centroid(c).transpose();
    }
    return out;
}

/// coverage_cells with every agent at the swarm's radius.
inline LimitedPartition coverage_cells(const Swarm& swarm, const ConvexPolygon* env, Index owned = -1, int threads = 0) {
    return coverage_cells(swarm, AgentRadii{}, env, owned, threads);
}

/// Quadrature nodes of the clipped cells of agents 0..owned-1 (see quadrature_nodes): flat arrays,
/// node k at (x[k], y[k]) (caller's frame) with weight w[k] in the cell of agent owner[k]; agent i's
/// nodes are [ptr[i], ptr[i+1]).
struct CoverageQuadrature {
    std::vector<double> x, y, w;
    std::vector<Index> ptr{0};
    std::vector<char> open;  ///< per cell: W_i reaches its circle (reaches_circle); empty for Q itself
};

inline CoverageQuadrature coverage_quadrature(const Swarm& swarm, const AgentRadii& radii, const ConvexPolygon* env,
                                              int order, Index owned = -1, int threads = 0) {
    detail::require_moment_radius(swarm.radius());
    const GaussRule g(order);
    const Index n = owned < 0 ? swarm.size() : std::min(owned, swarm.size());
    std::vector<std::vector<double>> xs(static_cast<std::size_t>(n)), ys(xs), ws(xs);
    CoverageQuadrature out;
    out.open.assign(static_cast<std::size_t>(n), 0);
    detail::for_each_agent(n, threads, nullptr, [&](Index i, detail::CoverageWorkspace& w) {
        detail::clipped_local_cell(swarm, radii, i, env, w);
        const auto ii = static_cast<std::size_t>(i);
        out.open[ii] = reaches_circle(w.clipped);
        const Vec2 c = swarm.point(i);
        const std::size_t k = quadrature_size(w.clipped, g);
        xs[ii].clear();
        ys[ii].clear();
        ws[ii].clear();
        xs[ii].reserve(k);
        ys[ii].reserve(k);
        ws[ii].reserve(k);
        quadrature_nodes(w.clipped, w.radius, g, [&](const Vec2& q, double wt) {
            xs[ii].push_back(c.x() + q.x());
            ys[ii].push_back(c.y() + q.y());
            ws[ii].push_back(wt);
        });
    });
    for (Index i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        out.x.insert(out.x.end(), xs[ii].begin(), xs[ii].end());
        out.y.insert(out.y.end(), ys[ii].begin(), ys[ii].end());
        out.w.insert(out.w.end(), ws[ii].begin(), ws[ii].end());
        out.ptr.push_back(static_cast<Index>(out.x.size()));
    }
    return out;
}

/// coverage_quadrature with every agent at the swarm's radius.
inline CoverageQuadrature coverage_quadrature(const Swarm& swarm, const ConvexPolygon* env, int order, Index owned = -1,
                                              int threads = 0) {
    return coverage_quadrature(swarm, AgentRadii{}, env, order, owned, threads);
}

/// Quadrature nodes of the environment itself (a fan of triangles from vertex 0, the same rule), for
/// Φ(Q) under a density.
inline CoverageQuadrature environment_quadrature(const ConvexPolygon& env, int order) {
    const GaussRule g(order);
    CoverageQuadrature out;
    const auto& v = env.vertices();
    std::vector<Piece> fan;
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
        fan = {Piece{0, v[k] - v[0], 0.0}, Piece{0, v[k + 1] - v[0], 0.0}, Piece{0, Vec2::Zero(), 0.0}};
        // Only the piece (v[k], v[k+1]) spans a triangle with the apex v[0]; the two through v[0] have
        // zero area and emit nothing.
        quadrature_nodes(fan, 0.0, g, [&](const Vec2& q, double wt) {
            out.x.push_back(v[0].x() + q.x());
            out.y.push_back(v[0].y() + q.y());
            out.w.push_back(wt);
        });
    }
    out.ptr.push_back(static_cast<Index>(out.x.size()));
    return out;
}

/// The Lloyd move p + gain (C - p), kept in `env`: shortened (halved) while rounding leaves it outside.
inline Vec2 lloyd_move(const Vec2& p, const Vec2& centroid, double gain, const ConvexPolygon* env) {
    Vec2 q = p + gain * (centroid - p);
    if (!env) return q;
    double t = gain;
    while (!env->contains(q)) {
        t *= 0.5;
        if (t < 1e-30) return p;
        q = p + t * (centroid - p);
    }
    return q;
}

/// Lloyd's algorithm on limited cells, stepped in place: holds the swarm (its grid survives the
/// steps), the environment and the gain.
///
/// \note Not thread-safe (one stepper per thread); each step uses an OpenMP team internally.
class LloydStepper {
public:
    /// \throws InputError for a gain outside (0, 1], a bad radius, non-finite points, or an agent
    ///         outside `env` (named by index).
    LloydStepper(PointsRef points, double radius, std::optional<ConvexPolygon> env = std::nullopt,
                 double gain = 1.0, int threads = 0)
        : env_(std::move(env)), gain_(gain), threads_(threads) {
        check(points, radius);
        swarm_ = Swarm(points, radius);
    }

    /// A heterogeneous team: agent i senses within radii[i] (top of this file). All radii equal give
    /// exactly the scalar stepper.
    /// \throws as above, and InputError naming `radius` for a wrong length or a bad radius.
    LloydStepper(PointsRef points, const std::vector<double>& radii, std::optional<ConvexPolygon> env = std::nullopt,
                 double gain = 1.0, int threads = 0)
        : env_(std::move(env)), gain_(gain), threads_(threads) {
        if (static_cast<Index>(radii.size()) != points.rows())
            throw InputError("radius must have one radius per agent: got " + std::to_string(radii.size()) +
                             " radii for " + std::to_string(points.rows()) + " agents");
        detail::require_finite_radii(radii);
        const double rmax = radii.empty() ? 1.0 : *std::max_element(radii.begin(), radii.end());
        check(points, rmax);
        for (const double R : radii) detail::require_moment_radius(R);
        swarm_ = Swarm(points, rmax);
        radii_ = AgentRadii(swarm_, radii);
    }

    const Swarm& swarm() const noexcept { return swarm_; }
    const Points& points() const noexcept { return swarm_.points(); }
    /// The radius, or the largest R̄ of a heterogeneous team.
    double radius() const noexcept { return swarm_.radius(); }
    const AgentRadii& radii() const noexcept { return radii_; }
    double gain() const noexcept { return gain_; }
    const ConvexPolygon* environment() const noexcept { return env_ ? &*env_ : nullptr; }

    /// The uniform-density cost H at the current positions (see the top of this file).
    double cost() const { return cost_of(coverage_moments(swarm_, radii_, environment(), -1, threads_)); }

    /// One Lloyd step with uniform density: cells at the current positions, then every agent moves.
    /// Returns H at the positions before the move.
    double step(const ProgressFn& progress = nullptr) {
        const CoverageMoments m = coverage_moments(swarm_, radii_, environment(), -1, threads_, progress);
        move_to_targets(m.centroid);
        return cost_of(m);
    }

    /// Moves every agent towards `centroids` (any density) with the stepper's gain.
    void move_to_targets(const Points& centroids) {
        if (centroids.rows() != swarm_.size())
            throw InputError("centroids must have one row per agent");
        Points next(swarm_.size(), 2);
        for (Index i = 0; i < swarm_.size(); ++i)
            next.row(i) = lloyd_move(swarm_.point(i), centroids.row(i).transpose(), gain_, environment()).transpose();
        swarm_.move_to(next);
    }

    /// Puts the agents at `points` (a user-driven loop); the grid is updated, not rebuilt.
    void set_points(PointsRef points) {
        if (env_)
            for (Eigen::Index i = 0; i < points.rows(); ++i)
                if (std::isfinite(points(i, 0)) && std::isfinite(points(i, 1)) &&
                    !env_->contains(points.row(i).transpose()))
                    throw InputError("points[" + std::to_string(i) + "] lies outside bounds");
        swarm_.move_to(points);
    }

    double cost_of(const CoverageMoments& m) const {
        const double area = env_ ? env_->area() : 0.0;
        return m.cost(radius(), env_ ? &area : nullptr);
    }

private:
    void check(PointsRef points, double radius) const {
        if (!(gain_ > 0.0 && gain_ <= 1.0))
            throw InputError("gain must be in (0, 1], got " + std::to_string(gain_));
        detail::require_finite_radius(radius);
        detail::require_moment_radius(radius);
        detail::require_finite_points(points, "points");
        if (env_)
            for (Eigen::Index i = 0; i < points.rows(); ++i)
                if (!env_->contains(points.row(i).transpose()))
                    throw InputError("points[" + std::to_string(i) + "] lies outside bounds");
    }

    std::optional<ConvexPolygon> env_;
    double gain_;
    int threads_;
    Swarm swarm_;
    AgentRadii radii_;
};

}  // namespace dvoronoi
