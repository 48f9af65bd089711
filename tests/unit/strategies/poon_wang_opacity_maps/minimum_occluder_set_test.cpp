// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/minimum_occluder_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <set>

using namespace occu;

namespace {
enum : OccluderId { A, B, C, D };

// All inclusion-minimal sets hitting every slot, by enumeration.
std::set<std::vector<OccluderId>> brute_force(const std::vector<std::vector<OccluderId>> &slots, unsigned ids)
{
    auto covers = [&](unsigned mask) {
        for (const auto &s : slots) {
            bool hit = false;
            for (OccluderId id : s)
                hit |= (mask >> id) & 1;
            if (!hit)
                return false;
        }
        return true;
    };
    std::set<std::vector<OccluderId>> minimal;
    for (unsigned mask = 1; mask < (1u << ids); ++mask) {
        if (!covers(mask))
            continue;
        bool is_minimal = true;
        for (unsigned b = 0; b < ids; ++b)
            if (((mask >> b) & 1) && covers(mask & ~(1u << b)))
                is_minimal = false;
        if (!is_minimal)
            continue;
        std::vector<OccluderId> set;
        for (unsigned b = 0; b < ids; ++b)
            if ((mask >> b) & 1)
                set.push_back(b);
        minimal.insert(set);
    }
    return minimal;
}
}  // namespace

TEST(MinimumOccluderSets, PaperFigure3GivesABCAndACD)
{
    // Pixels covered by A only, by C only, by A and B, by B and D, by C and D.
    const std::vector<std::vector<OccluderId>> table = {{A}, {C}, {A, B}, {B, D}, {C, D}};
    const MosSearchResult r = minimum_occluder_sets(table);
    ASSERT_TRUE(r.complete);
    const std::vector<std::vector<OccluderId>> expected = {{A, B, C}, {A, C, D}};
    EXPECT_EQ(r.sets, expected);
}

TEST(MinimumOccluderSets, UncoveredPixelsMeanNoSet)
{
    EXPECT_TRUE(minimum_occluder_sets({{A}, {}, {B}}).sets.empty());
}

TEST(MinimumOccluderSets, EqualsBruteForceOnRandomSmallTables)
{
    std::mt19937 rng(8);
    for (int trial = 0; trial < 300; ++trial) {
        const unsigned ids = 2 + rng() % 8;
        const unsigned slot_count = 1 + rng() % 10;
        std::vector<std::vector<OccluderId>> table(slot_count);
        for (auto &slot : table) {
            const unsigned size = 1 + rng() % std::min(4u, ids);
            while (slot.size() < size) {
                const OccluderId id = rng() % ids;
                if (std::find(slot.begin(), slot.end(), id) == slot.end())
                    slot.push_back(id);
            }
        }
        std::stable_sort(table.begin(), table.end(), [](const auto &a, const auto &b) { return a.size() < b.size(); });
        const MosSearchResult r = minimum_occluder_sets(table);
        const std::set<std::vector<OccluderId>> got(r.sets.begin(), r.sets.end());
        ASSERT_EQ(got.size(), r.sets.size()) << "duplicates in trial " << trial;
        ASSERT_EQ(got, brute_force(table, ids)) << "trial " << trial;
    }
}

TEST(MinimumOccluderSets, KeepCheapestPrunesButKeepsTheCheapest)
{
    std::mt19937 rng(9);
    for (int trial = 0; trial < 100; ++trial) {
        const unsigned ids = 6;
        std::vector<std::vector<OccluderId>> table(6);
        for (auto &slot : table)
            for (OccluderId id = 0; id < ids; ++id)
                if (rng() % 3 == 0 || (slot.empty() && id == ids - 1))
                    slot.push_back(id);
        MosSearchOptions o;
        for (unsigned i = 0; i < ids; ++i)
            o.cost.push_back(1.0 + double(rng() % 5));
        const MosSearchResult all = minimum_occluder_sets(table, o);
        o.keep_cheapest = 2;
        const MosSearchResult cheap = minimum_occluder_sets(table, o);
        ASSERT_LE(cheap.sets.size(), 2u);
        ASSERT_EQ(cheap.sets.size(), std::min<std::size_t>(2, all.sets.size()));
        auto cost = [&](const std::vector<OccluderId> &s) {
            double c = 0;
            for (OccluderId id : s)
                c += o.cost[id];
            return c;
        };
        // The kept sets cost what the cheapest sets of the full search cost.
        for (std::size_t i = 0; i < cheap.sets.size(); ++i)
            EXPECT_DOUBLE_EQ(cost(cheap.sets[i]), cost(all.sets[i])) << "trial " << trial;
        EXPECT_LE(cheap.steps, all.steps);
    }
}

TEST(MinimumOccluderSets, ExplodingTableStopsWithinItsBudget)
{
    // 32 occluders, each pixel group covered by four of them in a staggered
    // pattern: the number of minimal sets explodes.
    std::vector<std::vector<OccluderId>> table;
    for (OccluderId i = 0; i < 32; ++i)
        table.push_back({i, (i + 1) % 32, (i + 7) % 32, (i + 13) % 32});
    MosSearchOptions o;
    o.step_budget = 200000;
    const auto start = std::chrono::steady_clock::now();
    const MosSearchResult r = minimum_occluder_sets(table, o);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_FALSE(r.complete);
    EXPECT_LE(r.steps, o.step_budget);
    EXPECT_FALSE(r.sets.empty());
    EXPECT_LT(seconds, 10.0);
}
