// Nearest-obstacle queries for the grid Voronoi diagram: a uniform bucket grid over the area holding
// each convex part in every bucket its (slightly enlarged) bounding box overlaps, searched in square
// rings around the query point with distance lower bounds.
//
// Each bucket also keeps the short list of parts that can be nearest to some point inside it
// (build_candidates), so a query inside the grid evaluates only those, with no ring search.
//
// Why buckets and not a library kd-tree: the sites are shapes, not points, and the query must return
// exactly the brute-force answer (same distances, ties to the lower label). A ring search visits a
// part only if its bounding box is no farther than the best distance so far, and stops once the
// distance to the unsearched region exceeds it, so the answer equals a scan of all parts. With
// a few buckets per part a query looks at O(1) buckets on evenly spread obstacles and O(log n)-ish
// on clustered ones (the paper scans every obstacle edge per corner).
#pragma once

#include "dvoronoi/gvd/distance.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dvoronoi::gvd {

/// The nearest obstacle of a point: its label and squared distance (ties: lower label).
struct Nearest {
    std::int32_t label = -1;
    double sq = std::numeric_limits<double>::infinity();
    std::int32_t part = -1;  ///< the convex part that realises the distance
};

/// Per-thread scratch of the index (visited stamps and counters). Not shared between threads.
struct QueryContext {
    std::vector<std::uint32_t> stamp;
    std::uint32_t current = 0;
    DistanceCounters counters;
    std::uint64_t queries = 0;
    std::int32_t hint = -1;  ///< part that answered the previous query (tried first: nearby queries share it)
};

class ObstacleIndex {
public:
    ObstacleIndex() = default;

