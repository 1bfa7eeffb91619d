// Lloyd's algorithm on geodesic cells (geodesic_cells.hpp): coverage control on an occupancy grid, agents
// moving around walls (Breitenmoser et al., ICRA 2010; Bhattacharya, Michael & Kumar, 2013).
//
// One step from positions P with cells W_i and cost H(P):
//   1. target t_i = the centroid C_i of W_i under phi when C_i lies in a pixel of W_i, else the centre of
//      W_i's pixel nearest to C_i (the cell point minimising sum_{q in W_i} phi(q) |q - x|^2);
//   2. path_i = the shortest path from p_i to t_i (geodesic_path.hpp; every segment checked free);
//   3. backtracking on H: with a = gain, a/2, a/4, ... (at most `max_halvings` halvings) every agent moves
//      a * |path_i| along path_i; the first trial whose cost does not exceed H(P) is taken, else nobody
//      moves. A move ending on an occupied pixel's boundary (floor() lands in a wall) is not made.
// So H never increases, and agents only ever travel along free segments.
//
// A heterogeneous team (a range R_i per agent) has the cells and cost of geodesic_team.hpp and
// geodesic_cells.hpp; each agent's path comes from its own wavefront, and the same backtracking keeps
// the cost from increasing.
//
// Threads: the wavefront is sequential (a team's per-agent wavefronts run in parallel, each on its
// own); moments, targets and paths run on `workers` threads in fixed blocks, so every result is the
// same for every worker count.
#pragma once

#include "dvoronoi/coverage/geodesic_cells.hpp"
#include "dvoronoi/coverage/geodesic_path.hpp"
#include "dvoronoi/coverage/geodesic_team.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

namespace dvoronoi::coverage {

class GeodesicLloyd {
public:
    /*! `occ` rows x cols (nonzero occupied), agents in pixel units (checked by agents_on_map), `limit` the
        range in pixel units (+inf none), `weight` phi per pixel (empty = uniform); `ranges` (pixel units,
        one per agent, finite and > 0) makes a heterogeneous team, `limit` then ignored (empty: all at
        `limit`; all equal: the same as that `limit`). */
    GeodesicLloyd(std::vector<std::uint8_t> occ, std::int32_t rows, std::int32_t cols, std::vector<PixelPoint> agents,
                  double limit, std::vector<double> weight, double gain, int workers, int max_halvings = 12,
                  std::vector<double> ranges = {})
        : occ_(std::move(occ)), rows_(rows), cols_(cols), points_(std::move(agents)), limit_(limit),
          weight_(std::move(weight)), gain_(gain), workers_(std::max(1, workers)), max_halvings_(max_halvings),
          workspace_(occ_.data(), rows, cols) {
        if (!ranges.empty()) {
            if (ranges.size() != points_.size()) throw std::invalid_argument("radius must have one range per agent");
            for (const double R : ranges)
                if (!(R > 0 && std::isfinite(R))) throw std::invalid_argument("radius: every range must be positive and finite");
            limit_ = *std::max_element(ranges.begin(), ranges.end());
            if (std::any_of(ranges.begin(), ranges.end(), [&](double R) { return R != limit_; })) ranges_ = std::move(ranges);
        }
        if (occ_.size() != std::size_t(rows) * cols) throw std::invalid_argument("occupancy size does not match rows x cols");
        if (!weight_.empty() && weight_.size() != occ_.size())
            throw std::invalid_argument("density must have one value per pixel");
        if (!(gain > 0 && gain <= 1)) throw std::invalid_argument("gain must be in (0, 1]");
        reachable_ = reachable_pixels(occ_.data(), rows_, cols_, points_);
        evaluate(points_, field_, moments_);
    }

    const std::vector<PixelPoint>& points() const { return points_; }
    const GeodesicField& field() const { return field_; }
    const GeodesicMoments& moments() const { return moments_; }
    double cost() const { return moments_.cost; }
    //! Halvings the last step needed (-1: no trial was accepted, nobody moved).
    int last_halvings() const { return last_halvings_; }
    //! Agents whose path the last step could not use (a segment not free; they stayed).
    std::int64_t last_stuck() const { return last_stuck_; }

