// SPDX-License-Identifier: MIT
// The strategy registry: every listed name builds a strategy of its
// family with its settings; traits come from the family, not the name;
// approximation knobs at tolerance=0 are exact; unknown strategies,
// settings and values are refused naming them and what is known; former
// names keep working.
#include "culling/registry.h"
#include "culling/databases.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <set>
#include <stdexcept>

#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "render/scene_renderer.h"

using namespace occu;

namespace {

std::string error_of(const std::string &spec, const std::vector<std::string> &common = {})
{
    try {
        choose_strategy(spec, common);
    } catch (const std::invalid_argument &e) {
        return e.what();
    }
    return "";
}

struct OneBox {
    OneBox()
    {
        scene.meshes.emplace_back();
        append_box(scene.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
        scene.update_bounds();
        h.emplace(Hierarchy::build(scene));
        renderer.emplace(scene, *h);
    }
    gl::OffscreenContext ctx{8, 8};   // ou queries the context's extensions
    Scene scene;
    std::optional<Hierarchy> h;
    std::optional<SceneRenderer> renderer;
};

}  // namespace

TEST(Registry, EveryFamilyNamesItsPaperAndFactory)
{
    ASSERT_GE(strategy_families().size(), 5u);
    for (const StrategyFamily &f : strategy_families()) {
        EXPECT_FALSE(f.paper.empty()) << f.name;
        EXPECT_FALSE(f.summary.empty()) << f.name;
        EXPECT_TRUE(f.make) << f.name;
        for (const SettingSpec &s : f.settings) {
            if (s.role == SettingSpec::Role::approximation) {
                EXPECT_EQ(s.name, "tolerance") << f.name << ": approximation knobs are all called tolerance";
            }
        }
    }
    const auto help = strategies_help();
    for (const std::string &n : strategy_names())
        EXPECT_NE(help.find(n), std::string::npos) << n;
}

// docs/strategies.md's table: a row per family in the registry's order, each
// with the table's six cells (a '|' inside a cell is escaped), naming the
// family, its listed presets, its paper and every setting.
TEST(Registry, MarkdownTableHasARowPerFamily)
{
    const std::string table = strategies_markdown();
    std::vector<std::string> rows;
    for (std::size_t at = 0, end; at < table.size(); at = end + 1) {
        end = table.find('\n', at);
        ASSERT_NE(end, std::string::npos) << "the table ends with a newline";
        rows.push_back(table.substr(at, end - at));
    }
    ASSERT_EQ(rows.size(), strategy_families().size() + 2);
    for (const std::string &row : rows) {
        int cells = -1;
        for (std::size_t i = 0; i < row.size(); ++i)
            cells += row[i] == '|' && (i == 0 || row[i - 1] != '\\');
        EXPECT_EQ(cells, 6) << row;
    }
    for (std::size_t i = 0; i < strategy_families().size(); ++i) {
        const StrategyFamily &f = strategy_families()[i];
        const std::string &row = rows[i + 2];
        EXPECT_EQ(row.rfind("| `" + f.name + "` |", 0), 0u) << row;
        EXPECT_NE(row.find(f.paper), std::string::npos) << f.name;
        for (const StrategyPreset &p : f.presets)
            EXPECT_NE(row.find("`" + p.name + "`"), std::string::npos) << p.name;
        for (const SettingSpec &s : f.settings)
            EXPECT_NE(row.find("`" + s.name + "="), std::string::npos) << f.name << ": " << s.name;
    }
    EXPECT_NE(table.find("| `pvs` |"), std::string::npos);
    EXPECT_NE(table.find("(0..1; approximation, exact at 0)"), std::string::npos);
    EXPECT_NE(table.find("box\\|triangles"), std::string::npos) << "a choice's '|' escaped";
}

// At their defaults, every approximation knob is exact: a strategy is
// conservative unless its family is not (bsp-pvs: a compiler's PVS).
TEST(Registry, EveryNameBuildsAConservativeStrategyAtDefaults)
{
    const OneBox box;
    const StrategyContext context{box.scene, *box.h, *box.renderer};
    for (const std::string &n : strategy_names()) {
        const StrategyChoice c = choose_strategy(n);
        EXPECT_EQ(c.conservative(), c.family->conservative) << n;
        const auto read = databases_read(c);
        if (std::any_of(read.begin(), read.end(), [](const DatabaseNeed *d) { return d->required; })) {
            // Not given a database it requires (tests/integration have one made).
            EXPECT_THROW(make_strategy(n, context), std::invalid_argument) << n;
            continue;
        }
        if (!c.family->refusal(box.scene).empty()) {
            // A scene it cannot serve: a plain mesh has no 2.5D occluders.
            EXPECT_THROW(make_strategy(n, context), std::invalid_argument) << n;
            continue;
        }
        const Strategy s = make_strategy(n, context);
        EXPECT_TRUE(s.culler) << n;
        EXPECT_EQ(s.choice.label(), n);
    }
}

TEST(Registry, TraitsComeFromTheFamily)
{
    EXPECT_TRUE(choose_strategy("ou-shared").family->traversal.coherence);
    EXPECT_FALSE(choose_strategy("om-fh").family->traversal.coherence);
    EXPECT_TRUE(choose_strategy("om-fh").family->traversal.switch_off);
    EXPECT_FALSE(choose_strategy("vfc").family->traversal.switch_off);
    EXPECT_TRUE(choose_strategy("ideal").family->needs_truth);
    EXPECT_FALSE(choose_strategy("none").family->needs_truth);
    // A tolerance makes an approximation; 0 is exact again.
    EXPECT_FALSE(choose_strategy("ou:tolerance=0.1").conservative());
    EXPECT_TRUE(choose_strategy("ou:tolerance=0").conservative());
    EXPECT_FALSE(choose_strategy("om-ps:tolerance=4").conservative());
    // Cost knobs never make a strategy approximate.
    EXPECT_TRUE(choose_strategy("om-ps:coverage-ratio=0.9:occluders=2").conservative());
}

TEST(Registry, PresetsAndFormerNames)
{
    const StrategyChoice shared = choose_strategy("ou-shared");
    EXPECT_EQ(shared.family->name, "ou");
    EXPECT_EQ(shared.settings.text("passes"), "shared");
    EXPECT_EQ(choose_strategy("occu-hier-shared").settings.text("passes"), "shared");
    EXPECT_EQ(choose_strategy("occu-hier").settings.text("passes"), "disjoint");
    const StrategyChoice mos = choose_strategy("mos-om");
    EXPECT_EQ(mos.family->name, "om");
    EXPECT_EQ(mos.settings.text("selection"), "mos");
    EXPECT_EQ(choose_strategy("pc-fh").settings.text("compare"), "pixels");
    EXPECT_EQ(choose_strategy("pc-fh").settings.text("selection"), "fh");
    // Former names are accepted but not listed.
    const auto names = strategy_names();
    EXPECT_EQ(std::count(names.begin(), names.end(), "occu-hier"), 0);
    EXPECT_EQ(std::count(names.begin(), names.end(), "om-mos"), 1);
    // Labels show what differs from the preset.
    EXPECT_EQ(choose_strategy("om-ps:occluders=8").label(), "om-ps:occluders=8");
    EXPECT_EQ(choose_strategy("om:selection=fh").label(), "om:selection=fh");
    EXPECT_EQ(choose_strategy("om-mos", {"database=/data/city.db"}).label(), "om-mos") << "files are not in labels";
}

// What the shared integration tests run of each family beyond its names
// (StrategyTestVariant): variants of the family that declares them, exact,
// each once, the bounds on what they draw naming what those tests run
// beside them (a listed name, or a variant in batches of 16 without
// policies across frames) with a positive share.
TEST(Registry, FamiliesDeclareConservativeTestVariantsOfTheirOwn)
{
    const auto names = strategy_names();
    std::set<std::string> comparable(names.begin(), names.end()), declared;
    std::size_t variants = 0;
    for (const StrategyFamily &family : strategy_families())
        for (const StrategyTestVariant &v : family.test_variants)
            if (v.batch == 16 && !v.coherence && !v.probing_switch_off)
                comparable.insert(v.spec);
    for (const StrategyFamily &family : strategy_families())
        for (const StrategyTestVariant &v : family.test_variants) {
            SCOPED_TRACE(v.spec);
            ++variants;
            const StrategyChoice choice = choose_strategy(v.spec);
            EXPECT_EQ(choice.family, &family) << "declared by " << family.name;
            EXPECT_TRUE(choice.conservative());
            EXPECT_GE(v.batch, 1u);
            EXPECT_TRUE(declared.insert(v.spec + "/" + std::to_string(v.batch) + (v.coherence ? "/coherent" : "") +
                                        (v.probing_switch_off ? "/probes" : ""))
                            .second)
                << "declared twice";
            for (const StrategyTestVariant::Bound &bound : v.draws_at_most) {
                EXPECT_TRUE(comparable.count(bound.spec)) << "bounded by " << bound.spec << ", which the tests do not run";
                EXPECT_GT(bound.share, 0.0);
            }
        }
    EXPECT_GT(variants, 0u);
    // A declaration the tests would not tell apart from a listed name is refused here.
    for (const StrategyFamily &family : strategy_families())
        for (const StrategyTestVariant &v : family.test_variants)
            EXPECT_FALSE(v.batch == 16 && !v.coherence && !v.probing_switch_off &&
                         std::count(names.begin(), names.end(), v.spec))
                << v.spec << " is a listed name: the tests run it already";
}

TEST(Registry, DistinctStrategiesNameEachSettingsOnce)
{
    const auto names = distinct_strategy_names();
    // om's defaults are om-ps's: the preset is listed, the family's own name is not.
    EXPECT_EQ(std::count(names.begin(), names.end(), "om"), 0);
    EXPECT_EQ(std::count(names.begin(), names.end(), "om-ps"), 1);
    // A family whose presets all change something keeps its own name.
    EXPECT_EQ(std::count(names.begin(), names.end(), "ou"), 1);
    EXPECT_EQ(std::count(names.begin(), names.end(), "ou-shared"), 1);
    EXPECT_EQ(std::count(names.begin(), names.end(), "occu-hier"), 0) << "former names are not listed";
    // No two names mean the same family and settings.
    std::set<std::string> meanings;
    for (const std::string &n : names) {
        const StrategyChoice c = choose_strategy(n);
        EXPECT_TRUE(meanings.insert(c.family->name + ":" + c.settings.changed()).second) << n << " repeats another";
    }
}

TEST(Registry, SettingsAndCommonSettings)
{
    const StrategyChoice c = choose_strategy("om-ps:occluders=8:tolerance=2", {"occluders=16", "tolerance=1"});
    EXPECT_EQ(c.settings.integer("occluders"), 8) << "a strategy's own settings win over common ones";
    EXPECT_EQ(c.settings.integer("tolerance"), 2);
    EXPECT_EQ(choose_strategy("om-ps", {"occluders=16"}).settings.integer("occluders"), 16);
    EXPECT_EQ(choose_strategy("vfc", {"occluders=16"}).settings.changed(), "") << "ignored where unknown";
    EXPECT_DOUBLE_EQ(choose_strategy("ou:max-test-area=1").settings.number("max-test-area"), 1.0);
    const std::vector<StrategyChoice> chosen = {choose_strategy("vfc"), choose_strategy("om-ps")};
    EXPECT_NO_THROW(check_common_settings(chosen, {"occluders=3"}));
    try {
        check_common_settings(chosen, {"passes=shared"});
        FAIL() << "no exception";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("'passes'"), std::string::npos) << e.what();
    }
}

