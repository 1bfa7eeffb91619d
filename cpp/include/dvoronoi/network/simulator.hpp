// The message-passing engine every network algorithm runs on: messages in flight over links,
// delivered one at a time in a seeded random order (asynchronous: any message in flight may arrive
// next, so one seed is one reproducible interleaving and different seeds exercise different ones),
// links that fail per transmission with a given probability (the sender repeats until delivery and
// every try is counted), both counts of docs/spec.md per node and message type — transmissions (radio
// sends: a broadcast to all neighbours is one, a unicast hop is one, every try counted) and link
// deliveries (one per message per link that receives it) —, termination detected when no message is
// in flight, and a message budget that stops a run with an error instead of a hang.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace dvoronoi::network {

/// A run sent more transmissions than its budget allows.
class BudgetExceeded : public Error {
public:
    using Error::Error;
};

/// The two counts of docs/spec.md per node and message type. A transmission is one radio send: a
/// broadcast to all neighbours is one (repeated until every neighbour has it: one per try), a unicast
/// over a link one per try, a multi-hop route one per hop. A link delivery is one message received
/// over one link (a broadcast to k neighbours makes k; a repeated try is not delivered twice).
struct TransmissionCounts {
    std::vector<std::string> types;          ///< message type names (columns)
    std::vector<std::int64_t> sent;          ///< n x types, row-major: transmissions by the node
    std::vector<std::int64_t> received;      ///< n x types: link deliveries to the node
    Index nodes = 0;

    void reset(Index n, std::vector<std::string> names) {
        types = std::move(names);
        nodes = n;
        sent.assign(static_cast<std::size_t>(n) * types.size(), 0);
        received.assign(static_cast<std::size_t>(n) * types.size(), 0);
    }
    std::int64_t total_sent() const {
        std::int64_t t = 0;
        for (auto v : sent) t += v;
        return t;
    }
    std::int64_t total_received() const {
        std::int64_t t = 0;
        for (auto v : received) t += v;
        return t;
    }
    std::int64_t sent_of_type(std::size_t type) const {
        std::int64_t t = 0;
        for (Index i = 0; i < nodes; ++i) t += sent[static_cast<std::size_t>(i) * types.size() + type];
        return t;
    }
    std::int64_t received_of_type(std::size_t type) const {
        std::int64_t t = 0;
        for (Index i = 0; i < nodes; ++i) t += received[static_cast<std::size_t>(i) * types.size() + type];
        return t;
    }
};

/// Per-run settings shared by every algorithm.
struct RunOptions {
    double loss = 0.0;                ///< probability that one try over a link fails, in [0, 1)
    std::uint64_t seed = 0;           ///< delivery order and link failures
    std::int64_t budget = 0;          ///< most transmissions allowed; 0 = 10^9
};

inline void require_run_options(const RunOptions& o) {
    if (!(o.loss >= 0.0 && o.loss < 1.0))
        throw InputError("loss must be a probability in [0, 1), got " + std::to_string(o.loss));
    if (o.budget < 0) throw InputError("budget must be >= 0 (0 = no practical limit), got " + std::to_string(o.budget));
}

/// Messages of type Msg in flight; Msg has `Index to` (the final receiver).
template <class Msg>
class Simulator {
public:
    Simulator(Index nodes, std::vector<std::string> type_names, const RunOptions& opt)
        : rng_(opt.seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL), loss_(opt.loss),
          budget_(opt.budget > 0 ? opt.budget : 1000000000LL) {
        require_run_options(opt);
        counts_.reset(nodes, std::move(type_names));
        if (loss_ > 0.0) fails_ = std::geometric_distribution<std::int64_t>(1.0 - loss_);
    }

    /// One hop of a message of `type` from `from` to `to` (a link): counts the tries (transmissions)
    /// and the link delivery.
    void count_hop(Index from, Index to, std::size_t type) {
        const std::int64_t tries = 1 + (loss_ > 0.0 ? fails_(rng_) : 0);
        const std::size_t T = counts_.types.size();
        counts_.received[static_cast<std::size_t>(to) * T + type] += 1;
        add_transmissions(from, type, tries);
    }

    /// A broadcast of one message of `type` from `from` to every node of `to` (its neighbours): one
    /// transmission per try, repeated until each neighbour has received it (each link fails
    /// independently per try), and one link delivery per neighbour. A node without neighbours still
    /// transmits once.
    void count_broadcast(Index from, const std::vector<Index>& to, std::size_t type) {
        std::int64_t tries = 1;
        const std::size_t T = counts_.types.size();
        for (Index t : to) {
            if (loss_ > 0.0) tries = std::max<std::int64_t>(tries, 1 + fails_(rng_));
            counts_.received[static_cast<std::size_t>(t) * T + type] += 1;
        }
        add_transmissions(from, type, tries);
    }

    /// count_broadcast, and the message make(t) put in flight to every t of `to`.
    template <class Make>
    void broadcast(Index from, const std::vector<Index>& to, std::size_t type, Make&& make) {
        count_broadcast(from, to, type);
        for (Index t : to) inflight_.push_back(make(t));
    }

    /// Puts a message in flight along a route of nodes (route[0] the sender, route.back() the receiver;
    /// each hop is one transmission, counted now). A route of one node is a message to oneself (free).
    void send_along(const std::vector<Index>& route, std::size_t type, Msg msg) {
        for (std::size_t h = 0; h + 1 < route.size(); ++h) count_hop(route[h], route[h + 1], type);
        inflight_.push_back(std::move(msg));
    }

    /// A one-hop message over a link.
    void send(Index from, Index to, std::size_t type, Msg msg) {
        count_hop(from, to, type);
        inflight_.push_back(std::move(msg));
    }

    /// Delivers messages in a random order until none is in flight (termination) and returns how many
    /// were delivered. `handle(msg)` may send more.
    template <class Handler>
    std::int64_t run(Handler&& handle) {
        std::int64_t delivered = 0;
        while (!inflight_.empty()) {
            std::uniform_int_distribution<std::size_t> pick(0, inflight_.size() - 1);
            const std::size_t k = pick(rng_);
            std::swap(inflight_[k], inflight_.back());
            Msg m = std::move(inflight_.back());
            inflight_.pop_back();
            ++delivered;
            handle(m);
        }
        return delivered;
    }

    std::mt19937_64& rng() { return rng_; }
    const TransmissionCounts& counts() const { return counts_; }
    TransmissionCounts& counts() { return counts_; }
    std::int64_t total() const { return total_; }

private:
    void add_transmissions(Index from, std::size_t type, std::int64_t tries) {
        counts_.sent[static_cast<std::size_t>(from) * counts_.types.size() + type] += tries;
        total_ += tries;
        if (total_ > budget_)
            throw BudgetExceeded("message budget of " + std::to_string(budget_) +
                                 " transmissions exceeded with " + std::to_string(inflight_.size()) +
                                 " messages still in flight; raise budget= or check the network");
    }

    std::mt19937_64 rng_;
    double loss_;
    std::int64_t budget_, total_ = 0;
    std::geometric_distribution<std::int64_t> fails_;
    TransmissionCounts counts_;
    std::vector<Msg> inflight_;
};

}  // namespace dvoronoi::network
