// One agent's range-limited Voronoi cell V_i ∩ B(p_i, R), as a robot computes it from the positions it
// knows. Pure function of (center, others, radius): no I/O, no threads, no global state.
#pragma once

#include "dvoronoi/cells/boundary_scan.hpp"
#include "dvoronoi/cells/rcvc.hpp"

#include <string>

namespace dvoronoi {

/// Which algorithm computes the limited cell (docs/spec.md, API conventions). All three return the
/// same cells.
enum class Method {
    /// Our certified fast path (default): in the all-agents drivers, incremental clipping with
    /// certified floating-point decisions (cells/certified_clip.hpp), Boundary Scan where it gives
    /// up; for one agent (limited_cell), Boundary Scan. Not a published algorithm.
    Auto,
    Scan,    ///< Boundary Scan (He, Feng & Ren 2018) on every agent: O(m log m).
    Chords,  ///< RCVC (Guruprasad & Dasgupta 2012) on every agent: checkChords is O(m^2) worst case.
};

inline Method parse_method(const std::string& name) {
    if (name == "auto") return Method::Auto;
    if (name == "scan") return Method::Scan;
    if (name == "chords") return Method::Chords;
    throw InputError("method must be \"auto\", \"scan\" or \"chords\", got \"" + name + "\"");
}

inline const char* method_name(Method m) {
    return m == Method::Auto ? "auto" : m == Method::Scan ? "scan" : "chords";
}

/// The limited cell of the agent at `center` among the agents `others` (any frame; only positions
/// closer than 2*radius matter, the rest are ignored).
///
/// Edge pieces name their neighbour by its row in `others`. Combinatorics (which agents are limited
/// neighbours, the order of pieces, whether two edges meet inside the disk) are decided with exact
/// predicates; vertex coordinates, arc spans and measures are within 2^-40 of the cell's diameter of
/// the exact values (docs/guarantees.md, core/accurate.hpp).
///
/// \throws InputError if `radius` is not positive and finite, a coordinate is NaN or inf.
/// \throws CoincidentError if an agent of `others` lies at `center` or two agents within 2*radius
///         coincide (the error names them).
/// \throws RangeError if `radius` lies outside [kMinRadius, kMaxRadius], an exact test over- or
///         underflows (coordinates far outside the exact range, core/expansion.hpp), or Chords has
///         more than kMaxChordsCandidates agents within 2*radius.
/// \note Thread-safe (pure function). Complexity O(m log m) for Auto and Scan (both run Boundary
///       Scan here), O(m^2) worst case for Chords,
///       m = agents within 2*radius (at most kMaxChordsCandidates for Chords).
inline LimitedCell limited_cell(const Vec2& center, PointsRef others, double radius,
                                Method method = Method::Auto) {
    detail::require_finite_radius(radius);
    detail::require_finite_point(center, "center");
    detail::require_finite_points(others, "others");
    // One agent: Auto is Boundary Scan (the clipping filter needs candidates known to be distinct,
    // and Boundary Scan's errors name coinciding agents).
    return method == Method::Chords ? rcvc_cell(center, others, radius)
                                    : boundary_scan_cell(center, others, radius);
}

}  // namespace dvoronoi