    /// Builds the buckets over `scene.box`, the candidate lists with `threads` threads (the same
    /// index for every count). \note O(parts x buckets each overlaps).
    explicit ObstacleIndex(const Scene& scene, bool visibility = true, int threads = 1)
        : scene_(&scene), visibility_(visibility) {
        const Box& b = scene.box;
        const double w = b.x1 - b.x0, h = b.y1 - b.y0;
        const double n = static_cast<double>(std::max<std::size_t>(1, scene.parts.size()));
        // about four buckets per part (short candidate lists), at most 1024 x 1024 buckets
        cell_ = std::max(w, h) / std::min(1024.0, std::max(1.0, std::ceil(2.0 * std::sqrt(n))));
        nx_ = std::max(1, static_cast<int>(std::ceil(w / cell_)));
        ny_ = std::max(1, static_cast<int>(std::ceil(h / cell_)));
        x0_ = b.x0;
        y0_ = b.y0;
        eps_ = 1e-9 * std::max({w, h, std::abs(b.x0), std::abs(b.y0), std::abs(b.x1), std::abs(b.y1)});
        std::vector<std::uint32_t> count(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
        auto range = [&](const Box& pb, int& i0, int& i1, int& j0, int& j1) {
            i0 = bx(pb.x0 - eps_); i1 = bx(pb.x1 + eps_);
            j0 = by(pb.y0 - eps_); j1 = by(pb.y1 + eps_);
        };
        for (const ConvexPart& p : scene.parts) {
            int i0, i1, j0, j1;
            range(p.box, i0, i1, j0, j1);
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) ++count[bucket(i, j) + 1];
        }
        for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
        start_ = count;
        items_.resize(count.back());
        for (std::size_t pi = 0; pi < scene.parts.size(); ++pi) {
            int i0, i1, j0, j1;
            range(scene.parts[pi].box, i0, i1, j0, j1);
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) items_[count[bucket(i, j)]++] = static_cast<std::uint32_t>(pi);
        }
        build_candidates(threads);
    }

    const Scene& scene() const { return *scene_; }
    bool visibility() const { return visibility_; }

    QueryContext context() const {
        QueryContext c;
        c.stamp.assign(scene_->parts.size(), 0);
        return c;
    }

    /// The nearest obstacle to p: the same answer as `nearest_brute_force`.
    /// \note Thread-safe with one QueryContext per thread.
    Nearest nearest(const Vec2& p, QueryContext& ctx) const {
        ++ctx.queries;
        const int bi = bx(p.x()), bj = by(p.y());
        const double lx = x0_ + bi * cell_, ly = y0_ + bj * cell_;
        if (p.x() >= lx && p.x() <= lx + cell_ && p.y() >= ly && p.y() <= ly + cell_) {
            // Inside the bucket: its candidate list holds every part that can be nearest here.
            Nearest best;
            const std::size_t b = bucket(bi, bj);
            if (ctx.hint >= 0) evaluate(static_cast<std::uint32_t>(ctx.hint), p, ctx, best);
            for (std::uint32_t k = cand_start_[b]; k < cand_start_[b + 1]; ++k) {
                const std::uint32_t pi = cand_items_[k];
                if (static_cast<std::int32_t>(pi) != ctx.hint) evaluate(pi, p, ctx, best);
            }
            ctx.hint = best.part;
            return best;
        }
        return nearest_by_rings(p, ctx);
    }

    /// The same answer by searching square rings of buckets (used outside the bucket grid).
    Nearest nearest_by_rings(const Vec2& p, QueryContext& ctx) const {
        next_stamp(ctx);
        Nearest best;
        // The previous answer first: consecutive queries are neighbouring corners, so this bound is
        // usually tight and the bounding-box test skips most other parts. The answer does not depend
        // on the order parts are looked at (smallest (distance, label) wins).
        if (ctx.hint >= 0) {
            const auto pi = static_cast<std::uint32_t>(ctx.hint);
            ctx.stamp[pi] = ctx.current;
            const ConvexPart& part = scene_->parts[pi];
            best = Nearest{part.label, sq_distance(*scene_, part, p, visibility_, &ctx.counters), ctx.hint};
        }
        const int ci = bx(p.x()), cj = by(p.y());
        const int max_ring = std::max({ci, nx_ - 1 - ci, cj, ny_ - 1 - cj});
        for (int r = 0; r <= max_ring; ++r) {
            const int i0 = ci - r, i1 = ci + r, j0 = cj - r, j1 = cj + r;
            for (int j = std::max(j0, 0); j <= std::min(j1, ny_ - 1); ++j) {
                const bool edge_row = (j == j0 || j == j1);
                for (int i = std::max(i0, 0); i <= std::min(i1, nx_ - 1); ++i) {
                    if (!edge_row && i != i0 && i != i1) {  // interior of the ring: jump to its right side
                        if (i1 > nx_ - 1) break;
                        i = i1;
                    }
                    visit(bucket(i, j), p, ctx, best);
                }
            }
            // Lower bound on the distance of every part not seen yet: such a part lies outside the
            // searched square (sides at the edge of the bucket grid hold everything beyond them).
            double lb = std::numeric_limits<double>::infinity();
            if (i0 > 0) lb = std::min(lb, p.x() - (x0_ + i0 * cell_));
            if (i1 < nx_ - 1) lb = std::min(lb, (x0_ + (i1 + 1) * cell_) - p.x());
            if (j0 > 0) lb = std::min(lb, p.y() - (y0_ + j0 * cell_));
            if (j1 < ny_ - 1) lb = std::min(lb, (y0_ + (j1 + 1) * cell_) - p.y());
            if (lb == std::numeric_limits<double>::infinity()) break;  // whole grid searched
            lb -= 2 * eps_;
            if (lb > 0 && lb * lb > best.sq) break;
        }
        ctx.hint = best.part;
        return best;
    }

    /// nearest(p), and how much farther than it the nearest part of another label is (Euclidean
    /// distances, capped at `cap`; `cap` when there is none within it). The other labels looked at
    /// are the candidates of p's bucket (every part that can be nearest or tie somewhere in that
    /// closed bucket), or every part when p lies outside the bucket grid (`global` is then true).
    /// The nearest obstacle is exactly nearest(p)'s.
    Nearest nearest_gap(const Vec2& p, double cap, QueryContext& ctx, double& gap, bool& global) const {
        std::size_t b;
        if (!bucket_of(p, b)) {
            const Nearest n = nearest(p, ctx);
            gap = global_gap(p, n, cap, ctx);
            global = true;
            return n;
        }
        ++ctx.queries;
        global = false;
        // The two nearest labels: (best) and the nearest part of any other label (second).
        Nearest best;
        double second = std::numeric_limits<double>::infinity();
        double limit = std::numeric_limits<double>::infinity();  // (best + cap)^2, padded: farther parts neither win nor count
        auto improve = [&](double d, std::int32_t label, std::uint32_t pi) {
            best = Nearest{label, d, static_cast<std::int32_t>(pi)};
            const double reach = std::sqrt(d) + cap;
            limit = reach * reach * (1.0 + 1e-12) + 1e-300;
        };
        auto look = [&](std::uint32_t pi) {
            const ConvexPart& part = scene_->parts[pi];
            if (part.box.sq_distance(p) > limit) return;
            const double d = sq_distance(*scene_, part, p, visibility_, &ctx.counters);
            if (part.label == best.label) {
                if (d < best.sq) improve(d, part.label, pi);
            } else if (d < best.sq || (d == best.sq && part.label < best.label)) {
                second = best.sq;  // the old best's label is now "another label" (inf when unset)
                improve(d, part.label, pi);
            } else {
                second = std::min(second, d);
            }
        };
        if (ctx.hint >= 0) look(static_cast<std::uint32_t>(ctx.hint));
        for (std::uint32_t k = cand_start_[b]; k < cand_start_[b + 1]; ++k) {
            const std::uint32_t pi = cand_items_[k];
            if (static_cast<std::int32_t>(pi) != ctx.hint) look(pi);
        }
        ctx.hint = best.part;
        gap = std::min(cap, std::sqrt(second) - std::sqrt(best.sq));
        return best;
    }

    /// The closed bucket holding p, as nearest() finds it; false when p lies outside the bucket grid.
    bool bucket_of(const Vec2& p, std::size_t& b) const {
        const int bi = bucket_column(p.x()), bj = bucket_row(p.y());
        if (bi < 0 || bj < 0) return false;
        b = bucket(bi, bj);
        return true;
    }
    /// The column (row) of buckets whose closed range holds x (y) as nearest() finds it, -1 when x
    /// (y) lies outside the bucket grid. A point is in the bucket (column, row) when both are >= 0.
    int bucket_column(double x) const {
        const int bi = bx(x);
        const double lx = x0_ + bi * cell_;
        return x >= lx && x <= lx + cell_ ? bi : -1;
    }
    int bucket_row(double y) const {
        const int bj = by(y);
        const double ly = y0_ + bj * cell_;
        return y >= ly && y <= ly + cell_ ? bj : -1;
    }

    /// Side of a bucket, and the absolute tolerance (1e-9 of the coordinates' magnitude) the index
    /// pads its boxes with.
    double bucket_size() const { return cell_; }
    double tolerance() const { return eps_; }

    /// How much farther than `n` (p's nearest) the nearest candidate of bucket b with another label
    /// is, capped at `cap`.
    double bucket_gap(const Vec2& p, const Nearest& n, std::size_t b, double cap, QueryContext& ctx) const {
        const double d1 = std::sqrt(n.sq), reach = d1 + cap;
        double second = std::numeric_limits<double>::infinity();
        for (std::uint32_t k = cand_start_[b]; k < cand_start_[b + 1]; ++k) {
            const ConvexPart& part = scene_->parts[cand_items_[k]];
            if (part.label == n.label) continue;
            if (part.box.sq_distance(p) > reach * reach * (1.0 + 1e-12) + 1e-300) continue;
            second = std::min(second, sq_distance(*scene_, part, p, visibility_, &ctx.counters));
        }
        return std::min(cap, std::sqrt(second) - d1);
    }

    /// The same over every part (square rings of buckets out to the capped reach).
    double global_gap(const Vec2& p, const Nearest& n, double cap, QueryContext& ctx) const {
        next_stamp(ctx);
        const double d1 = std::sqrt(n.sq), reach = d1 + cap;
        double second = std::numeric_limits<double>::infinity();
        const int ci = bx(p.x()), cj = by(p.y());
        const int max_ring = std::max({ci, nx_ - 1 - ci, cj, ny_ - 1 - cj});
        for (int r = 0; r <= max_ring; ++r) {
            const int i0 = ci - r, i1 = ci + r, j0 = cj - r, j1 = cj + r;
            for (int j = std::max(j0, 0); j <= std::min(j1, ny_ - 1); ++j)
                for (int i = std::max(i0, 0); i <= std::min(i1, nx_ - 1); ++i) {
                    if (j != j0 && j != j1 && i != i0 && i != i1) {  // interior of the ring: jump to its right side
                        if (i1 > nx_ - 1) break;
                        i = i1;
                    }
                    const std::size_t bk = bucket(i, j);
                    for (std::uint32_t k = start_[bk]; k < start_[bk + 1]; ++k) {
                        const std::uint32_t pi = items_[k];
                        if (ctx.stamp[pi] == ctx.current) continue;
                        ctx.stamp[pi] = ctx.current;
                        const ConvexPart& part = scene_->parts[pi];
                        if (part.label == n.label) continue;
                        if (part.box.sq_distance(p) > reach * reach * (1.0 + 1e-12) + 1e-300) continue;
                        second = std::min(second, sq_distance(*scene_, part, p, visibility_, &ctx.counters));
                    }
                }
            double lb = std::numeric_limits<double>::infinity();
            if (i0 > 0) lb = std::min(lb, p.x() - (x0_ + i0 * cell_));
            if (i1 < nx_ - 1) lb = std::min(lb, (x0_ + (i1 + 1) * cell_) - p.x());
            if (j0 > 0) lb = std::min(lb, p.y() - (y0_ + j0 * cell_));
            if (j1 < ny_ - 1) lb = std::min(lb, (y0_ + (j1 + 1) * cell_) - p.y());
            if (lb == std::numeric_limits<double>::infinity()) break;
            lb -= 2 * eps_;
            if (lb > 0 && lb > std::min(reach, std::sqrt(second))) break;
        }
        return std::min(cap, std::sqrt(second) - d1);
    }

    /// Calls f(a, b) once for every pair of parts a < b with different labels whose bounding boxes,
    /// padded by tolerance(), overlap and reach the columns x in [x_lo, x_hi] (found in the buckets
    /// over those columns). \note O(sum over those buckets of their part count squared).
    template <class F>
    void for_each_close_pair(double x_lo, double x_hi, F&& f) const {
        std::vector<std::uint64_t> pairs;
        const int i_lo = bx(x_lo), i_hi = bx(x_hi);
        for (int j = 0; j < ny_; ++j)
            for (int i = i_lo; i <= i_hi; ++i) {
                const std::size_t bk = bucket(i, j);
                for (std::uint32_t s = start_[bk]; s < start_[bk + 1]; ++s)
                    for (std::uint32_t t = s + 1; t < start_[bk + 1]; ++t) {
                        std::uint32_t a = items_[s], b = items_[t];
                        const ConvexPart &pa = scene_->parts[a], &pb = scene_->parts[b];
                        if (pa.label == pb.label) continue;
                        if (pa.box.x0 - eps_ > pb.box.x1 + eps_ || pb.box.x0 - eps_ > pa.box.x1 + eps_ ||
                            pa.box.y0 - eps_ > pb.box.y1 + eps_ || pb.box.y0 - eps_ > pa.box.y1 + eps_)
                            continue;
                        if (std::max(pa.box.x0, pb.box.x0) - eps_ > x_hi || std::min(pa.box.x1, pb.box.x1) + eps_ < x_lo) continue;
                        if (a > b) std::swap(a, b);
                        pairs.push_back((static_cast<std::uint64_t>(a) << 32) | b);
                    }
            }
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        for (std::uint64_t ab : pairs) f(static_cast<std::uint32_t>(ab >> 32), static_cast<std::uint32_t>(ab & 0xffffffffu));
    }

    /// Is segment ab farther than `radius` from every obstacle (strictly)? Labels in `ignore` (or -1)
    /// are not considered.
    bool segment_clear(const Vec2& a, const Vec2& b, double radius, QueryContext& ctx) const {
        next_stamp(ctx);
        Box sb;
        sb.add(a);
        sb.add(b);
        const double pad = radius + eps_;
        const int i0 = bx(sb.x0 - pad), i1 = bx(sb.x1 + pad), j0 = by(sb.y0 - pad), j1 = by(sb.y1 + pad);
        const double r2 = radius * radius;
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const std::size_t bk = bucket(i, j);
                for (std::uint32_t k = start_[bk]; k < start_[bk + 1]; ++k) {
                    const std::uint32_t pi = items_[k];
                    if (ctx.stamp[pi] == ctx.current) continue;
                    ctx.stamp[pi] = ctx.current;
                    const ConvexPart& part = scene_->parts[pi];
                    const double d2 = sq_segment_distance(*scene_, part, a, b);
                    if (!(d2 > r2)) return false;
                }
            }
        return true;
    }

