// The CSV of a network simulation (network/run.hpp): one row per node with the columns of the other
// writers (io/csv.hpp) — `agent,x,y,neighbors` (space-separated, ascending) — then `area`, and the
// transmissions (`sent_<type>`) and link deliveries (`received_<type>`) per message type, DV-Hop's
// types first.
#pragma once

#include "dvoronoi/network/run.hpp"

#include <ostream>
#include <variant>

namespace dvoronoi::io {

inline void write_network_csv(std::ostream& os, const network::Result& result) {
    const network::RunBase& r = network::base(result);
    static const network::TransmissionCounts none;
    const network::TransmissionCounts& dv =
        std::holds_alternative<network::BsRun>(result) ? std::get<network::BsRun>(result).dv_hop_counts : none;
    const network::TransmissionCounts& c = r.counts;
    const bool areas = !r.cells.areas.empty();
    const auto old_precision = os.precision(17);
    os << "agent,x,y,neighbors";
    if (areas) os << ",area";
    for (const auto& t : dv.types) os << ",sent_" << t << ",received_" << t;
    for (const auto& t : c.types) os << ",sent_" << t << ",received_" << t;
    os << '\n';
    for (Index i = 0; i < r.size(); ++i) {
        const auto ii = static_cast<std::size_t>(i);
        os << i << ',' << r.points(i, 0) << ',' << r.points(i, 1) << ',';
        for (Index q = r.indptr[ii]; q < r.indptr[ii + 1]; ++q)
            os << (q > r.indptr[ii] ? " " : "") << r.indices[static_cast<std::size_t>(q)];
        if (areas) os << ',' << r.cells.areas[ii];
        for (std::size_t t = 0; t < dv.types.size(); ++t)
            os << ',' << dv.sent[ii * dv.types.size() + t] << ',' << dv.received[ii * dv.types.size() + t];
        for (std::size_t t = 0; t < c.types.size(); ++t)
            os << ',' << c.sent[ii * c.types.size() + t] << ',' << c.received[ii * c.types.size() + t];
        os << '\n';
    }
    os.precision(old_precision);
}

}  // namespace dvoronoi::io