TEST(Registry, BadNamesSettingsAndValuesAreRefusedNamingThem)
{
    std::string e = error_of("zbuffer-magic");
    EXPECT_NE(e.find("'zbuffer-magic'"), std::string::npos) << e;
    EXPECT_NE(e.find("vfc"), std::string::npos) << e;
    EXPECT_NE(e.find("om-mos"), std::string::npos) << e;
    e = error_of("ou:threshold=0.1");
    EXPECT_NE(e.find("'threshold'"), std::string::npos) << e;
    EXPECT_NE(e.find("tolerance"), std::string::npos) << e;
    e = error_of("vfc:tolerance=1");
    EXPECT_NE(e.find("it has none"), std::string::npos) << e;
    EXPECT_NE(error_of("ou:tolerance=1.5").find("tolerance"), std::string::npos);
    EXPECT_NE(error_of("ou:tolerance=nan").find("'nan'"), std::string::npos);
    EXPECT_NE(error_of("ou:tolerance=inf").find("'inf'"), std::string::npos);
    EXPECT_NE(error_of("ou:max-test-area=0").find("max-test-area"), std::string::npos);
    EXPECT_NE(error_of("om-ps:map-divisor=0").find("map-divisor"), std::string::npos);
    EXPECT_NE(error_of("om-ps:occluders=-1").find("occluders"), std::string::npos);
    EXPECT_NE(error_of("ou:passes=sometimes").find("disjoint, shared"), std::string::npos);
    EXPECT_NE(error_of("ou:passes").find("not key=value"), std::string::npos);
    EXPECT_NE(error_of(":passes=shared").find("empty strategy name"), std::string::npos);
}

