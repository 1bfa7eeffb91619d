// One reading of a convex region given as a vertex list, shared by the exact cells' `bounds`
// (cells/clip.hpp) and coverage's environment (coverage/environment.hpp), so that every spelling of
// the same polygon is accepted, or refused, the same way everywhere.
#pragma once

#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace dvoronoi::detail {

/// How many times the edges of a ring that turns the same way (left) at every vertex go round: the
/// edge direction turns by less than pi at each vertex, so it passes the direction (1, 0) once a
/// round, from below to above. Exact: the signs of coordinate differences are comparisons.
inline std::size_t windings(const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    auto upper = [&](std::size_t k) {  // edge k's direction lies in [0, pi)
        const Vec2 &a = v[k], &b = v[(k + 1) % n];
        return b.y() > a.y() || (b.y() == a.y() && b.x() > a.x());
    };
    std::size_t w = 0;
    for (std::size_t k = 0; k < n; ++k) w += !upper(k) && upper((k + 1) % n);
    return w;
}

/// The ring of the polygon `in` describes, in its own orientation, in one spelling: without repeated
/// vertices (a closed ring's last vertex, as GeoJSON and shapely write it, included: `A, B, B, C`) and
/// without vertices on the straight segment between their neighbours. All decided with exact
/// orientation tests and exact comparisons. `at` (if given) receives each kept vertex's index in `in`,
/// for messages that point at what the user wrote. Shared by convex regions (convex_ring) and the grid
/// diagram's obstacle polygons, so that every spelling is accepted, or refused, the same way.
/// \throws InputError naming `name` when the path turns back on itself along one line (a spike:
///         dropping it would change the shape), or fewer than three vertices that are not collinear
///         remain.
inline std::vector<Vec2> clean_ring(const std::vector<Vec2>& in, const std::string& name,
                                    std::vector<std::size_t>* at = nullptr) {
    std::vector<Vec2> v;
    std::vector<std::size_t> from;
    for (std::size_t k = 0; k < in.size(); ++k)
        if (v.empty() || !(in[k] == v.back())) v.push_back(in[k]), from.push_back(k);
    while (v.size() > 1 && v.back() == v.front()) v.pop_back(), from.pop_back();  // the closing vertex, repeated
    const std::size_t m = v.size();
    const auto no_polygon = [&](const std::string& why) {
        return InputError(name + ": a polygon needs at least three vertices that are not collinear (" + why + ")");
    };
    // All on one line: say so before a straight-back turn would be called a spike.
    bool turns = false;
    for (std::size_t k = 0; k < m && m >= 3 && !turns; ++k)
        turns = pred::orient(v[(k + m - 1) % m], v[k], v[(k + 1) % m]) != 0;
    if (!turns)
        throw no_polygon(m < 3 ? std::to_string(m) + " distinct" : "all " + std::to_string(m) + " lie on one line");
    std::vector<Vec2> kept;
    if (at) at->clear();
    for (std::size_t k = 0; k < m; ++k) {
        const Vec2& a = v[(k + m - 1) % m];
        const Vec2& b = v[k];
        const Vec2& c = v[(k + 1) % m];
        if (pred::orient(a, b, c) == 0) {
            // Straight on (b between a and c: exact coordinate comparisons) is dropped; turning
            // back is a spike.
            const bool between = (std::min(a.x(), c.x()) <= b.x() && b.x() <= std::max(a.x(), c.x())) &&
                                 (std::min(a.y(), c.y()) <= b.y() && b.y() <= std::max(a.y(), c.y()));
            if (!between)
                throw InputError(name + ": the polygon turns back on itself at vertex " + std::to_string(from[k]) +
                                 " (its edges overlap)");
            continue;
        }
        kept.push_back(b);
        if (at) at->push_back(from[k]);
    }
    // a ring that turns somewhere keeps at least three corners
    if (kept.size() < 3) throw no_polygon(std::to_string(kept.size()) + " corners");
    return kept;
}

/// The strictly convex, counter-clockwise vertex ring of the polygon `v` describes (clean_ring's
/// spellings). The ring starts at the first vertex that is kept.
/// \throws InputError naming `name` when a coordinate is not finite, as clean_ring, when the path
///         turns both ways (not convex) or winds more than once.
inline std::vector<Vec2> convex_ring(const std::vector<Vec2>& v, const std::string& name) {
    for (std::size_t k = 0; k < v.size(); ++k)
        require_finite_point(v[k], name + "[" + std::to_string(k) + "]");
    std::vector<std::size_t> at;
    std::vector<Vec2> kept = clean_ring(v, name, &at);
    const std::size_t m = kept.size();
    int turn = 0;
    for (std::size_t k = 0; k < m; ++k) {
        const int o = pred::orient(kept[(k + m - 1) % m], kept[k], kept[(k + 1) % m]);
        if (turn != 0 && o != turn)
            throw InputError(name + ": the polygon is not convex (vertex " + std::to_string(at[k]) +
                             " turns the other way)");
        turn = o;
    }
    if (turn < 0) std::reverse(kept.begin(), kept.end());
    // The turns all agree, so the polygon is simple exactly when it goes round once.
    if (windings(kept) != 1) throw InputError(name + ": the polygon winds around more than once (not simple)");
    return kept;
}

}  // namespace dvoronoi::detail
