// RCVC generalised to radical axes (cells/power_rcvc.hpp) against the exact clipping, on the
// issue's degenerate families, including agents outside their own cells.
#include "dvoronoi/cells/power_rcvc.hpp"

#include "power_families.hpp"

#include <doctest/doctest.h>

using namespace dvoronoi;

namespace {

void walk(const Vec2& c, double r, const std::vector<detail::Candidate>& cand, const std::vector<double>& rs, LimitedCell& out) {
    detail::PowerChordWorkspace ws;
    detail::power_rcvc(c, r, cand, rs, out, ws);
}

}  // namespace

TEST_CASE("the generalised RCVC gives the exact clipping's cells") {
    int outside = 0;
    for (const auto& t : power_families::teams()) outside += power_families::check_against_clipping(t, walk);
    CHECK(outside > 20);
}

TEST_CASE("checkChords: a chord beyond another is redundant or leaves an empty cell") {
    // Agent at the origin (r = 1). Agent 0's disk covers most of it (its chord is near x = 0.9,
    // c is outside its half-plane: the cell is the cap x > 0.9); agent 1's axis, x = -0.5, lies
    // beyond it on c's side: redundant.
    const std::vector<detail::Candidate> cand{{Vec2(-5, 0), 0}, {Vec2(-1, 0), 1}};
    const double R0 = std::sqrt(25.0 + 1.0 + 2.0 * 5 * 0.9), R1 = 1.0;  // axis of 0 at x = 0.9; of 1 at x = -0.5
    LimitedCell c;
    walk(Vec2(0, 0), 1.0, cand, {R0, R1}, c);
    CHECK(c.neighbors() == std::vector<Index>{0});
    CHECK(c.chords_after_check == 1);
    // Agent 1 on the other side with its axis at x = 0.5 < 0.9 and facing away: nothing is left.
    const std::vector<detail::Candidate> cand2{{Vec2(-5, 0), 0}, {Vec2(1, 0), 1}};
    walk(Vec2(0, 0), 1.0, cand2, {R0, 1.0}, c);
    CHECK(c.pieces.empty());
    CHECK(c.measures().area == 0.0);
}

TEST_CASE("more agents than RCVC accepts name the method") {
    std::vector<detail::Candidate> cand;
    std::vector<double> rs;
    // Agents on a circle of radius 1.5 around c, radius 1: every radical axis cuts the unit disk.
    for (std::size_t k = 0; k <= kMaxChordsCandidates; ++k) {
        const double a = 6.283185307179586 * static_cast<double>(k) / static_cast<double>(kMaxChordsCandidates + 1);
        cand.push_back({Vec2(1.5 * std::cos(a), 1.5 * std::sin(a)), static_cast<Index>(k)});
        rs.push_back(1.0);
    }
    LimitedCell c;
    CHECK_THROWS_WITH_AS(walk(Vec2(0, 0), 1.0, cand, rs, c), doctest::Contains("chords"), RangeError);
    // As many agents far away (their axes miss the disk) are no reason to refuse.
    for (auto& q : cand) q.p *= 10.0;
    walk(Vec2(0, 0), 1.0, cand, rs, c);
    CHECK(c.pieces.size() == 1);  // the whole disk
}
