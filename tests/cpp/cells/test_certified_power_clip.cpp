// The certified fast path of heterogeneous cells (cells/certified_power_clip.hpp): where it decides,
// the exact clipping's cells; on exact ties it gives up rather than guess.
#include "dvoronoi/cells/certified_power_clip.hpp"

#include "power_families.hpp"

#include <doctest/doctest.h>

using namespace dvoronoi;

namespace {

int decided = 0, gave_up = 0;

void fast(const Vec2& c, double r, const std::vector<detail::Candidate>& cand, const std::vector<double>& rs, LimitedCell& out) {
    detail::PowerClipWorkspace w;
    w.start(c, r);
    for (std::size_t k = 0; k < cand.size(); ++k) w.add(cand[k].p, rs[k], cand[k].id);
    if (detail::certified_power_clip_loaded(out, w)) {
        ++decided;
        return;
    }
    ++gave_up;
    detail::PowerWorkspace ws;
    detail::power_cell(c, r, cand, rs, out, ws);
}

}  // namespace

TEST_CASE("the fast path gives the exact clipping's cells, and gives up on ties") {
    for (const auto& t : power_families::teams()) power_families::check_against_clipping(t, fast);
    CHECK(decided > 300);
    CHECK(gave_up > 0);  // lattices and radical centres have exact ties
}

TEST_CASE("three radical axes through one point inside the disk: the exact route decides") {
    // Power -144 at the origin for all: the fast path cannot certify the vertex's side.
    const std::vector<detail::Candidate> cand{{Vec2(0, 9), 1}, {Vec2(-16, 0), 2}, {Vec2(0, -5), 3}};
    detail::PowerClipWorkspace w;
    w.start(Vec2(5, 0), 13.0);
    for (std::size_t k = 0; k < cand.size(); ++k) w.add(cand[k].p, std::vector<double>{15, 20, 13}[k], cand[k].id);
    LimitedCell c;
    CHECK(!detail::certified_power_clip_loaded(c, w));
}

TEST_CASE("a disk inside a bigger one is empty at step 1") {
    detail::PowerClipWorkspace w;
    w.start(Vec2(0.5, 0), 0.25);
    w.add(Vec2(0, 0), 1.0, 0);
    LimitedCell c;
    c.pieces.resize(3);
    REQUIRE(detail::certified_power_clip_loaded(c, w));
    CHECK(c.pieces.empty());
    CHECK(c.measures().area == 0.0);
    CHECK(c.measures().centroid == Vec2(0.5, 0));
}

TEST_CASE("a ring of small disks cutting caps off a big one: an arc after every edge") {
    // The big disk (r = 1) keeps all but k caps; the clipper holds 2 k vertices.
    for (int k : {9, 16, 24}) {
        std::vector<detail::Candidate> cand;
        std::vector<double> rs;
        detail::PowerClipWorkspace w;
        w.start(Vec2(0, 0), 1.0);
        for (int t = 0; t < k; ++t) {
            const double a = 2 * 3.14159265358979 * t / k + 0.1, d = 1.05 + 0.001 * t;
            cand.push_back({Vec2(d * std::cos(a), d * std::sin(a)), t});
            rs.push_back(0.1);
            w.add(cand.back().p, 0.1, t);
        }
        LimitedCell fast, exact;
        REQUIRE(detail::certified_power_clip_loaded(fast, w));
        detail::PowerWorkspace ws;
        detail::power_cell(Vec2(0, 0), 1.0, cand, rs, exact, ws);
        CHECK(fast.pieces.size() == static_cast<std::size_t>(2 * k));
        CHECK(power_families::labels(fast) == power_families::labels(exact));
        CHECK(fast.measures().area == doctest::Approx(exact.measures().area).epsilon(1e-13));
    }
}
