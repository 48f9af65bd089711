#include "culling/culler.h"
#include "mos/occluder_database.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "gl/offscreen_context.h"
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
