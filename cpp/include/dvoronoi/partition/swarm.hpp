// A swarm whose agents move a little at every step: a uniform grid of buckets (square cells of side
// just above 2R) kept across steps. After a move only the agents that crossed into another bucket are
// rebucketed, so a time step pays for the cells, not for rebuilding the index.
//
// Each agent carries an id (its global index: the row in a single-process run, the agent's number
// across all ranks in an MPI run). Neighbour queries return candidates sorted by id, which makes each
// agent's cell a function of the positions alone -- independent of the order agents are stored in,
// of the bucket layout, and so of how many processes share the swarm.
#pragma once

#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace dvoronoi {

class Swarm {
public:
    Swarm() = default;

    /// Agents `points` with ids `ids` (empty: 0..n-1), cell radius `radius`.
    /// \throws InputError for a bad radius, non-finite coordinates or ids of the wrong length.
    Swarm(PointsRef points, double radius, std::vector<Index> ids = {})
        : radius_(radius), pts_(points), ids_(std::move(ids)) {
        detail::require_finite_radius(radius);
        detail::require_finite_points(points, "points");
        const Index n = pts_.rows();
        if (ids_.empty()) {
            ids_.resize(static_cast<std::size_t>(n));
            for (Index i = 0; i < n; ++i) ids_[static_cast<std::size_t>(i)] = i;
        }
        if (static_cast<Index>(ids_.size()) != n)
            throw InputError("ids must have one entry per point (" + std::to_string(n) + "), got " +
                             std::to_string(ids_.size()));
        rebuild();
    }

    Index size() const noexcept { return pts_.rows(); }
    double radius() const noexcept { return radius_; }
    const Points& points() const noexcept { return pts_; }
    const std::vector<Index>& ids() const noexcept { return ids_; }
    Vec2 point(Index i) const { return pts_.row(i).transpose(); }
    /// Agents that changed bucket in the last move_to (all of them after a rebuild).
    Index rebucketed() const noexcept { return rebucketed_; }
    /// Number of full rebuilds of the index so far (the first construction counts).
    Index rebuilds() const noexcept { return rebuilds_; }

    /// Moves every agent to `points` (same count, same ids). Only agents whose bucket changed are
    /// rebucketed; an agent leaving the grid's extent triggers one rebuild with a wider extent.
    /// \note O(n + movers); not thread-safe against concurrent queries.
    void move_to(PointsRef points) {
        if (points.rows() != pts_.rows())
            throw InputError("points must keep the swarm's " + std::to_string(pts_.rows()) +
                             " agents, got " + std::to_string(points.rows()));
        detail::require_finite_points(points, "points");
        pts_ = points;
        rebucketed_ = 0;
        const Index n = pts_.rows();
        for (Index i = 0; i < n; ++i) {
            const Key k = key_at(pts_(i, 0), pts_(i, 1));
            if (!inside(k)) {
                rebuild();
                return;
            }
        }
        for (Index i = 0; i < n; ++i) {
            const auto ii = static_cast<std::size_t>(i);
            const Key k = key_at(pts_(i, 0), pts_(i, 1));
            if (k.cx == key_[ii].cx && k.cy == key_[ii].cy) {
                Entry& e = bucket_for_insert(k)[static_cast<std::size_t>(slot_[ii])];
                e.x = pts_(i, 0);
                e.y = pts_(i, 1);
                continue;
            }
            remove(i);
            key_[ii] = k;
            insert(i);
            ++rebucketed_;
        }
    }

    /// Agents j != i strictly within 2R of agent i (exact predicate), as (position, id), sorted by id.
    /// Agents at exactly the position of i are reported in `same` (ids) and left out of `out`.
    void within(Index i, std::vector<detail::Candidate>& out, std::vector<Index>* same = nullptr) const {
        out.clear();
        const auto ii = static_cast<std::size_t>(i);
        const Vec2 c = point(i);
        const Key k = key_[ii];
        const double r2 = 4.0 * radius_ * radius_, r2hi = r2 * (1.0 + 1e-9), r2lo = r2 * (1.0 - 1e-9);
        for (std::int64_t cx = k.cx - 1; cx <= k.cx + 1; ++cx)
            for (std::int64_t cy = k.cy - 1; cy <= k.cy + 1; ++cy) {
                const std::vector<Entry>* b = bucket(cx, cy);
                if (!b) continue;
                for (const Entry& e : *b) {
                    const double dx = e.x - c.x(), dy = e.y - c.y();
                    const double d2 = dx * dx + dy * dy;
                    if (d2 > r2hi) continue;
                    const Index j = e.i;
                    if (j == i) continue;
                    const Vec2 p(e.x, e.y);
                    if (p == c) {
                        if (same) same->push_back(ids_[static_cast<std::size_t>(j)]);
                        continue;
                    }
                    if (d2 < r2lo || pred::within_2r(c, p, radius_) > 0)
                        out.push_back({p, ids_[static_cast<std::size_t>(j)]});
                }
            }
        std::sort(out.begin(), out.end(),
                  [](const detail::Candidate& a, const detail::Candidate& b) { return a.id < b.id; });
    }

private:
    struct Key {
        std::int64_t cx = 0, cy = 0;
    };
    /// A bucket entry keeps the agent's position, so a query scans contiguous memory.
    struct Entry {
        double x, y;
        Index i;
    };

