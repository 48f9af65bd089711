// SPDX-License-Identifier: MIT
#include "camera/camera.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

using namespace occu;

namespace {
Camera looking_down_minus_z()
{
    Camera c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    c.near_plane = 1.0f;
    c.far_plane = 100.0f;
    return c;
}

bool point_inside(const glm::mat4 &vp, const glm::vec3 &p)
{
    const glm::vec4 c = vp * glm::vec4(p, 1.0f);
    return c.w > 0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
}
}  // namespace

TEST(Frustum, ClassifiesObviousBoxes)
{
    const Frustum f(looking_down_minus_z().view_projection());
    EXPECT_EQ(f.classify(Aabb::of({-1, -1, -11}, {1, 1, -9})), Frustum::Side::inside);
    EXPECT_EQ(f.classify(Aabb::of({-1, -1, 5}, {1, 1, 9})), Frustum::Side::outside);        // behind the eye
    EXPECT_EQ(f.classify(Aabb::of({-1, -1, -200}, {1, 1, -150})), Frustum::Side::outside);  // past far
    EXPECT_EQ(f.classify(Aabb::of({-1, -1, -2}, {1, 1, 2})), Frustum::Side::intersecting);  // contains the eye
    EXPECT_EQ(f.classify(Aabb::of({-1, -1, -1.5f}, {1, 1, -0.5f})), Frustum::Side::intersecting);  // near plane
}

TEST(Frustum, NeverCullsABoxWithAPointInside)
{
    Camera c = looking_down_minus_z();
    c.position = {3, 2, 1};
    c.target = {-5, 1, -20};
    c.aspect = 1.5f;
    const glm::mat4 vp = c.view_projection();
    const Frustum f(vp);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> pos(-60, 60), size(0.01f, 20), unit(0, 1);
    int outside = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 lo{pos(rng), pos(rng) * 0.3f, pos(rng)};
        const Aabb box = Aabb::of(lo, lo + glm::vec3(size(rng), size(rng), size(rng)));
        if (f.classify(box) != Frustum::Side::outside)
            continue;
        ++outside;
        for (int k = 0; k < 200; ++k) {
            const glm::vec3 p = box.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * box.extent();
            ASSERT_FALSE(point_inside(vp, p)) << "box " << i << " culled with a point inside";
        }
    }
    EXPECT_GT(outside, 200);   // the test exercised culling
}

TEST(Frustum, HugeCoordinatesStayFinite)
{
    const Frustum f(looking_down_minus_z().view_projection());
    EXPECT_EQ(f.classify(Aabb::of({-1e30f, -1e30f, -1e30f}, {1e30f, 1e30f, 1e30f})), Frustum::Side::intersecting);
    EXPECT_EQ(f.classify(Aabb::of({1e20f, 1e20f, -1e20f}, {2e20f, 2e20f, -1e19f})), Frustum::Side::outside);
}

TEST(ProjectBox, FootprintOrNothingNearTheEye)
{
    const Camera c = looking_down_minus_z();
    const glm::mat4 vp = c.view_projection();
    EXPECT_FALSE(project_box(vp, c.position, Aabb::of({-1, -1, -1}, {1, 1, 1})));        // holds the eye
    EXPECT_FALSE(project_box(vp, c.position, Aabb::of({-1, -1, -3}, {1, 1, -0.5f})));    // crosses near (1)
    const auto p = project_box(vp, c.position, Aabb::of({-1, -1, -10}, {1, 1, -5}));
    ASSERT_TRUE(p);
    EXPECT_NEAR(p->ndc_max.x, -p->ndc_min.x, 1e-6f);   // centred
    EXPECT_LT(p->ndc_max.x, 1.0f);
    // The nearest corner's window depth: the face at z = -5.
    const glm::vec4 clip = vp * glm::vec4(1, 1, -5, 1);
    EXPECT_NEAR(p->window_z_near, 0.5f * clip.z / clip.w + 0.5f, 1e-7f);
}

