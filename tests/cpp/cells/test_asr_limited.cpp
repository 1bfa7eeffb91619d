// The limited cell by the routes the Boundary Scan paper times (EVT, ASR+BS, ASR+EVT) equals the
// Boundary Scan limited cell (itself checked against the CGAL oracle): same pieces, neighbours and
// area, on uniform inputs of every density of the paper's Figure 8 and on half-integer lattices
// (exact ties: cocircular vertices, agents at exactly 2R, vertices exactly on the circle).
#include "dvoronoi/cells/asr_limited.hpp"
#include "dvoronoi/cells/limited_cell.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace dvoronoi;

namespace {

bool same_cell(const LimitedCell& a, const LimitedCell& b) {
    if (a.neighbors() != b.neighbors() || a.pieces.size() != b.pieces.size()) return false;
    // The same cycle of pieces (edges by neighbour, arcs), whichever piece each starts from.
    const std::size_t m = a.pieces.size();
    bool rotation = false;
    for (std::size_t off = 0; off < m && !rotation; ++off) {
        rotation = true;
        for (std::size_t t = 0; t < m && rotation; ++t)
            rotation = a.pieces[t].neighbor == b.pieces[(t + off) % m].neighbor;
    }
    return rotation && std::fabs(a.measures().area - b.measures().area) <= 1e-12 * (1.0 + a.measures().area);
}

}  // namespace

TEST_CASE("EVT, ASR+BS and ASR+EVT give the Boundary Scan limited cell") {
    std::mt19937_64 rng(5);
    int compared = 0, bad = 0, early = 0;
    for (int rep = 0; rep < 150; ++rep) {
        const int n = 30 + rep % 120;
        const double side = 1.0 + rep % 15;  // Figure 8's densities (R = 0.5)
        std::uniform_real_distribution<double> u(0.0, side);
        Points p(n, 2);
        for (int i = 0; i < n; ++i) {
            p(i, 0) = u(rng);
            p(i, 1) = u(rng);
        }
        if (rep % 3 == 0) {  // distinct sites of a half-unit lattice: exact degeneracies
            const int w = static_cast<int>(std::ceil(std::sqrt(2.0 * n)));
            std::vector<int> sites(static_cast<std::size_t>(w * w));
            for (int k = 0; k < w * w; ++k) sites[static_cast<std::size_t>(k)] = k;
            std::shuffle(sites.begin(), sites.end(), rng);
            for (int i = 0; i < n; ++i) {
                p(i, 0) = 0.5 * (sites[static_cast<std::size_t>(i)] % w);
                p(i, 1) = 0.5 * (sites[static_cast<std::size_t>(i)] / w);
            }
        }
        for (int i = 0; i < n; ++i) {
            Points others(n - 1, 2);
            for (int j = 0, k = 0; j < n; ++j)
                if (j != i) others.row(k++) = p.row(j);
            const Vec2 c = p.row(i).transpose();
            const LimitedCell want = limited_cell(c, others, 0.5);
            int steps = 0;
            const LimitedCell asr_bs = asr_limited_cell(c, others, 0.5, LimitedInner::Scan, &steps);
            const LimitedCell asr_evt = asr_limited_cell(c, others, 0.5, LimitedInner::Evt);
            detail::CellWorkspace ws;
            detail::DelaunayWorkspace dws;
            LimitedCell evt;
            detail::evt_limited_cell(c, detail::candidates_within_2r(c, others, 0.5), 0.5, evt, ws, dws);
            bad += !same_cell(want, asr_bs) + !same_cell(want, asr_evt) + !same_cell(want, evt);
            early += steps > 0 && asr_bs.candidates < want.candidates;
            ++compared;
        }
    }
    CHECK(compared > 10000);
    CHECK(early > 500);  // ASR often stops before the full radius
    CHECK(bad == 0);
}
