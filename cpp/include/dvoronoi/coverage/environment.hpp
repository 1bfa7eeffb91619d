// The convex environment Q a swarm covers: an axis-aligned box or a convex polygon. Agents are kept
// inside it and their limited cells are clipped to it (coverage/clip.hpp).
#pragma once

#include "dvoronoi/core/convex_ring.hpp"
#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace dvoronoi {

/// A convex polygon with counter-clockwise vertices (a box is a polygon of four).
///
/// Construction reads the vertex list once with detail::convex_ring, as the exact cells' `bounds`
/// do: either orientation, a closed ring, repeated and straight-on vertices give the same polygon;
/// fewer than three vertices that are not collinear, a reflex turn, a spike or a second winding is
/// an error. Containment is decided exactly; the boundary counts as inside.
class ConvexPolygon {
public:
    ConvexPolygon() = default;

    /// \throws InputError naming `name` and the offending vertex.
    explicit ConvexPolygon(std::vector<Vec2> vertices, const std::string& name = "bounds")
        : v_(detail::convex_ring(std::move(vertices), name)) {
        const std::size_t n = v_.size();
        area_ = 0.0;
        for (std::size_t k = 0; k < n; ++k) {
            const Vec2& a = v_[k];
            const Vec2& b = v_[(k + 1) % n];
            area_ += 0.5 * (a.x() * b.y() - a.y() * b.x());
        }
        for (std::size_t k = 0; k < n; ++k) {
            const Vec2 e = v_[(k + 1) % n] - v_[k];
            normal_.push_back(Vec2(e.y(), -e.x()) / e.norm());
        }
    }

    /// The box [xmin, xmax] x [ymin, ymax]. \throws InputError unless xmin < xmax and ymin < ymax.
    static ConvexPolygon box(double xmin, double ymin, double xmax, double ymax,
                             const std::string& name = "bounds") {
        if (!(xmin < xmax) || !(ymin < ymax) || !std::isfinite(xmin) || !std::isfinite(xmax) ||
            !std::isfinite(ymin) || !std::isfinite(ymax))
            throw InputError(name + " must be a box (xmin, ymin, xmax, ymax) with xmin < xmax and "
                             "ymin < ymax, all finite");
        return ConvexPolygon({Vec2(xmin, ymin), Vec2(xmax, ymin), Vec2(xmax, ymax), Vec2(xmin, ymax)},
                             name);
    }

    std::size_t size() const noexcept { return v_.size(); }
    bool empty() const noexcept { return v_.empty(); }
    const std::vector<Vec2>& vertices() const noexcept { return v_; }
    /// Outward unit normal of edge k (from vertex k to vertex k+1).
    const Vec2& normal(std::size_t k) const { return normal_[k]; }
    double area() const noexcept { return area_; }

    /// Is p in the closed polygon? Exact.
    bool contains(const Vec2& p) const {
        const std::size_t n = v_.size();
        for (std::size_t k = 0; k < n; ++k)
            if (pred::orient(v_[k], v_[(k + 1) % n], p) < 0) return false;
        return true;
    }

private:
    std::vector<Vec2> v_;
    std::vector<Vec2> normal_;
    double area_ = 0.0;
};

}  // namespace dvoronoi
