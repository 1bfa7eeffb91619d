// The range-limited Voronoi partition as flat arrays: the result of limited_cells (and of its
// heterogeneous-radius overload, partition/power_partition.hpp), read by io/, the CLI and the bindings.
#pragma once

#include "dvoronoi/cells/limited_cell.hpp"

#include <string>
#include <utility>
#include <vector>

namespace dvoronoi {

/// How many cells each algorithm computed in one limited_cells call (they add up to n).
struct AlgorithmCounts {
    Index clip = 0;    ///< the certified clipping filter (cells/certified_clip.hpp; Method::Auto only)
    Index scan = 0;    ///< Boundary Scan (every cell under Method::Scan; the filter's give-ups under Auto)
    Index chords = 0;  ///< RCVC (Method::Chords)
    Index power = 0;   ///< the power-cell clipping of heterogeneous radii (cells/power_cell.hpp)

    /// Adds a thread's counts (each driver sums its threads' counts this way).
    AlgorithmCounts& operator+=(const AlgorithmCounts& o) {
        clip += o.clip;
        scan += o.scan;
        chords += o.chords;
        power += o.power;
        return *this;
    }
};

/// The range-limited Voronoi partition of n agents (the result of limited_cells).
///
/// Cells are stored flat: agent i owns pieces [piece_ptr[i], piece_ptr[i+1]); a piece starts at
/// (piece_x, piece_y), ends where the next piece of the same agent starts (cyclically), and is an edge
/// with neighbour piece_neighbor >= 0 or an arc (kArc) sweeping piece_span radians.
/// Limited neighbours are the CSR pair (indptr, indices), ascending per agent (scipy's layout).
struct LimitedPartition {
    double radius = 0.0;
    /// One radius per agent (heterogeneous teams, partition/power_partition.hpp); empty when every
    /// agent has `radius` (then radius_of(i) is `radius`).
    std::vector<double> radii;
    Method method = Method::Auto;
    AlgorithmCounts computed_by;  ///< which algorithm computed how many of the cells
    Points points;  ///< the agents, as given
    std::vector<Index> piece_ptr{0};
    std::vector<Index> piece_neighbor;
    std::vector<double> piece_x, piece_y, piece_span;
    std::vector<Index> indptr{0};
    std::vector<Index> indices;
    std::vector<double> areas, perimeters;
    Points centroids;
    std::vector<Index> candidates;  ///< agents within 2R examined per agent

    Index size() const noexcept { return static_cast<Index>(points.rows()); }

    /// Agent i's radius.
    double radius_of(Index i) const { return radii.empty() ? radius : radii[static_cast<std::size_t>(i)]; }

    /// True when agent i's cell has zero area (heterogeneous teams only: a larger disk covers it).
    bool is_empty(Index i) const {
        check_index(i);
        return piece_ptr[static_cast<std::size_t>(i)] == piece_ptr[static_cast<std::size_t>(i) + 1];
    }

    /// Agent i's cell, rebuilt from the flat arrays.
    LimitedCell cell(Index i) const {
        check_index(i);
        LimitedCell c;
        c.center = points.row(i).transpose();
        c.radius = radius_of(i);
        c.candidates = candidates[static_cast<std::size_t>(i)];
        c.chords_after_check = -1;
        const auto ii = static_cast<std::size_t>(i);
        c.measures_.area = areas[ii];
        c.measures_.perimeter = perimeters[ii];
        c.measures_.centroid = centroids.row(i).transpose();
        for (Index k = piece_ptr[i]; k < piece_ptr[i + 1]; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            Piece p;
            p.neighbor = piece_neighbor[kk];
            p.start = Vec2(piece_x[kk], piece_y[kk]);
            p.arc_span = piece_span[kk];
            c.pieces.push_back(p);
        }
        return c;
    }

    /// Limited neighbours of agent i, ascending (a view into `indices`).
    std::pair<const Index*, const Index*> neighbors(Index i) const {
        check_index(i);
        return {indices.data() + indptr[i], indices.data() + indptr[i + 1]};
    }

    void check_index(Index i) const {
        if (i < 0 || i >= size())
            throw InputError("agent index " + std::to_string(i) + " out of range [0, " +
                             std::to_string(size()) + ")");
    }
};

}  // namespace dvoronoi
