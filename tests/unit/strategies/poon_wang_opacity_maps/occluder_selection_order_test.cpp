// SPDX-License-Identifier: MIT
// The greedy order of section 4.3's selection
// (strategies/poon_wang_opacity_maps/occluder_scoring.h,
// order_by_marginal_score): gain and cost counted against what the sets
// chosen before already hide and hold.
#include "strategies/poon_wang_opacity_maps/occluder_scoring.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace occu {
namespace {

using Ids = std::vector<std::uint32_t>;

// Occludees 0..5: 0 and 1 hidden by {1,2}, 2 by {3}, 3 and 4 by {1,4},
// 5 by {1,2,3} only. Costs: occluder 3 costs 1.1, occluder 4 costs 1.5.
// Static scores (gain with the superset rule / cost): d = {1,2,3} hides
// 0, 1, 2, 5: 4 / 3.1 = 1.29; a = {1,2}: 2 / 2 = 1.0; b = {3}: 1 / 1.1 =
// 0.91; c = {1,4}: 2 / 2.5 = 0.8.
TEST(OccluderSelectionOrder, ChosenOccludersCostNothingAndHiddenOccludeesGainNothing)
{
    const std::vector<Ids> sets{{1, 2, 3}, {1, 2}, {3}, {1, 4}};   // d, a, b, c: static order
    const std::vector<std::vector<Ids>> sets_of{{{1, 2}}, {{1, 2}}, {{3}}, {{1, 4}}, {{1, 4}}, {{1, 2, 3}}};
    const std::vector<double> cost{1.0, 1.0, 1.0, 1.1, 1.5};
    // After d, occluder 1 is chosen: c gains 2 for 1.5; a and b hide only
    // what d hides already, so they follow in static order.
    EXPECT_EQ(order_by_marginal_score(sets, sets_of, cost), (std::vector<std::size_t>{0, 3, 1, 2}));
}

TEST(OccluderSelectionOrder, IsAPermutationAndEachStepTakesTheBestMarginalScore)
{
    std::mt19937 rng(6);
    for (int round = 0; round < 50; ++round) {
        std::uniform_int_distribution<std::uint32_t> id(0, 9), size(1, 3), count(1, 3);
        std::vector<std::vector<Ids>> sets_of(12);
        std::vector<Ids> sets;
        for (auto &mos : sets_of)
            for (std::uint32_t k = count(rng); k-- > 0;) {
                Ids s;
                for (std::uint32_t n = size(rng); n-- > 0;)
                    s.push_back(id(rng));
                std::sort(s.begin(), s.end());
                s.erase(std::unique(s.begin(), s.end()), s.end());
                mos.push_back(s);
                if (std::find(sets.begin(), sets.end(), s) == sets.end())
                    sets.push_back(s);
            }
        std::vector<double> cost(10);
        for (double &c : cost)
            c = 1.0 + double(id(rng)) / 4.0;
        const auto order = order_by_marginal_score(sets, sets_of, cost);
        auto sorted = order;
        std::sort(sorted.begin(), sorted.end());
        for (std::size_t i = 0; i < sorted.size(); ++i)
            ASSERT_EQ(sorted[i], i);
        ASSERT_EQ(order.size(), sets.size());

        // Replay: every step's marginal score is the best among the sets left.
        std::vector<bool> chosen(10, false), taken(sets.size(), false);
        auto hidden = [&](std::size_t o) {
            return std::any_of(sets_of[o].begin(), sets_of[o].end(), [&](const Ids &t) {
                return std::all_of(t.begin(), t.end(), [&](std::uint32_t x) { return chosen[x]; });
            });
        };
        auto marginal = [&](std::size_t i, double &gain) {
            gain = 0.0;
            double c = 0.0;
            for (std::size_t o = 0; o < sets_of.size(); ++o)
                gain += !hidden(o) && std::any_of(sets_of[o].begin(), sets_of[o].end(), [&](const Ids &t) {
                    return std::includes(sets[i].begin(), sets[i].end(), t.begin(), t.end());
                });
            for (std::uint32_t x : sets[i])
                c += chosen[x] ? 0.0 : cost[x];
            return gain / std::max(c, 1e-9);
        };
        for (std::size_t step : order) {
            double gain = 0.0;
            const double score = marginal(step, gain);
            if (gain == 0.0)
                break;   // the rest add nothing
            for (std::size_t j = 0; j < sets.size(); ++j) {
                double g = 0.0;
                if (!taken[j]) {
                    EXPECT_LE(marginal(j, g), score + 1e-9) << "round " << round;
                }
            }
            taken[step] = true;
            for (std::uint32_t x : sets[step])
                chosen[x] = true;
        }
        for (std::size_t o = 0; o < sets_of.size(); ++o)
            EXPECT_TRUE(hidden(o)) << "round " << round << ": occludee " << o << " left visible by every set";
    }
}

}  // namespace
}  // namespace occu
