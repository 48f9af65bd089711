// Conservative strategies never remove a visible pixel: on short routes of
// a small city, every frame drawn with vfc, with occu-hier (batched and
// strictly front to back, testing every box), with om-ps (opacity and
// sparse depth maps), with occu-hier testing leaves by their triangles,
// and with occu-hier-shared
// (overlapping boxes share passes), also with temporal coherence across the
// route's frames, equals the unculled frame byte for byte, while
// occu-hier draws fewer triangles (so the comparison can fail).
// Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>
#include <vector>

#include "camera/route.h"
#include "culling/traversal.h"
#include "gl/offscreen_context.h"
#include "mos/occluder_database.h"
#include "mos/occluder_preprocessing.h"
#include "scene/city.h"

using namespace occu;

namespace {

struct Frame {
    std::vector<std::uint8_t> pixels;
    std::uint64_t triangles;
};

Frame draw(const gl::OffscreenContext &ctx, const SceneRenderer &renderer, const Hierarchy &h, Culler &culler,
           const Camera &camera, std::size_t batch, Coherence *coherence = nullptr)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    load_camera(camera);
    TraversalOptions o;
    o.batch = batch;
    const FrameStats s = render_hierarchy(renderer, h, culler, camera, o, coherence);
    glFinish();
    const std::size_t n = std::size_t(ctx.width()) * std::size_t(ctx.height()) * 4;
    return {std::vector<std::uint8_t>(ctx.pixels(), ctx.pixels() + n), s.triangles};
}

// A city of 4x4 blocks in leaves of at most 128 triangles, drawn into a
// 128x128 context with depth test and back-face culling: the scene of the
// short-route tests.
struct SmallCity {
    SmallCity()
    {
        city.blocks_x = city.blocks_z = 4;
        scene = generate_city(city);
        HierarchyOptions ho;
        ho.max_leaf_triangles = 128;
        h.emplace(Hierarchy::build(scene, ho));
        renderer.emplace(scene, *h);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
    }
    gl::OffscreenContext ctx{128, 128};
    CityOptions city;
    Scene scene;
    std::optional<Hierarchy> h;
    std::optional<SceneRenderer> renderer;
};

}  // namespace

TEST(ConservativeCulling, FramesEqualUnculledFrames)
{
    const SmallCity small;
    const gl::OffscreenContext &ctx = small.ctx;
    const CityOptions &city = small.city;
    const Scene &scene = small.scene;
    const Hierarchy &h = *small.h;
    const SceneRenderer &renderer = *small.renderer;

    CullerOptions test_everything;
    test_everything.max_test_area = 1.0;
    auto none = make_culler("none"), vfc = make_culler("vfc"), occu = make_culler("occu-hier", test_everything);
    auto shared = make_culler("occu-hier-shared");
    CullerOptions with_scene;
    with_scene.hierarchy = &h;
    with_scene.renderer = &renderer;
    auto om = make_culler("om-ps", with_scene);
    CullerOptions by_geometry = with_scene;   // leaves tested by their own triangles
    by_geometry.leaf_geometry = true;
    by_geometry.max_test_area = 1.0;
    auto occu_geometry = make_culler("occu-hier", by_geometry);
    std::uint64_t drawn_none = 0, drawn_occu = 0, drawn_om = 0, drawn_geometry = 0;
    for (const char *route : {"dense", "medium", "open"}) {
        const auto cameras = make_route(route, scene.bounds, city, 5, 1.0f);
        Coherence coherence;
        coherence.retest_period = 3;
        for (std::size_t f = 0; f < cameras.size(); ++f) {
            const Frame reference = draw(ctx, renderer, h, *none, cameras[f], 16);
            const Frame culled_vfc = draw(ctx, renderer, h, *vfc, cameras[f], 16);
            const Frame culled_one = draw(ctx, renderer, h, *occu, cameras[f], 1);
            const Frame culled_batch = draw(ctx, renderer, h, *occu, cameras[f], 16);
            const Frame culled_shared = draw(ctx, renderer, h, *shared, cameras[f], 32);
            const Frame culled_coherent = draw(ctx, renderer, h, *shared, cameras[f], 32, &coherence);
            const Frame culled_om = draw(ctx, renderer, h, *om, cameras[f], 16);
            const Frame culled_geometry = draw(ctx, renderer, h, *occu_geometry, cameras[f], 16);
            EXPECT_TRUE(reference.pixels == culled_vfc.pixels) << route << " frame " << f << ": vfc";
            EXPECT_TRUE(reference.pixels == culled_one.pixels) << route << " frame " << f << ": occu-hier, batch 1";
            EXPECT_TRUE(reference.pixels == culled_batch.pixels) << route << " frame " << f << ": occu-hier, batch 16";
            EXPECT_TRUE(reference.pixels == culled_shared.pixels) << route << " frame " << f << ": occu-hier-shared";
            EXPECT_TRUE(reference.pixels == culled_coherent.pixels)
                << route << " frame " << f << ": occu-hier-shared with temporal coherence";
            EXPECT_TRUE(reference.pixels == culled_om.pixels) << route << " frame " << f << ": om-ps";
            EXPECT_TRUE(reference.pixels == culled_geometry.pixels)
                << route << " frame " << f << ": occu-hier, leaves tested by their triangles";
            drawn_geometry += culled_geometry.triangles;
            drawn_om += culled_om.triangles;
            drawn_none += reference.triangles;
            drawn_occu += culled_batch.triangles;
        }
    }
    EXPECT_LT(drawn_occu, drawn_none / 2) << "occu-hier culled too little for the comparison to mean anything";
    EXPECT_LT(drawn_om, drawn_none) << "om-ps culled nothing";
    EXPECT_LE(drawn_geometry, drawn_occu) << "triangles as proxies should cull at least what boxes do";
}