// A box inside another, classified against the planes its enclosing box
// crosses alone, gets the answer of a classification against all six, and
// the planes it reports crossing are those its own classification reaches
// across.
TEST(Frustum, PlaneMaskOfAnEnclosingBoxGivesTheSameAnswer)
{
    Camera c = looking_down_minus_z();
    c.position = {3, 2, 1};
    c.target = {-5, 1, -20};
    c.aspect = 1.5f;
    const Frustum f(c.view_projection());
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-60, 60), size(0.01f, 60), unit(0, 1);
    int masked = 0, inside = 0;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 lo{pos(rng), pos(rng) * 0.3f, pos(rng)};
        const Aabb outer = Aabb::of(lo, lo + glm::vec3(size(rng), size(rng), size(rng)));
        unsigned crossing = Frustum::all_planes;
        if (f.classify(outer, crossing) == Frustum::Side::outside)
            continue;
        // Two nested boxes inside it: the mask carries down two levels.
        const glm::vec3 a = outer.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * outer.extent();
        const glm::vec3 b = outer.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * outer.extent();
        const Aabb middle = Aabb::of(glm::min(a, b), glm::max(a, b));
        const glm::vec3 d = middle.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * middle.extent();
        const Aabb inner = Aabb::of(d, glm::min(d + glm::vec3(size(rng)), middle.max));
        masked += crossing != Frustum::all_planes;
        unsigned middle_crossing = crossing;
        const Frustum::Side m = f.classify(middle, middle_crossing);
        ASSERT_EQ(m, f.classify(middle)) << "box " << i;
        if (m == Frustum::Side::outside)
            continue;
        unsigned full = Frustum::all_planes;
        f.classify(middle, full);
        ASSERT_EQ(middle_crossing, full) << "box " << i;
        const Frustum::Side n = f.classify(inner, middle_crossing);
        ASSERT_EQ(n, f.classify(inner)) << "box " << i;
        inside += n == Frustum::Side::inside;
    }
    EXPECT_GT(masked, 500);   // enclosing boxes left planes out
    EXPECT_GT(inside, 100);   // and answers came from the masked planes alone
}