TEST(Baselines, VfcCullsOnlyWhatTheFrustumExcludes)
{
    const OneBox box;
    const StrategyContext context{box.scene, *box.h, *box.renderer};
    Camera c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    const Frame frame(c, 8, 8);
    const Strategy vfc = make_strategy("vfc", context), none = make_strategy("none", context);
    vfc.culler->begin_frame(frame);
    none.culler->begin_frame(frame);
    std::vector<NodeTest> tests = {{0, Aabb::of({-1, -1, -20}, {1, 1, -10})}, {0, Aabb::of({-1, -1, 10}, {1, 1, 20})}};
    std::vector<NodeTest> same = tests;
    vfc.culler->test(tests);
    none.culler->test(same);
    EXPECT_EQ(tests[0].result, Visibility::visible);
    EXPECT_EQ(tests[1].result, Visibility::view_culled);
    EXPECT_EQ(same[1].result, Visibility::visible);
    EXPECT_STREQ(visibility_name(Visibility::occluded), "occluded");
}

TEST(Baselines, IdealDrawsTheOraclesVisibleLeavesAndNeedsTheOracle)
{
    const OneBox box;
    const StrategyContext context{box.scene, *box.h, *box.renderer};
    Camera c;
    c.position = {0.5f, 0.5f, 5};
    c.target = {0.5f, 0.5f, 0};
    const Strategy ideal = make_strategy("ideal", context);
    EXPECT_THROW(ideal.culler->begin_frame(Frame(c, 8, 8)), std::runtime_error);
    VisibilityTruth truth;
    truth.in_frustum = {0};
    const Frame hidden(c, 8, 8, &truth);   // the oracle saw nothing
    ideal.culler->begin_frame(hidden);
    std::vector<NodeTest> tests = {{0, box.h->nodes()[0].bounds, true}};
    ideal.culler->test(tests);
    EXPECT_EQ(tests[0].result, Visibility::occluded);
    truth.visible = {0};
    ideal.culler->begin_frame(Frame(c, 8, 8, &truth));
    ideal.culler->test(tests);
    EXPECT_EQ(tests[0].result, Visibility::visible);
}