    Key key_at(double x, double y) const {
        return {static_cast<std::int64_t>(std::floor((x - x0_) / cell_)),
                static_cast<std::int64_t>(std::floor((y - y0_) / cell_))};
    }
    bool inside(const Key& k) const { return k.cx >= 0 && k.cy >= 0 && k.cx < nx_ && k.cy < ny_; }

    const std::vector<Entry>* bucket(std::int64_t cx, std::int64_t cy) const {
        if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return nullptr;
        if (dense_) return &buckets_[static_cast<std::size_t>(cx * ny_ + cy)];
        const auto it = sparse_.find(pack(cx, cy));
        return it == sparse_.end() ? nullptr : &buckets_[it->second];
    }
    static std::uint64_t pack(std::int64_t cx, std::int64_t cy) {
        return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy);
    }
    std::vector<Entry>& bucket_for_insert(const Key& k) {
        if (dense_) return buckets_[static_cast<std::size_t>(k.cx * ny_ + k.cy)];
        const auto [it, fresh] = sparse_.try_emplace(pack(k.cx, k.cy), buckets_.size());
        if (fresh) buckets_.emplace_back();
        return buckets_[it->second];
    }
    void insert(Index i) {
        const auto ii = static_cast<std::size_t>(i);
        std::vector<Entry>& b = bucket_for_insert(key_[ii]);
        slot_[ii] = static_cast<Index>(b.size());
        b.push_back({pts_(i, 0), pts_(i, 1), i});
    }
    void remove(Index i) {
        const auto ii = static_cast<std::size_t>(i);
        std::vector<Entry>& b = bucket_for_insert(key_[ii]);
        const auto s = static_cast<std::size_t>(slot_[ii]);
        b[s] = b.back();
        slot_[static_cast<std::size_t>(b[s].i)] = static_cast<Index>(s);
        b.pop_back();
    }

    /// A fresh grid over the agents' bounding box plus a margin of a few cells (so agents that move
    /// a little stay inside it). Cells of side 2R (1 + 2^-16): the margin covers the rounding of
    /// (x - x0) / cell, so the 3 x 3 block around an agent's bucket holds every agent within 2R
    /// (the argument of core/grid_index.hpp).
    void rebuild() {
        ++rebuilds_;
        const Index n = pts_.rows();
        rebucketed_ = n;
        key_.assign(static_cast<std::size_t>(n), Key{});
        slot_.assign(static_cast<std::size_t>(n), 0);
        buckets_.clear();
        sparse_.clear();
        cell_ = 2.0 * radius_ * (1.0 + std::ldexp(1.0, -16));
        if (n == 0) {
            nx_ = ny_ = 0;
            return;
        }
        const double xmin = pts_.col(0).minCoeff(), xmax = pts_.col(0).maxCoeff();
        const double ymin = pts_.col(1).minCoeff(), ymax = pts_.col(1).maxCoeff();
        const double max_cells = std::ldexp(1.0, 30);
        cell_ = std::max({cell_, (xmax - xmin) / max_cells, (ymax - ymin) / max_cells});
        const double pad = 4.0 * cell_;
        x0_ = xmin - pad;
        y0_ = ymin - pad;
        nx_ = static_cast<std::int64_t>(std::floor((xmax + pad - x0_) / cell_)) + 1;
        ny_ = static_cast<std::int64_t>(std::floor((ymax + pad - y0_) / cell_)) + 1;
        dense_ = static_cast<double>(nx_) * static_cast<double>(ny_) <= 4.0 * static_cast<double>(n) + 4096.0;
        if (dense_) buckets_.assign(static_cast<std::size_t>(nx_ * ny_), {});
        for (Index i = 0; i < n; ++i) {
            key_[static_cast<std::size_t>(i)] = key_at(pts_(i, 0), pts_(i, 1));
            insert(i);
        }
    }

    double radius_ = 1.0;
    Points pts_;
    std::vector<Index> ids_;
    double x0_ = 0.0, y0_ = 0.0, cell_ = 1.0;
    std::int64_t nx_ = 0, ny_ = 0;
    bool dense_ = true;
    std::vector<Key> key_;
    std::vector<Index> slot_;
    std::vector<std::vector<Entry>> buckets_;
    std::unordered_map<std::uint64_t, std::size_t> sparse_;
    Index rebucketed_ = 0, rebuilds_ = 0;
};

}  // namespace dvoronoi