// project_box takes its corners four at a time in SIMD lanes; its answer is
// the corner-by-corner fold of glm's float transform, bit for bit (the
// footprints, and so every strategy's culling, do not move), near the eye,
// across the near plane, far off and with non-finite corners too.
TEST(ProjectBox, EqualsGlmsTransformCornerByCornerBitForBit)
{
    const auto reference = [](const glm::mat4 &vp, const glm::vec3 &eye, const Aabb &box) {
        std::optional<BoxProjection> none;
        if (box.contains(eye))
            return none;
        BoxProjection p{glm::vec2(1e30f), glm::vec2(-1e30f), 1.0f};
        for (int i = 0; i < 8; ++i) {
            const glm::vec4 c = vp * glm::vec4(box.corner(i), 1.0f);
            if (c.w <= 0.0f || c.z < -c.w)
                return none;
            const glm::vec2 ndc(c.x / c.w, c.y / c.w);
            p.ndc_min = glm::min(p.ndc_min, ndc);
            p.ndc_max = glm::max(p.ndc_max, ndc);
            p.window_z_near = std::min(p.window_z_near, 0.5f * (c.z / c.w) + 0.5f);
        }
        return std::optional<BoxProjection>(p);
    };
    const auto bits = [](float f) {
        std::uint32_t u;
        std::memcpy(&u, &f, sizeof u);
        return u;
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(-1, 1), size(0.001f, 1), fov(20, 120);
    int projected = 0, none = 0;
    for (int i = 0; i < 20000; ++i) {
        Camera c;
        const float scale = std::pow(10.0f, float(i % 7));   // 1 m to 1e6 m from the origin
        c.position = glm::vec3(unit(rng), unit(rng), unit(rng)) * scale;
        c.target = c.position + glm::vec3(unit(rng), unit(rng), unit(rng));
        c.fovy_degrees = fov(rng);
        c.aspect = 0.5f + size(rng);
        const glm::mat4 vp = c.view_projection();
        const glm::vec3 lo = c.position + glm::vec3(unit(rng), unit(rng), unit(rng)) * 50.0f;
        Aabb box = Aabb::of(lo, lo + glm::vec3(size(rng), size(rng), size(rng)) * 30.0f);
        if (i % 97 == 0)
            box.max.y = std::numeric_limits<float>::infinity();
        const auto expected = reference(vp, c.position, box);
        const auto got = project_box(vp, c.position, box);
        ASSERT_EQ(bool(expected), bool(got)) << "box " << i;
        if (!expected) {
            ++none;
            continue;
        }
        ++projected;
        ASSERT_EQ(bits(got->ndc_min.x), bits(expected->ndc_min.x)) << "box " << i;
        ASSERT_EQ(bits(got->ndc_min.y), bits(expected->ndc_min.y)) << "box " << i;
        ASSERT_EQ(bits(got->ndc_max.x), bits(expected->ndc_max.x)) << "box " << i;
        ASSERT_EQ(bits(got->ndc_max.y), bits(expected->ndc_max.y)) << "box " << i;
        ASSERT_EQ(bits(got->window_z_near), bits(expected->window_z_near)) << "box " << i;
    }
    EXPECT_GT(projected, 5000);   // the test compared footprints
    EXPECT_GT(none, 1000);        // and boxes across the near plane or around the eye
}

// Frustum::classify takes four planes a step in SIMD lanes; its answer and
// the planes it reports crossed are those of the planes tested one by one
// in order (glm::dot's float sums), for any subset of planes, boxes from
// tiny to huge and far from the origin.
TEST(Frustum, LanesAnswerAsThePlanesOneByOne)
{
    const auto reference = [](const Frustum &f, const Aabb &box, unsigned &crossing) {
        Frustum::Side side = Frustum::Side::inside;
        const unsigned planes = crossing;
        crossing = 0;
        for (unsigned i = 0; i < 6; ++i) {
            if (!(planes & (1u << i)))
                continue;
            const glm::vec4 &p = f.planes()[i];
            const glm::vec3 n(p);
            const glm::vec3 far_corner{n.x >= 0 ? box.max.x : box.min.x, n.y >= 0 ? box.max.y : box.min.y,
                                       n.z >= 0 ? box.max.z : box.min.z};
            const glm::vec3 near_corner{n.x >= 0 ? box.min.x : box.max.x, n.y >= 0 ? box.min.y : box.max.y,
                                        n.z >= 0 ? box.min.z : box.max.z};
            if (glm::dot(n, far_corner) + p.w < 0.0f)
                return Frustum::Side::outside;
            if (glm::dot(n, near_corner) + p.w < 0.0f) {
                side = Frustum::Side::intersecting;
                crossing |= 1u << i;
            }
        }
        return side;
    };
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(-1, 1), size(0.001f, 1), fov(20, 120);
    std::uniform_int_distribution<unsigned> mask(0, Frustum::all_planes);
    int counts[3] = {};
    for (int i = 0; i < 20000; ++i) {
        Camera c;
        const float scale = std::pow(10.0f, float(i % 7));
        c.position = glm::vec3(unit(rng), unit(rng), unit(rng)) * scale;
        c.target = c.position + glm::vec3(unit(rng), unit(rng), unit(rng));
        c.fovy_degrees = fov(rng);
        c.near_plane = 0.1f;
        c.far_plane = 200.0f;
        const Frustum f(c.view_projection());
        const glm::vec3 lo = c.position + glm::vec3(unit(rng), unit(rng), unit(rng)) * 250.0f;
        const Aabb box = Aabb::of(lo, lo + glm::vec3(size(rng), size(rng), size(rng)) * std::pow(10.0f, float(i % 4)));
        unsigned expected_crossing = i % 2 ? Frustum::all_planes : mask(rng), crossing = expected_crossing;
        const Frustum::Side expected = reference(f, box, expected_crossing);
        ASSERT_EQ(f.classify(box, crossing), expected) << "box " << i;
        ASSERT_EQ(crossing, expected_crossing) << "box " << i;
        ++counts[int(expected)];
    }
    for (int side = 0; side < 3; ++side)
        EXPECT_GT(counts[side], 1000) << "side " << side;   // every answer was compared
}
