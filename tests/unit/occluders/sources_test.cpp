// SPDX-License-Identifier: MIT
// The shared occluder sources (occluders/sources.h) reach the families
// through what a family declares: every family that names a source has
// each of its settings once, the source's database is read only where the
// family's settings take occluders from it, and a setting the family
// declares itself is not added twice.
#include "occluders/sources.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "culling/databases.h"

using namespace occu;

namespace {

long count_of(const std::vector<SettingSpec> &specs, const std::string &name)
{
    return std::count_if(specs.begin(), specs.end(), [&](const SettingSpec &s) { return s.name == name; });
}

}  // namespace

TEST(OccluderSources, EveryFamilyThatNamesASourceHasItsSettingsOnce)
{
    std::set<std::string> skin_users;
    for (const StrategyFamily &f : strategy_families())
        for (const OccluderSourceUse &use : f.occluder_sources) {
            ASSERT_NE(use.source, nullptr) << f.name;
            if (use.source == &skin_occluder_source())
                skin_users.insert(f.name);
            for (const SettingSpec &s : use.source->settings)
                EXPECT_EQ(count_of(f.settings, s.name), 1) << f.name << " " << s.name;
            for (const DatabaseNeed &d : use.source->databases)
                EXPECT_EQ(std::count_if(f.databases.begin(), f.databases.end(),
                                        [&](const DatabaseNeed &e) { return e.setting == d.setting; }),
                          1)
                    << f.name << " " << d.setting;
        }
    EXPECT_EQ(skin_users, (std::set<std::string>{"skins", "hzb", "hom", "shadow", "planes"}));
}

TEST(OccluderSources, ASourcesDatabaseIsReadOnlyWhereTheFamilyDrawsFromIt)
{
    auto reads_skins = [](const std::string &spec) {
        const StrategyChoice choice = choose_strategy(spec);
        const std::vector<const DatabaseNeed *> read = databases_read(choice);
        return std::any_of(read.begin(), read.end(), [](const DatabaseNeed *d) { return d->setting == "skin-database"; });
    };
    EXPECT_TRUE(reads_skins("skins"));
    EXPECT_TRUE(reads_skins("skins-both"));
    EXPECT_FALSE(reads_skins("skins-drawn"));
    EXPECT_TRUE(reads_skins("hzb"));
    EXPECT_FALSE(reads_skins("hzb-last-frame"));
    EXPECT_TRUE(reads_skins("hom"));
    EXPECT_TRUE(reads_skins("shadow"));
    EXPECT_TRUE(reads_skins("planes:skin-source=brushes"));
    EXPECT_FALSE(reads_skins("ou"));
}

TEST(OccluderSources, AFamilysOwnSettingIsNotAddedTwice)
{
    StrategyFamily f;
    f.name = "test";
    f.settings = {integer_setting("skin-boxes", 2, 1, 4, SettingSpec::Role::cost, "the family's own")};
    f.occluder_sources = {{&skin_occluder_source()}};
    const std::vector<StrategyFamily> done = with_occluder_sources({std::move(f)});
    ASSERT_EQ(done.size(), 1u);
    EXPECT_EQ(count_of(done[0].settings, "skin-boxes"), 1);
    EXPECT_EQ(done[0].settings[0].help, "the family's own");
    EXPECT_EQ(count_of(done[0].settings, "skin-voxel"), 1);
    EXPECT_EQ(done[0].databases.size(), 1u);
}
