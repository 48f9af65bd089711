// SPDX-License-Identifier: MIT
// The resource provider (culling/databases.h), with a family of its own:
// a database is made the first time it is asked for and found afterwards
// (in this provider and in another on the same directory), a provenance
// that differs names another file, only what the settings read and do not
// name is made, optional databases only when asked, a making that fails
// leaves no file behind, a file found under the name whose provenance
// differs or that is cut short is made again (saying why), and a making
// that records another provenance than it declared is an error.
#include "culling/databases.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
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
                  choice_setting("fail", {"no", "yes", "records-otherwise"}, "whether making the table fails"),
                  path_setting("table", "the table"), path_setting("extra", "an optional one")};
    DatabaseNeed table;
    table.setting = "table";
    table.name = "table";
    table.required = true;
    table.read_by = [](const Settings &s) { return s.text("use") == "yes"; };
    table.provenance = [](const DatabaseRequest &r) {
        return DatabaseProvenance::current("counting", "size=" + r.settings.text("size"),
                                           "width=" + std::to_string(r.width), false);
    };
    table.make = [](const DatabaseRequest &r, const std::string &path) {
        if (r.settings.text("fail") == "yes") {
            std::ofstream(path) << "half";
            throw std::runtime_error("no table today");
        }
        ++made;
        DatabaseProvenance p = DatabaseProvenance::current("counting", "size=" + r.settings.text("size"),
                                                           "width=" + std::to_string(r.width), false);
        if (r.settings.text("fail") == "records-otherwise")
            p.settings += " and more";
        DatabaseWriter out(path, "table", 1, p);
        out.out() << "row " << r.settings.text("size") << '\n';
        out.finish();
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

// A scene of one box, its hierarchy and renderer in a context of their own.
struct OneBox {
    static Scene make_scene()
    {
        Scene scene;
        scene.meshes.emplace_back();
        append_box(scene.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
        scene.update_bounds();
        return scene;
    }
    gl::OffscreenContext ctx{8, 8};
    const Scene scene = make_scene();
    const Hierarchy h = Hierarchy::build(scene);
    const SceneRenderer renderer{scene, h};
    const StrategyContext context{scene, h, renderer};
};

}  // namespace

TEST(DatabaseProvider, MakesOnceFindsAfterAndKeysByProvenance)
{
    const OneBox box;
    const StrategyContext &context = box.context;
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

TEST(DatabaseProvider, MakesAgainWhatIsFoundDamagedOrOfAnotherProvenance)
{
    const OneBox box;
    const StrategyContext &context = box.context;
    const StrategyFamily family = counting_family();
    const std::string dir = ::testing::TempDir() + "occu-databases-again-" + std::to_string(getpid());
    made = 0;
    DatabaseProvider first(dir, DatabaseProvider::Makes::required, nullptr);
    const std::string path = first.settings_for(choice_of(family, ""), context, 64, 64).at(0).substr(6);
    ASSERT_EQ(made, 1);
    std::string whole;
    {
        std::ifstream in(path);
        whole.assign(std::istreambuf_iterator<char>(in), {});
    }

    // The file under the name holds another provenance (a name shared by
    // chance, or a hand-made file), is cut short, or is of the old format.
    const std::string other = "occu-database table 1\nalgorithm counting\nsettings size=99\nscene width=64\n"
                              "code 0\nmesa none\nrow 99\nend\n";
    const std::string cut = whole.substr(0, whole.rfind("end"));
    const std::pair<std::string, std::string> cases[] = {{other, "its provenance differs: settings 'size=99'"},
                                                         {cut, "ends before its end record"},
                                                         {"occu-occluder-skins 1\n", "the format before occu-database"}};
    for (const auto &[text, why] : cases) {
        std::ofstream(path) << text;
        char *report_text = nullptr;
        std::size_t report_size = 0;
        std::FILE *report = open_memstream(&report_text, &report_size);
        DatabaseProvider again(dir, DatabaseProvider::Makes::required, report);
        EXPECT_EQ(again.settings_for(choice_of(family, ""), context, 64, 64).at(0), "table=" + path);
        std::fclose(report);
        const std::string said(report_text, report_size);
        std::free(report_text);
        EXPECT_NE(said.find(path + " made again: "), std::string::npos) << said;
        EXPECT_NE(said.find(why), std::string::npos) << said;
        EXPECT_EQ(again.made(), std::vector<std::string>{path});
        std::ifstream in(path);
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), whole) << "not made again whole";
    }
    EXPECT_EQ(made, 4);

    // A making that writes another provenance than it declares would be
    // made again by every run: an error, and no file.
    try {
        first.settings_for(choice_of(family, "fail=records-otherwise:size=7"), context, 64, 64);
        ADD_FAILURE() << "took a database of another provenance";
    } catch (const std::logic_error &e) {
        EXPECT_NE(std::string(e.what()).find("is not the one asked for: its provenance differs: settings"),
                  std::string::npos)
            << e.what();
    }
    std::size_t databases = 0;
    for (const auto &entry : std::filesystem::directory_iterator(dir))
        databases += entry.path() != path;
    EXPECT_EQ(databases, 0u);
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