private:
    void evaluate(std::uint32_t pi, const Vec2& p, QueryContext& ctx, Nearest& best) const {
        const ConvexPart& part = scene_->parts[pi];
        if (part.box.sq_distance(p) > best.sq * (1.0 + 1e-12) + 1e-300) return;  // cannot win or tie
        const double d = sq_distance(*scene_, part, p, visibility_, &ctx.counters);
        if (d < best.sq || (d == best.sq && part.label < best.label)) {
            best.sq = d;
            best.label = part.label;
            best.part = static_cast<std::int32_t>(pi);
        }
    }

    static double box_box_distance(const Box& a, const Box& b) {
        const double dx = std::max({0.0, a.x0 - b.x1, b.x0 - a.x1});
        const double dy = std::max({0.0, a.y0 - b.y1, b.y0 - a.y1});
        return std::sqrt(dx * dx + dy * dy);
    }

    /// Per bucket B, the parts that can be nearest to some point of B. The distance to a convex part
    /// is a convex function, so its largest value over B is at one of B's corners; U = the smallest
    /// such maximum over the parts bounds the nearest distance everywhere in B, and only parts whose
    /// bounding box comes within U of B can win (or tie). Found by growing rings of buckets around B
    /// until they are farther than U.
    /// Candidate lists of every bucket, rows split between threads (each builds its rows' lists;
    /// they are joined in row order, so the result does not depend on the thread count).
    void build_candidates(int threads) {
        const int T = std::max(1, std::min({threads, ny_, ::dvoronoi::detail::max_team()}));
        const std::size_t nb = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
        std::vector<std::uint32_t> count(nb, 0);
        std::vector<std::vector<std::uint32_t>> items(static_cast<std::size_t>(T));
        auto rows = [&](int t) {
            const Scene& s = *scene_;
            QueryContext ctx = context();
            std::vector<std::uint32_t> seen;
            auto& out = items[static_cast<std::size_t>(t)];
            for (int bj = ny_ * t / T; bj < ny_ * (t + 1) / T; ++bj)
                for (int bi = 0; bi < nx_; ++bi) {
                    Box B;
                    B.add(Vec2(x0_ + bi * cell_, y0_ + bj * cell_));
                    B.add(Vec2(x0_ + (bi + 1) * cell_, y0_ + (bj + 1) * cell_));
                    const Vec2 corner[4] = {Vec2(B.x0, B.y0), Vec2(B.x1, B.y0), Vec2(B.x1, B.y1), Vec2(B.x0, B.y1)};
                    next_stamp(ctx);
                    seen.clear();
                    double U = std::numeric_limits<double>::infinity();
                    const int max_ring = std::max({bi, nx_ - 1 - bi, bj, ny_ - 1 - bj});
                    for (int r = 0; r <= max_ring; ++r) {
                        for (int j = std::max(bj - r, 0); j <= std::min(bj + r, ny_ - 1); ++j)
                            for (int i = std::max(bi - r, 0); i <= std::min(bi + r, nx_ - 1); ++i) {
                                if (std::max(std::abs(i - bi), std::abs(j - bj)) != r) continue;
                                const std::size_t bk = bucket(i, j);
                                for (std::uint32_t k = start_[bk]; k < start_[bk + 1]; ++k) {
                                    const std::uint32_t pi = items_[k];
                                    if (ctx.stamp[pi] == ctx.current) continue;
                                    ctx.stamp[pi] = ctx.current;
                                    seen.push_back(pi);
                                    double ub = 0.0;
                                    for (const Vec2& c : corner) ub = std::max(ub, sq_distance(s, s.parts[pi], c, false));
                                    U = std::min(U, std::sqrt(ub));
                                }
                            }
                        // parts not seen yet lie outside the searched square: at least r * cell_ from B
                        if (static_cast<double>(r) * cell_ > U * (1.0 + 1e-9) + 4 * eps_) break;
                    }
                    const double limit = U * (1.0 + 1e-9) + 4 * eps_;
                    const std::size_t before = out.size();
                    for (std::uint32_t pi : seen)
                        if (box_box_distance(s.parts[pi].box, B) <= limit) out.push_back(pi);
                    count[bucket(bi, bj)] = static_cast<std::uint32_t>(out.size() - before);
                }
        };
        run_team(T, rows);
        cand_start_.assign(nb + 1, 0);
        for (std::size_t b = 0; b < nb; ++b) cand_start_[b + 1] = cand_start_[b] + count[b];
        cand_items_.clear();
        cand_items_.reserve(cand_start_.back());
        for (const auto& v : items) cand_items_.insert(cand_items_.end(), v.begin(), v.end());
    }

    static void next_stamp(QueryContext& ctx) {
        if (++ctx.current == 0) {
            std::fill(ctx.stamp.begin(), ctx.stamp.end(), 0u);
            ctx.current = 1;
        }
    }

    void visit(std::size_t bk, const Vec2& p, QueryContext& ctx, Nearest& best) const {
        for (std::uint32_t k = start_[bk]; k < start_[bk + 1]; ++k) {
            const std::uint32_t pi = items_[k];
            if (ctx.stamp[pi] == ctx.current) continue;
            ctx.stamp[pi] = ctx.current;
            evaluate(pi, p, ctx, best);
        }
    }

    int bx(double x) const {
        const double t = std::floor((x - x0_) / cell_);
        return static_cast<int>(std::clamp(t, 0.0, static_cast<double>(nx_ - 1)));
    }
    int by(double y) const {
        const double t = std::floor((y - y0_) / cell_);
        return static_cast<int>(std::clamp(t, 0.0, static_cast<double>(ny_ - 1)));
    }
    std::size_t bucket(int i, int j) const {
        return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
    }

    const Scene* scene_ = nullptr;
    bool visibility_ = true;
    double cell_ = 1.0, x0_ = 0.0, y0_ = 0.0, eps_ = 0.0;
    int nx_ = 1, ny_ = 1;
    std::vector<std::uint32_t> start_, items_;
    std::vector<std::uint32_t> cand_start_, cand_items_;
};

/// The nearest obstacle by scanning every part (the oracle's labelling; same distances, same ties).
inline Nearest nearest_brute_force(const Scene& s, const Vec2& p, bool visibility) {
    Nearest best;
    for (std::size_t pi = 0; pi < s.parts.size(); ++pi) {
        const double d = sq_distance(s, s.parts[pi], p, visibility);
        if (d < best.sq || (d == best.sq && s.parts[pi].label < best.label)) {
            best.sq = d;
            best.label = s.parts[pi].label;
            best.part = static_cast<std::int32_t>(pi);
        }
    }
    return best;
}

}  // namespace dvoronoi::gvd