// The same at a distance: the default city seen from the open route, where
// depth resolution is coarse and proxy faces lie on the surfaces they bound.
TEST(ConservativeCulling, FramesEqualUnculledFramesFarAway)
{
    gl::OffscreenContext ctx(256, 256);
    const CityOptions city;
    const Scene scene = generate_city(city);
    const Hierarchy h = Hierarchy::build(scene);
    SceneRenderer renderer(scene, h);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    CullerOptions test_everything;
    test_everything.max_test_area = 1.0;
    auto none = make_culler("none"), occu = make_culler("occu-hier", test_everything);
    const auto cameras = make_route("open", scene.bounds, city, 3, 1.0f);
    std::uint64_t drawn_none = 0, drawn_occu = 0;
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        const Frame reference = draw(ctx, renderer, h, *none, cameras[f], 16);
        const Frame culled = draw(ctx, renderer, h, *occu, cameras[f], 16);
        EXPECT_TRUE(reference.pixels == culled.pixels) << "open frame " << f;
        drawn_none += reference.triangles;
        drawn_occu += culled.triangles;
    }
    EXPECT_LT(drawn_occu, drawn_none) << "occu-hier culled nothing";
}

// The other opacity-map strategies (Poon and Wang): occluders by first hit,
// from a minimum-occluder-set database preprocessed here for the small city,
// and the pixel-wise comparison (PC); at zero tolerance no frame may lose a
// pixel, and mos-om must cull something.
TEST(ConservativeCulling, OpacityMapStrategiesEqualUnculledFrames)
{
    const SmallCity small;
    const gl::OffscreenContext &ctx = small.ctx;
    const CityOptions &city = small.city;
    const Scene &scene = small.scene;
    const Hierarchy &h = *small.h;
    const SceneRenderer &renderer = *small.renderer;

    OccluderDatabase db;
    db.grid.points = {5, 1, 5};
    db.grid.directions = 4;
    db.grid.origin = scene.bounds.min + glm::vec3(0.0f, 1.7f, 0.0f);
    db.grid.spacing = scene.bounds.extent() / 4.0f;
    db.grid.spacing.y = 0.0f;
    PreprocessOptions pre;
    pre.resolution = 32;   // the maps' resolution for a 128 x 128 frame
    Camera lens;
    lens.far_plane = 2.0f * glm::length(scene.bounds.extent());
    for (std::uint32_t v = 0; v < db.grid.view_count(); ++v)
        db.views[v] = select_occluders_for_view(renderer, h, db.grid.view_camera(v, lens), pre);
    glClearColor(0, 0, 0, 0);

    CullerOptions with_scene;
    with_scene.hierarchy = &h;
    with_scene.renderer = &renderer;
    with_scene.occluder_database = &db;
    auto none = make_culler("none");
    std::uint64_t drawn_none = 0, drawn_mos = 0;
    for (const char *name : {"om-fh", "mos-om", "pc-mos"}) {
        auto culler = make_culler(name, with_scene);
        for (const char *route : {"dense", "medium"}) {
            const auto cameras = make_route(route, scene.bounds, city, 5, 1.0f);
            for (std::size_t f = 0; f < cameras.size(); ++f) {
                const Frame reference = draw(ctx, renderer, h, *none, cameras[f], 16);
                const Frame culled = draw(ctx, renderer, h, *culler, cameras[f], 16);
                EXPECT_TRUE(reference.pixels == culled.pixels) << route << " frame " << f << ": " << name;
                if (std::string(name) == "mos-om") {
                    drawn_none += reference.triangles;
                    drawn_mos += culled.triangles;
                }
            }
        }
    }
    EXPECT_LT(drawn_mos, drawn_none) << "mos-om culled nothing";
}