// What a family declares it needs: every database need names a path
// setting of its family, says how to make it and what it depends on; the
// scene requirements say what they want. The ones declared today: the
// minimum-occluder-set database (required, read only with selection=mos),
// the skins' and the view cells' (made by the strategy itself without one),
// and the view cells' 2.5D occluders.
TEST(Registry, FamiliesDeclareTheirDatabasesAndScenes)
{
    std::size_t needs = 0, required = 0;
    for (const StrategyFamily &f : strategy_families()) {
        for (const DatabaseNeed &d : f.databases) {
            SCOPED_TRACE(f.name + " " + d.setting);
            ++needs;
            required += d.required;
            const auto spec = std::find_if(f.settings.begin(), f.settings.end(),
                                           [&d](const SettingSpec &s) { return s.name == d.setting; });
            ASSERT_NE(spec, f.settings.end()) << "a database need names no setting of its family";
            EXPECT_EQ(spec->kind, SettingSpec::Kind::path);
            EXPECT_TRUE(d.provenance);
            EXPECT_TRUE(d.make);
            EXPECT_FALSE(d.name.empty());
        }
        for (const SceneRequirement &r : f.scene_requirements) {
            EXPECT_FALSE(r.what.empty()) << f.name;
            EXPECT_TRUE(r.met) << f.name;
        }
    }
    EXPECT_GE(needs, 7u);
    EXPECT_EQ(required, 1u);
    EXPECT_EQ(databases_read(choose_strategy("om-mos")).size(), 1u);
    EXPECT_EQ(databases_read(choose_strategy("om-ps")).size(), 0u) << "om-ps reads no database";
    EXPECT_EQ(databases_read(choose_strategy("hzb-last-frame")).size(), 0u);
    EXPECT_EQ(databases_read(choose_strategy("skins-drawn")).size(), 0u);
    Scene plain;
    EXPECT_NE(choose_strategy("pvs").family->refusal(plain).find("2.5D occluders"), std::string::npos);
    EXPECT_EQ(choose_strategy("ou").family->refusal(plain), "");
}

