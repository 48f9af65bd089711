// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/occluder_scoring.h"

#include <algorithm>
#include <map>

namespace occu {

ScoredSets score_sets(const std::vector<std::vector<OccluderSet>> &sets_of, const std::vector<double> &cost)
{
    std::map<OccluderSet, double> gain;
    for (const auto &sets : sets_of)
        for (const OccluderSet &set : sets)
            gain[set] += 1.0;
    auto cost_of = [&cost](std::uint32_t id) { return id < cost.size() ? cost[id] : 1.0; };
    struct Scored {
        double score;
        const OccluderSet *set;
    };
    std::vector<Scored> scored;
    for (const auto &[set, g] : gain) {
        // The superset rule: a set also occludes what its subsets do.
        double total = g, c = 0.0;
        for (const auto &[other, og] : gain)
            if (other.size() < set.size() && std::includes(set.begin(), set.end(), other.begin(), other.end()))
                total += og;
        for (std::uint32_t id : set)
            c += cost_of(id);
        scored.push_back({total / c, &set});
    }
    std::stable_sort(scored.begin(), scored.end(), [](const Scored &a, const Scored &b) { return a.score > b.score; });
    ScoredSets out;
    for (const Scored &s : scored) {
        out.sets.push_back(*s.set);
        out.scores.push_back(s.score);
    }
    return out;
}

std::vector<std::size_t> order_by_marginal_score(const std::vector<OccluderSet> &sets,
                                                 const std::vector<std::vector<OccluderSet>> &sets_of,
                                                 const std::vector<double> &cost)
{
    const std::size_t count = sets.size();
    auto is_subset = [](const std::vector<std::uint32_t> &t, const std::vector<std::uint32_t> &s) {
        return t.size() <= s.size() && std::includes(s.begin(), s.end(), t.begin(), t.end());
    };
    // covers[i]: occludees one of whose sets is a subset of set i.
    std::vector<std::vector<std::uint32_t>> covers(count);
    for (std::uint32_t o = 0; o < sets_of.size(); ++o)
        for (std::size_t i = 0; i < count; ++i)
            if (std::any_of(sets_of[o].begin(), sets_of[o].end(), [&](const auto &t) { return is_subset(t, sets[i]); }))
                covers[i].push_back(o);
    std::vector<bool> hidden(sets_of.size(), false), used(count, false), chosen;
    auto is_chosen = [&chosen](std::uint32_t id) { return id < chosen.size() && chosen[id]; };
    auto cost_of = [&cost](std::uint32_t id) { return id < cost.size() ? cost[id] : 1.0; };
    std::vector<std::size_t> order;
    for (;;) {
        std::size_t best = count;
        double best_score = 0.0;
        for (std::size_t i = 0; i < count; ++i) {
            if (used[i])
                continue;
            double g = 0.0, c = 0.0;
            for (std::uint32_t o : covers[i])
                g += !hidden[o];
            for (std::uint32_t id : sets[i])
                c += is_chosen(id) ? 0.0 : cost_of(id);
            const double score = g / std::max(c, 1e-9);
            if (g > 0.0 && score > best_score) {
                best_score = score;
                best = i;
            }
        }
        if (best == count)
            break;
        used[best] = true;
        order.push_back(best);
        for (std::uint32_t id : sets[best]) {
            if (id >= chosen.size())
                chosen.resize(std::size_t(id) + 1, false);
            chosen[id] = true;
        }
        for (std::uint32_t o = 0; o < sets_of.size(); ++o)
            hidden[o] = hidden[o] || std::any_of(sets_of[o].begin(), sets_of[o].end(), [&](const auto &t) {
                            return std::all_of(t.begin(), t.end(), is_chosen);
                        });
    }
    for (std::size_t i = 0; i < count; ++i)
        if (!used[i])
            order.push_back(i);
    return order;
}

std::vector<std::uint32_t> select_without_redundancy(IdBuffer &ids, const Camera &camera,
                                                     const std::vector<OccluderSet> &sets, std::size_t nodes,
                                                     int resolution, std::size_t max_occluders)
{
    std::vector<std::uint32_t> selected;
    std::vector<bool> in_selection(nodes, false);
    const std::size_t batch = 16;
    std::size_t next = 0;
    while (next < sets.size() && selected.size() < max_occluders) {
        const std::size_t before = selected.size();
        for (; next < sets.size() && selected.size() < before + batch; ++next)
            for (std::uint32_t c : sets[next])
                if (c < nodes && !in_selection[c]) {
                    in_selection[c] = true;
                    selected.push_back(c);
                }
        const auto shown = pixels_per_leaf(ids.render(camera, selected, resolution, resolution), nodes);
        std::vector<std::uint32_t> kept;
        // Hidden or redundant occluders stay marked, so later sets do not bring them back.
        for (std::uint32_t c : selected)
            if (shown[c])
                kept.push_back(c);
        selected = std::move(kept);
    }
    if (selected.size() > max_occluders)
        selected.resize(max_occluders);
    return selected;
}

}  // namespace occu
