// Test helpers for the cell algorithms: an exact brute-force reference for limited neighbours
// (quadratic, independent of any scan order) and the degenerate point families.
#pragma once

#include "dvoronoi/cells/bisectors.hpp"
#include "dvoronoi/core/predicates.hpp"

#include <cmath>
#include <set>
#include <vector>

namespace testref {

using dvoronoi::Index;
using dvoronoi::Points;
using dvoronoi::Vec2;
namespace pred = dvoronoi::pred;

/// Limited neighbours of agent i by definition: j (closer than 2R) is one when L_j keeps a part of
/// positive length inside the disk and every other half-plane. All decisions exact.
inline std::set<Index> brute_limited_neighbors(const Points& P, Index i, double R) {
    const Vec2 c = P.row(i).transpose();
    std::vector<Index> near;
    for (Index j = 0; j < P.rows(); ++j)
        if (j != i && pred::within_2r(c, P.row(j).transpose(), R) > 0) near.push_back(j);
    std::set<Index> out;
    for (Index j : near) {
        const Vec2 pj = P.row(j).transpose();
        std::vector<Vec2> lower, upper;
        bool empty = false;
        for (Index l : near) {
            if (l == j) continue;
            const Vec2 pl = P.row(l).transpose();
            const int o = pred::orient(c, pj, pl);
            if (o > 0) upper.push_back(pl);
            else if (o < 0) lower.push_back(pl);
            else if (pred::dot_sign(c, pj, pl) > 0 && pred::compare_distance(c, pl, pj) < 0) empty = true;
        }
        for (const Vec2& u : upper)
            if (!(pred::vertex_position(c, pj, u) >= 0 || pred::vertex_in_disk(c, pj, u, R) < 0)) empty = true;
        for (const Vec2& l : lower)
            if (!(pred::vertex_position(c, pj, l) <= 0 || pred::vertex_in_disk(c, pj, l, R) < 0)) empty = true;
        for (const Vec2& l : lower)
            for (const Vec2& u : upper)
                if (!empty && pred::vertex_side(c, pj, l, u) >= 0) empty = true;
        if (!empty) out.insert(j);
    }
    return out;
}

struct Family {
    const char* name;
    Points pts;
    double radius;
};

inline Points grid(int k, double spacing, Vec2 offset = Vec2::Zero()) {
    Points P(k * k, 2);
    for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) P.row(a * k + b) << offset.x() + a * spacing, offset.y() + b * spacing;
    return P;
}

inline std::vector<Family> degenerate_families() {
    std::vector<Family> f;
    for (double R : {0.5, 0.6, 0.75, 1.0, 1.5, 2.5}) f.push_back({"square lattice", grid(7, 1.0), R});
    {  // hexagonal lattice (rounded coordinates: nearly cocircular sextets)
        Points P(64, 2);
        for (int a = 0; a < 8; ++a)
            for (int b = 0; b < 8; ++b) P.row(a * 8 + b) << a + 0.5 * (b % 2), b * std::sqrt(3.0) / 2;
        for (double R : {0.5, 0.51, 0.58, 1.0}) f.push_back({"hexagonal lattice", P, R});
    }
    {  // 12 integer points exactly on the circle of radius 5, with the center
        Points P(13, 2);
        P << 5, 0, -5, 0, 0, 5, 0, -5, 3, 4, -3, 4, 3, -4, -3, -4, 4, 3, -4, 3, 4, -3, -4, -3, 0, 0;
        for (double R : {2.0, 2.5, 3.0, 5.0, 10.0}) f.push_back({"cocircular with center", P, R});
        f.push_back({"cocircular", Points(P.topRows(12)), 4.0});
        f.push_back({"cocircular", Points(P.topRows(12)), 100.0});
    }
    {  // nearly collinear: a line with 1e-12 jitter plus an exact line
        Points P(40, 2);
        for (int a = 0; a < 20; ++a) {
            P.row(a) << a * 0.5, (a % 3 - 1) * 1e-12;
            P.row(20 + a) << a * 0.5 + 0.25, 1.0;
        }
        for (double R : {0.3, 0.6, 2.0}) f.push_back({"nearly collinear", P, R});
    }
    for (double R : {0.5, 0.75, 1.0, 1.5}) f.push_back({"lattice near 1e7", grid(6, 1.0, Vec2(1e7, -1e7)), R});
    for (double R : {0.5e-9, 0.75e-9, 1e-9, 1.5e-9}) f.push_back({"lattice spacing 1e-9", grid(6, 1e-9, Vec2(0.3, 0.7)), R});
    return f;
}

}  // namespace testref