    //! One step; returns H before it.
    double step() {
        const double h0 = moments_.cost;
        const std::int32_t n = static_cast<std::int32_t>(points_.size());
        std::vector<PixelPoint> centroid(static_cast<std::size_t>(n));
        for (std::int32_t i = 0; i < n; ++i)
            centroid[i] = moments_.mass[i] > 0 ? PixelPoint{moments_.mu[i] / moments_.mass[i], moments_.mw[i] / moments_.mass[i]}
                                               : points_[i];
        const std::vector<std::int64_t> nearest = nearest_cell_pixels(field_, centroid, workers_);
        const OccupancyView g{occ_.data(), rows_, cols_};
        std::vector<std::vector<PixelPoint>> path(static_cast<std::size_t>(n));
        std::vector<double> length(static_cast<std::size_t>(n), 0.0);
        std::atomic<std::int32_t> next{0};
        run_team(std::max(1, std::min({workers_, n, ::dvoronoi::detail::max_team()})), [&](int) {
            for (std::int32_t i; (i = next++) < n;) {
                if (!(moments_.mass[i] > 0) || nearest[i] < 0) continue;
                PixelPoint t = centroid[i];
                std::int64_t q = pixel_of(t);
                if (q < 0 || field_.label[static_cast<std::size_t>(q)] != i) {
                    q = nearest[i];
                    t = {double(q % cols_) + 0.5, double(q / cols_) + 0.5};
                }
                path[i] = ranges_.empty() ? geodesic_path(field_, g, q, t)
                                          : team_path(waves_[static_cast<std::size_t>(i)], cols_, q, t);
                length[i] = path_length(path[i]);
            }
        });
        last_stuck_ = 0;
        for (std::int32_t i = 0; i < n; ++i) last_stuck_ += moments_.mass[i] > 0 && path[i].empty();
        double a = gain_;
        last_halvings_ = -1;
        for (int h = 0; h <= max_halvings_; ++h, a *= 0.5) {
            std::vector<PixelPoint> trial = points_;
            for (std::int32_t i = 0; i < n; ++i) {
                if (path[i].empty()) continue;
                const PixelPoint p = point_along(path[i], a * length[i]);
                if (pixel_of(p) >= 0) trial[i] = p;  // a point on a wall's boundary stays where it was
            }
            GeodesicMoments m;
            evaluate(trial, trial_field_, m, trial_waves_);
            if (m.cost <= h0) {
                points_ = std::move(trial);
                std::swap(field_, trial_field_);  // both keep their buffers for the next step
                std::swap(waves_, trial_waves_);
                moments_ = std::move(m);
                last_halvings_ = h;
                break;
            }
        }
        return h0;
    }

    //! Move the agents (same number, already checked); the reachable set is recomputed.
    void set_points(std::vector<PixelPoint> agents) {
        if (agents.size() != points_.size()) throw std::invalid_argument("set_points: the number of agents must not change");
        points_ = std::move(agents);
        reachable_ = reachable_pixels(occ_.data(), rows_, cols_, points_);
        evaluate(points_, field_, moments_);
    }

    //! A heterogeneous team's ranges (pixel units; empty when every agent has limit()).
    const std::vector<double>& ranges() const { return ranges_; }
    double limit() const { return limit_; }

private:
    // The free pixel containing p (floor), or -1.
    std::int64_t pixel_of(const PixelPoint& p) const {
        const double c = std::floor(p.u), r = std::floor(p.w);
        if (!(c >= 0 && r >= 0 && c < cols_ && r < rows_)) return -1;
        const std::int64_t q = std::int64_t(r) * cols_ + std::int64_t(c);
        return occ_[static_cast<std::size_t>(q)] ? -1 : q;
    }

    void evaluate(const std::vector<PixelPoint>& pts, GeodesicField& f, GeodesicMoments& m) { evaluate(pts, f, m, waves_); }

    void evaluate(const std::vector<PixelPoint>& pts, GeodesicField& f, GeodesicMoments& m, std::vector<AgentWave>& waves) {
        const double* w = weight_.empty() ? nullptr : weight_.data();
        if (ranges_.empty()) {
            geodesic_field(occ_.data(), rows_, cols_, pts, limit_, f, workspace_);
            m = geodesic_moments(f, w, reachable_.data(), limit_, workers_);
            return;
        }
        geodesic_team_field(occ_.data(), rows_, cols_, pts, ranges_, workers_, f, waves);
        m = geodesic_moments(f, w, reachable_.data(), limit_, workers_, &ranges_);
    }

    std::vector<std::uint8_t> occ_;
    std::int32_t rows_, cols_;
    std::vector<PixelPoint> points_;
    double limit_;
    std::vector<double> weight_;
    double gain_;
    int workers_, max_halvings_;
    GeodesicWorkspace workspace_;
    std::vector<std::uint8_t> reachable_;
    std::vector<double> ranges_;
    GeodesicField field_, trial_field_;
    std::vector<AgentWave> waves_, trial_waves_;
    GeodesicMoments moments_;
    int last_halvings_ = 0;
    std::int64_t last_stuck_ = 0;
};

}  // namespace dvoronoi::coverage
