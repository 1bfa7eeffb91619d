// The cell representation shared by every algorithm: a counter-clockwise cycle of pieces, each a
// straight edge on the bisector with one named neighbour or an arc of the circle |q - center| = radius.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dvoronoi {

/// Marker stored in Piece::neighbor for arc pieces.
inline constexpr Index kArc = -1;

/// One piece of a cell boundary. It starts at `start` and ends where the next piece of the cycle
/// starts (the cycle is closed).
struct Piece {
    /// Edge: index of the agent across the edge (in the caller's indexing). Arc: kArc.
    Index neighbor = kArc;
    /// Start point, in the caller's frame.
    Vec2 start = Vec2::Zero();
    /// Arcs: the counter-clockwise angle swept, in (0, 2*pi]. Edges: 0. Computed from exact
    /// combinatorics plus one atan2/acos per line, so a tiny arc is never mistaken for a full turn.
    double arc_span = 0.0;

    bool is_arc() const noexcept { return neighbor < 0; }
};

/// Area, centroid and perimeter of a cell (circular segments included, never a polygon
/// approximation of the circle). The cell algorithms (emit_cell) compute them within 2^-40 D (area:
/// 2^-40 D^2, D the cell's diameter) of the exact values, see docs/guarantees.md.
struct CellMeasures {
    double area = 0.0;
    Vec2 centroid = Vec2::Zero();
    double perimeter = 0.0;
};

/// A range-limited Voronoi cell V_i ∩ B(center, radius).
///
/// `pieces` is a closed counter-clockwise cycle. An agent with nothing within 2*radius has one arc
/// piece with arc_span = 2*pi starting at center + (radius, 0).
struct LimitedCell {
    Vec2 center = Vec2::Zero();
    double radius = 0.0;
    std::vector<Piece> pieces;
    /// Number of agents within 2*radius that the algorithm examined (m in the papers).
    Index candidates = 0;
    /// RCVC only: chords left after checkChords (M' in the RCVC paper); -1 for other methods.
    Index chords_after_check = -1;

    std::size_t size() const noexcept { return pieces.size(); }

    /// End point of piece k (the start of the next piece, cyclically).
    const Vec2& piece_end(std::size_t k) const { return pieces[(k + 1) % pieces.size()].start; }

    /// Limited neighbours: agents sharing a boundary edge of positive length, ascending.
    std::vector<Index> neighbors() const {
        std::vector<Index> out;
        for (const Piece& p : pieces)
            if (!p.is_arc()) out.push_back(p.neighbor);
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }

    /// Counter-clockwise vertices (the piece start points). Empty for a full disk.
    std::vector<Vec2> vertices() const {
        std::vector<Vec2> out;
        if (pieces.size() == 1 && pieces[0].is_arc()) return out;
        out.reserve(pieces.size());
        for (const Piece& p : pieces) out.push_back(p.start);
        return out;
    }

    /// Area, centroid and perimeter. The algorithms compute them in the agent's own frame, from
    /// vertices relative to the agent (where differences to nearby agents are exact), so their
    /// accuracy does not degrade far from the origin.
    const CellMeasures& measures() const noexcept { return measures_; }

    CellMeasures measures_;
};

}  // namespace dvoronoi
