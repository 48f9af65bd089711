// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/minimum_occluder_set.h"

#include <algorithm>

namespace occu {

namespace {

class Search {
public:
    Search(const std::vector<std::vector<OccluderId>> &slots, const MosSearchOptions &o) : slots_(slots), o_(o)
    {
        cancelled_.assign(slots.size(), 0);
    }

    MosSearchResult run()
    {
        for (const auto &s : slots_)
            if (s.empty())
                return result_;   // uncoverable pixels: the occludee is visible
        descend(0);
        finish();
        return std::move(result_);
    }

private:
    double cost_of(OccluderId id) const { return id < o_.cost.size() ? o_.cost[id] : 1.0; }

    // The cost bound for pruning: the most expensive of the kept sets once
    // `keep_cheapest` are kept.
    bool pruned(double cost) const
    {
        if (!o_.keep_cheapest || kept_costs_.size() < o_.keep_cheapest)
            return false;
        return cost > kept_costs_.back();
    }

    void descend(std::size_t from)
    {
        // The first slot not yet cancelled, left to right.
        while (from < slots_.size() && cancelled_[from])
            ++from;
        if (from == slots_.size()) {
            record();
            return;
        }
        for (OccluderId id : slots_[from]) {
            if (o_.step_budget && result_.steps >= o_.step_budget) {
                result_.complete = false;
                return;
            }
            ++result_.steps;
            const double cost = current_cost_ + cost_of(id);
            if (pruned(cost))
                continue;
            current_.push_back(id);
            current_cost_ = cost;
            for (std::size_t s = from; s < slots_.size(); ++s)
                if (std::find(slots_[s].begin(), slots_[s].end(), id) != slots_[s].end())
                    ++cancelled_[s];
            descend(from + 1);
            for (std::size_t s = from; s < slots_.size(); ++s)
                if (std::find(slots_[s].begin(), slots_[s].end(), id) != slots_[s].end())
                    --cancelled_[s];
            current_cost_ -= cost_of(id);
            current_.pop_back();
        }
    }

    bool minimal(const std::vector<OccluderId> &set) const
    {
        // Minimal: every member is the only member of `set` in some slot.
        for (OccluderId id : set) {
            bool needed = false;
            for (const auto &slot : slots_) {
                std::size_t members = 0;
                bool has_id = false;
                for (OccluderId s : slot)
                    if (std::binary_search(set.begin(), set.end(), s)) {
                        ++members;
                        has_id |= s == id;
                    }
                if (has_id && members == 1) {
                    needed = true;
                    break;
                }
            }
            if (!needed)
                return false;
        }
        return true;
    }

    void record()
    {
        std::vector<OccluderId> set = current_;
        std::sort(set.begin(), set.end());
        set.erase(std::unique(set.begin(), set.end()), set.end());
        if (!minimal(set))
            return;
        for (const auto &f : found_)
            if (f.second == set)
                return;   // reached again in another order
        found_.push_back({current_cost_, set});
        if (o_.keep_cheapest) {
            kept_costs_.insert(std::upper_bound(kept_costs_.begin(), kept_costs_.end(), current_cost_), current_cost_);
            if (kept_costs_.size() > o_.keep_cheapest)
                kept_costs_.pop_back();
        }
    }

    void finish()
    {
        std::sort(found_.begin(), found_.end());
        found_.erase(std::unique(found_.begin(), found_.end()), found_.end());
        if (o_.keep_cheapest && found_.size() > o_.keep_cheapest)
            found_.resize(o_.keep_cheapest);
        for (auto &f : found_)
            result_.sets.push_back(std::move(f.second));
    }

    const std::vector<std::vector<OccluderId>> &slots_;
    const MosSearchOptions &o_;
    std::vector<std::uint32_t> cancelled_;   // how many picked occluders cover each slot
    std::vector<OccluderId> current_;
    double current_cost_ = 0.0;
    std::vector<double> kept_costs_;         // ascending, at most keep_cheapest
    std::vector<std::pair<double, std::vector<OccluderId>>> found_;
    MosSearchResult result_;
};

}  // namespace

MosSearchResult minimum_occluder_sets(const std::vector<std::vector<OccluderId>> &slots,
                                      const MosSearchOptions &options)
{
    return Search(slots, options).run();
}

}  // namespace occu

namespace occu {

std::vector<std::vector<OccluderId>> combination_table(std::vector<std::vector<OccluderId>> &stack)
{
    std::vector<std::vector<OccluderId>> slots;
    for (auto &pixel : stack) {
        if (pixel.empty())
            return {};
        std::sort(pixel.begin(), pixel.end());
        slots.push_back(std::move(pixel));
    }
    std::sort(slots.begin(), slots.end());
    slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
    std::stable_sort(slots.begin(), slots.end(), [](const auto &a, const auto &b) { return a.size() < b.size(); });
    return slots;
}

}  // namespace occu
