// SPDX-License-Identifier: MIT
#include "strategy_variants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

namespace occu::integration {

std::vector<StrategyTestVariant> conservative_test_variants()
{
    std::vector<StrategyTestVariant> variants;
    for (const std::string &name : strategy_names())
        if (choose_strategy(name).conservative())
            variants.emplace_back(name);
    for (const StrategyFamily &family : strategy_families())
        for (const StrategyTestVariant &v : family.test_variants)
            variants.push_back(v);
    return variants;
}

std::string variant_label(const StrategyTestVariant &variant)
{
    return variant.spec + "/" + std::to_string(variant.batch) + (variant.coherence ? "/coherent" : "") +
           (variant.probing_switch_off ? "/probes" : "");
}

SessionOptions checking_session_options(DatabaseProvider *databases)
{
    SessionOptions so;
    so.coherence = false;
    so.switch_off = 0.0;
    so.lost_pixels = SessionOptions::PixelCheck::all;
    so.allocator = AllocatorPolicy::system;
    for (float &c : so.clear_colour)
        c = 0.0f;
    so.databases = databases;
    return so;
}

SessionStrategy &add_variant(MeasurementSession &session, const StrategyTestVariant &variant,
                             const std::vector<std::string> &common)
{
    SessionStrategy &s = session.add(variant.spec, common, variant_label(variant), variant.batch);
    if (variant.coherence)
        s.policies.coherence.emplace(3);
    if (variant.probing_switch_off) {
        // Off after the first frame (no gain is enough), probing as soon as it may.
        SwitchOff::Settings probing;
        probing.min_gain = 1e9;
        probing.probe_period = 1;
        s.policies.switch_off.emplace(probing);
    }
    return s;
}

std::string visible_leaves_not_drawn(const StrategyFrame &frame)
{
    if (!frame.frame || !frame.frame->truth)
        return " none";
    const std::set<std::uint32_t> drawn(frame.stats.drawn.begin(), frame.stats.drawn.end());
    std::ostringstream out;
    for (std::uint32_t leaf : frame.frame->truth->visible)
        if (!drawn.count(leaf))
            out << ' ' << leaf;
    return out.str().empty() ? " none" : out.str();
}

std::size_t expect_declared_bounds(const MeasurementSession &session, const std::vector<StrategyTestVariant> &variants)
{
    std::map<std::string, double> triangles;
    for (const SessionStrategy &s : session.strategies())
        triangles[s.label] = s.measured.triangles;
    std::size_t checked = 0;
    for (const StrategyTestVariant &v : variants)
        for (const StrategyTestVariant::Bound &bound : v.draws_at_most) {
            const std::string label = variant_label(v);
            const std::string other = variant_label(StrategyTestVariant(bound.spec));
            if (!triangles.count(label) || !triangles.count(other)) {
                ADD_FAILURE() << label << " declares a bound by " << other << ", and one of them did not run";
                continue;
            }
            EXPECT_LE(triangles[label], bound.share * triangles[other])
                << label << " drew more triangles than " << bound.share << " times what " << other << " drew";
            ++checked;
        }
    return checked;
}

}  // namespace occu::integration
