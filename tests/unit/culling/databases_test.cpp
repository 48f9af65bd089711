// The resource provider (culling/databases.h), with a family of its own:
// a database is made the first time it is asked for and found afterwards
// (in this provider and in another on the same directory), a provenance
// that differs names another file, only what the settings read and do not
// name is made, optional databases only when asked, and a making that
// fails leaves no file behind.
#include "culling/databases.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "gl/offscreen_context.h"
#include "render/scene_renderer.h"

using namespace occu;

namespace {

int made = 0;

StrategyFamily counting_family()
{
    StrategyFamily f;
    f.name = "counting";
    f.settings = {choice_setting("use", {"yes", "no"}, "whether it reads the table"),
                  integer_setting("size", 3, 1, 100, SettingSpec::Role::choice, "the table's size"),
                  choice_setting("fail", {"no", "yes"}, "whether making the table fails"),
                  path_setting("table", "the table"), path_setting("extra", "an optional one")};
    DatabaseNeed table;
    table.setting = "table";
    table.name = "table";
    table.required = true;
    table.read_by = [](const Settings &s) { return s.text("use") == "yes"; };
    table.provenance = [](const DatabaseRequest &r) {
        return "table size " + r.settings.text("size") + " width " + std::to_string(r.width);
    };
    table.make = [](const DatabaseRequest &r, const std::string &path) {
        if (r.settings.text("fail") == "yes") {
            std::ofstream(path) << "half";
            throw std::runtime_error("no table today");
        }
        ++made;
        std::ofstream(path) << "table " << r.settings.text("size") << '\n';
    };
    DatabaseNeed extra = table;
    extra.setting = "extra";
    extra.name = "extra";
    extra.required = false;
    f.databases = {table, extra};
    return f;
}

StrategyChoice choice_of(const StrategyFamily &f, const std::string &settings)
{
    StrategyChoice c{f.name, f.name, &f, Settings(f.name, &f.settings)};
    c.settings.set_all(settings);
    return c;
}

}  // namespace

TEST(DatabaseProvider, MakesOnceFindsAfterAndKeysByProvenance)
{
    gl::OffscreenContext ctx(8, 8);
    Scene scene;
    scene.meshes.emplace_back();
    append_box(scene.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
    scene.update_bounds();
    const Hierarchy h = Hierarchy::build(scene);
    const SceneRenderer renderer(scene, h);
    const StrategyContext context{scene, h, renderer};
    const StrategyFamily family = counting_family();
    const std::string dir = ::testing::TempDir() + "occu-databases-test-" + std::to_string(getpid());
    made = 0;

    DatabaseProvider provider(dir, DatabaseProvider::Makes::required, nullptr);
    const auto first = provider.settings_for(choice_of(family, ""), context, 64, 64);
    ASSERT_EQ(first.size(), 1u) << "the required table only";
    EXPECT_EQ(first[0].rfind("table=", 0), 0u);
    const std::string path = first[0].substr(6);
    EXPECT_TRUE(std::filesystem::exists(path));
    EXPECT_EQ(made, 1);
    EXPECT_EQ(provider.settings_for(choice_of(family, ""), context, 64, 64), first);
    EXPECT_EQ(made, 1) << "made again";
    DatabaseProvider again(dir, DatabaseProvider::Makes::required, nullptr);
    EXPECT_EQ(again.settings_for(choice_of(family, ""), context, 64, 64), first);
    EXPECT_EQ(made, 1) << "another provider on the directory made it again";
    EXPECT_TRUE(again.made().empty());

    // Another provenance: another file.
    const auto bigger = provider.settings_for(choice_of(family, "size=4"), context, 64, 64);
    ASSERT_EQ(bigger.size(), 1u);
    EXPECT_NE(bigger, first);
    const auto wider = provider.settings_for(choice_of(family, ""), context, 128, 64);
    EXPECT_NE(wider, first);
    EXPECT_EQ(made, 3);

    // Not read, or named: nothing made.
    EXPECT_TRUE(provider.settings_for(choice_of(family, "use=no"), context, 64, 64).empty());
    EXPECT_TRUE(provider.settings_for(choice_of(family, "table=/elsewhere"), context, 64, 64).empty());
    EXPECT_EQ(made, 3);

    // Optional databases with Makes::all.
    DatabaseProvider all(dir, DatabaseProvider::Makes::all, nullptr);
    const auto both = all.settings_for(choice_of(family, ""), context, 64, 64);
    ASSERT_EQ(both.size(), 2u);
    EXPECT_EQ(both[0], first[0]);
    EXPECT_EQ(both[1].rfind("extra=", 0), 0u);
    EXPECT_EQ(made, 4);

    // A making that fails: its error, and no file under the database's name.
    const std::size_t files = std::distance(std::filesystem::directory_iterator(dir), {});
    EXPECT_THROW(provider.settings_for(choice_of(family, "fail=yes:size=9"), context, 64, 64), std::runtime_error);
    EXPECT_EQ(std::size_t(std::distance(std::filesystem::directory_iterator(dir), {})), files);
    std::filesystem::remove_all(dir);
}

TEST(DatabaseProvider, MakeDatabasesOption)
{
    EXPECT_EQ(make_databases_option("--make-databases", "all"), DatabaseProvider::Makes::all);
    EXPECT_EQ(make_databases_option("--make-databases", "required"), DatabaseProvider::Makes::required);
    try {
        make_databases_option("--make-databases", "some");
        ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("--make-databases"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("'some'"), std::string::npos);
    }
}
