#include "culling/culler.h"
#include "mos/occluder_database.h"

#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>

#include "gl/offscreen_context.h"
#include "culling/traversal.h"
#include "render/scene_renderer.h"

using namespace occu;

TEST(MakeCuller, KnownNamesAndAnErrorNamingTheUnknownOne)
{
    gl::OffscreenContext ctx(8, 8);   // occu-hier queries the context's extensions
    Scene scene;
    scene.meshes.emplace_back();
    append_box(scene.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
    scene.update_bounds();
    const Hierarchy h = Hierarchy::build(scene);
    const SceneRenderer renderer(scene, h);   // om-ps draws occluders with it
    CullerOptions with_scene;
    with_scene.hierarchy = &h;
    with_scene.renderer = &renderer;
    EXPECT_THROW(make_culler("om-ps"), std::invalid_argument);
    EXPECT_THROW(make_culler("mos-om", with_scene), std::invalid_argument);   // no database
    CullerOptions no_map = with_scene;
    no_map.map_divisor = 0;
    EXPECT_THROW(make_culler("om-ps", no_map), std::invalid_argument);
    const OccluderDatabase database;
    with_scene.occluder_database = &database;
    for (const std::string &n : culler_names()) {
        auto c = make_culler(n, with_scene);
        EXPECT_EQ(c->name(), n);
        EXPECT_TRUE(c->conservative());
    }
    try {
        make_culler("zbuffer-magic");
        FAIL() << "no exception";
    } catch (const std::invalid_argument &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'zbuffer-magic'"), std::string::npos) << what;
        EXPECT_NE(what.find("vfc"), std::string::npos) << what;
    }
    CullerOptions adaptive;
    adaptive.adaptive_threshold = 0.1f;
    EXPECT_FALSE(make_culler("occu-hier", adaptive)->conservative());
    CullerOptions bad;
    bad.adaptive_threshold = 1.5f;
    EXPECT_THROW(make_culler("occu-hier", bad), std::invalid_argument);
    bad = CullerOptions{};
    bad.max_test_area = 0.0;
    EXPECT_THROW(make_culler("occu-hier", bad), std::invalid_argument);
}

TEST(Vfc, CullsOnlyWhatTheFrustumExcludes)
{
    Camera c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    auto vfc = make_culler("vfc");
    auto none = make_culler("none");
    vfc->begin_frame(c);
    none->begin_frame(c);
    const Aabb ahead = Aabb::of({-1, -1, -20}, {1, 1, -10}), behind = Aabb::of({-1, -1, 10}, {1, 1, 20});
    EXPECT_EQ(vfc->test(ahead), Visibility::visible);
    EXPECT_EQ(vfc->test(behind), Visibility::view_culled);
    EXPECT_EQ(none->test(behind), Visibility::visible);
    EXPECT_STREQ(visibility_name(Visibility::occluded), "occluded");
}

namespace {

// Answers visible_subtree for the root (the adaptive overlap test giving
// up on it), visible otherwise, and counts the boxes it is asked about.
class GiveUpAtTheRoot final : public Culler {
public:
    explicit GiveUpAtTheRoot(const Aabb &root) : root_(root) {}
    std::string_view name() const override { return "give-up-at-the-root"; }
    bool conservative() const override { return true; }
    void begin_frame(const Camera &camera) override { frustum_.emplace(camera.view_projection()); }
    Visibility test(const Aabb &box) override
    {
        ++tested;
        if (frustum_->classify(box) == Frustum::Side::outside)
            return Visibility::view_culled;
        return box.min == root_.min && box.max == root_.max ? Visibility::visible_subtree : Visibility::visible;
    }
    std::uint32_t tested = 0;

private:
    Aabb root_;
    std::optional<Frustum> frustum_;
};

// A row of `n` unit boxes along x at z = -5, one leaf each (12 triangles),
// in a 32x32 context, and a camera at z = 20 that sees part of the row.
struct BoxRow {
    explicit BoxRow(int n)
    {
        scene.meshes.emplace_back();
        for (int i = 0; i < n; ++i)
            append_box(scene.meshes[0], Aabb::of({float(i) * 3.0f, 0, -5}, {float(i) * 3.0f + 1, 1, -4}));
        scene.update_bounds();
        HierarchyOptions ho;
        ho.max_leaf_triangles = 12;
        h.emplace(Hierarchy::build(scene, ho));
        renderer.emplace(scene, *h);
        camera.position = {10, 0.5f, 20};
        camera.target = {10, 0.5f, -5};
    }
    gl::OffscreenContext ctx{32, 32};
    Scene scene;
    std::optional<Hierarchy> h;
    std::optional<SceneRenderer> renderer;
    Camera camera;
};

}  // namespace

// Below a visible_subtree answer the traversal asks the culler nothing more
// about nodes in the frustum, and still draws exactly what vfc draws.
TEST(Traversal, VisibleSubtreeStopsOcclusionTestsBelowIt)
{
    const BoxRow row(40);
    const Hierarchy &h = *row.h;
    const SceneRenderer &renderer = *row.renderer;
    const Camera &c = row.camera;
    ASSERT_GT(h.leaf_count(), 8u);
    GiveUpAtTheRoot give_up(h.nodes()[0].bounds);
    auto vfc = make_culler("vfc");
    const FrameStats s = render_hierarchy(renderer, h, give_up, c, TraversalOptions{});
    const FrameStats v = render_hierarchy(renderer, h, *vfc, c, TraversalOptions{});
    EXPECT_EQ(s.leaves_drawn, v.leaves_drawn);
    EXPECT_GT(v.leaves_drawn, 0u);
    EXPECT_LT(v.leaves_drawn, h.leaf_count()) << "the frustum should leave some leaves out";
    // The root, then only nodes outside the frustum.
    EXPECT_EQ(give_up.tested, 1 + s.nodes_view_culled);
}

// Adaptive switch-off: where occlusion tests cull nothing, they stop after
// the first frame and come back only in probe frames, 8 frames later, then
// twice as long after each probe that finds them still not worth it, up to
// 64.
TEST(Traversal, SwitchedOffProbesBackOff)
{
    const BoxRow row(8);
    auto none = make_culler("none");   // tests, but never finds anything occluded
    Coherence coherence;
    coherence.switch_off_fraction = 0.5f;
    std::vector<std::uint32_t> tested;
    for (std::uint32_t f = 0; f < 200; ++f)
        if (render_hierarchy(*row.renderer, *row.h, *none, row.camera, TraversalOptions{}, &coherence).occlusion_tested)
            tested.push_back(f);
    EXPECT_EQ(tested, (std::vector<std::uint32_t>{0, 8, 24, 56, 120, 184}));
}