// A chain of strategies (NAME+NAME): a family made of its stages'.
TEST(Registry, ChainsAreFamiliesMadeOfTheirStages)
{
    const StrategyChoice c = choose_strategy("bsp-pvs+ou-shared:max-test-area=0.5");
    EXPECT_EQ(c.family->name, "bsp-pvs+ou");
    ASSERT_EQ(c.family->stages.size(), 2u);
    EXPECT_EQ(c.family->stages[0]->name, "bsp-pvs");
    EXPECT_FALSE(c.conservative()) << "bsp-pvs is not declared conservative";
    EXPECT_TRUE(c.family->traversal.coherence) << "ou's policies";
    EXPECT_FALSE(c.family->traversal.switch_off) << "switched off, a frame would lose the PVS too";
    EXPECT_EQ(c.settings.text("passes"), "shared") << "the preset's settings";
    EXPECT_EQ(c.settings.text("max-test-area"), "0.5");
    EXPECT_EQ(choose_strategy("bsp-pvs+ou").family, c.family) << "one family per sequence";
    const StrategyChoice v = choose_strategy("vfc+om-ps");
    EXPECT_TRUE(v.conservative());
    EXPECT_FALSE(v.family->traversal.coherence);
    EXPECT_FALSE(choose_strategy("vfc+ou:tolerance=0.1").conservative());
    EXPECT_TRUE(choose_strategy("ideal+ou").family->needs_truth);
    Scene plain;
    EXPECT_NE(choose_strategy("vfc+pvs").family->refusal(plain).find("2.5D occluders"), std::string::npos);
    EXPECT_NE(choose_strategy("bsp-pvs+ou").family->refusal(plain).find("Quake III level"), std::string::npos);
    EXPECT_EQ(databases_read(choose_strategy("vfc+om-mos")).size(), 1u) << "a stage's database";
    EXPECT_NE(error_of("vfc+nonesuch").find("unknown culling strategy 'nonesuch'"), std::string::npos);
    EXPECT_NE(error_of("vfc+").find("empty strategy name"), std::string::npos);
    EXPECT_NE(error_of("vfc+ou:nonesuch=1").find("nonesuch"), std::string::npos);
}

TEST(Registry, ChainOfAStrategyWithItsOwnTraversalIsRefused)
{
    const OneBox box;
    const StrategyContext context{box.scene, *box.h, *box.renderer};
    for (const char *name : {"vfc+chc", "chc+vfc"}) {
        try {
            make_strategy(name, context);
            ADD_FAILURE() << "chc made as a stage of " << name;
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find("chc walks the hierarchy itself"), std::string::npos) << e.what();
        }
    }
    const Strategy s = make_strategy("vfc+ou", context);
    EXPECT_EQ(s.choice.label(), "vfc+ou");
}
