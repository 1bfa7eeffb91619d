// Boundary Scan generalised to radical axes (cells/power_boundary_scan.hpp) against the exact
// clipping, on the degenerate families, including agents outside their own cells.
#include "dvoronoi/cells/power_boundary_scan.hpp"

#include "power_families.hpp"

#include <doctest/doctest.h>

using namespace dvoronoi;

namespace {

void scan(const Vec2& c, double r, const std::vector<detail::Candidate>& cand, const std::vector<double>& rs, LimitedCell& out) {
    detail::PowerChordWorkspace ws;
    detail::power_boundary_scan(c, r, cand, rs, out, ws);
}

}  // namespace

TEST_CASE("the generalised Boundary Scan gives the exact clipping's cells") {
    int outside = 0;
    for (const auto& t : power_families::teams()) outside += power_families::check_against_clipping(t, scan);
    CHECK(outside > 20);  // crescents and cells away from their agents were exercised
}

TEST_CASE("equal radii: Boundary Scan's own cells") {
    const auto t = power_families::teams().front();
    std::vector<detail::Candidate> cand;
    std::vector<double> rs;
    for (std::size_t i = 0; i < t.p.size(); ++i) {
        power_families::others_of(t, i, cand, rs);
        LimitedCell got;
        scan(t.p[i], t.r[i], cand, rs, got);
        Points others(static_cast<Index>(cand.size()), 2);
        for (std::size_t k = 0; k < cand.size(); ++k) others.row(static_cast<Index>(k)) = cand[k].p.transpose();
        const LimitedCell bs = boundary_scan_cell(t.p[i], others, t.r[i]);
        std::vector<Index> want;
        for (Index k : bs.neighbors()) want.push_back(cand[static_cast<std::size_t>(k)].id);
        std::sort(want.begin(), want.end());
        CHECK(got.neighbors() == want);
        CHECK(got.measures().area == doctest::Approx(bs.measures().area).epsilon(1e-12));
    }
}

TEST_CASE("the issue's crescent: the small agent keeps the cap beyond the big circle, not its own place") {
    const std::vector<detail::Candidate> big{{Vec2(0, 0), 0}};
    LimitedCell c;
    scan(Vec2(9.5, 0), 1.0, big, {10.0}, c);
    REQUIRE(c.pieces.size() == 2);
    CHECK(c.neighbors() == std::vector<Index>{0});
    CHECK(c.measures().centroid.x() > 10.0);
    // Same place, different radii: the larger holds the cell.
    const std::vector<detail::Candidate> here{{Vec2(1, 1), 0}};
    scan(Vec2(1, 1), 1.0, here, {2.0}, c);
    CHECK(c.pieces.empty());
    scan(Vec2(1, 1), 2.0, here, {1.0}, c);
    CHECK(c.measures().area == doctest::Approx(4 * 3.14159265358979323846));
    CHECK_THROWS_AS(scan(Vec2(1, 1), 2.0, here, {2.0}, c), CoincidentError);
}
