// SPDX-License-Identifier: MIT
// The occluder choice's lanes (occluders/choice_kernels.h): the scalar and
// AVX2 twins give the same scores, facing bounds, nearest w and kept lanes
// bit for bit, on triangles beyond, across and behind the near plane,
// facing both ways, inside and outside the frustum, loaded in a row or
// gathered, for every batch size; and the hierarchy's boxes bounded and
// classified eight at a time, as Frustum::classify classifies them.
#include "occluders/choice_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "camera/camera.h"
#include "culling/culler.h"
#include "raster/depth_rasterizer.h"

using namespace occu;

namespace {

choice::ChoiceView view_of(const Frame &frame)
{
    const glm::mat4 &vp = frame.view_projection;
    choice::ChoiceView v;
    v.eye = frame.camera.position;
    v.w_row = glm::vec4(vp[0][3], vp[1][3], vp[2][3], vp[3][3]);
    const glm::vec3 x_row(vp[0][0], vp[1][0], vp[2][0]), y_row(vp[0][1], vp[1][1], vp[2][1]);
    v.area_scale = -glm::dot(x_row, glm::cross(y_row, glm::vec3(v.w_row)));
    v.near = frame.camera.near_plane;
    for (int i = 0; i < 6; ++i)
        v.planes[i] = frame.frustum.planes()[i];
    return v;
}

// View `view` of a test's sixteen: a random eye and direction, a narrow
// or wide field, a near or farther near plane.
Camera random_camera(std::mt19937 &rng, int view)
{
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Camera camera;
    camera.position = glm::vec3(10.0f * unit(rng), 10.0f * unit(rng), 10.0f * unit(rng));
    camera.target = camera.position + glm::vec3(unit(rng), unit(rng), unit(rng));
    camera.fovy_degrees = view % 2 ? 60.0f : 120.0f;
    camera.near_plane = view % 3 ? 0.1f : 2.0f;
    return camera;
}

bool same_bits(const choice::LaneScores &a, const choice::LaneScores &b)
{
    return a.keep == b.keep && std::memcmp(a.score, b.score, sizeof a.score) == 0 &&
           std::memcmp(a.most, b.most, sizeof a.most) == 0 && std::memcmp(a.nearest_w, b.nearest_w, sizeof a.nearest_w) == 0;
}

}  // namespace

TEST(ChoiceKernels, ScalarAndAvx2AgreeBitForBit)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-3.0f, 2.0f);
    // Groups of 2 to 20 triangles and one, each starting a block.
    choice::TriangleArrays arrays;
    std::vector<std::pair<std::uint32_t, int>> groups;   // first slot, count
    const int triangles = 2000;
    for (int i = 0; i < triangles; ++i) {
        if (groups.empty() || groups.back().second == int(groups.size() % 20) + 1)
            groups.emplace_back(arrays.start_group(), 0);
        ++groups.back().second;
        const glm::vec3 a(30.0f * unit(rng), 30.0f * unit(rng), 30.0f * unit(rng));
        const float size = std::pow(10.0f, exponent(rng));
        const glm::vec3 p[3] = {a, a + size * glm::vec3(unit(rng), unit(rng), unit(rng)),
                                a + size * glm::vec3(unit(rng), unit(rng), unit(rng))};
        const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        arrays.add(p, n, glm::length(n));
    }
    arrays.finish();
    const choice::TriangleLanes lanes = arrays.lanes();
    std::uniform_int_distribution<std::uint32_t> any(0, triangles - 1);
    for (const auto &[first, count] : groups)
        EXPECT_EQ(first % 8, 0u) << "a group not starting a block";
    int compared = 0, kept = 0, dropped = 0;
    for (int view = 0; view < 16; ++view) {
        const Frame frame(random_camera(rng, view), 64, 48);
        const choice::ChoiceView v = view_of(frame);
        std::vector<std::uint32_t> gather(8);
        for (const auto &[group_slot, group_count] : groups)
            for (int done = 0; done < group_count; done += 8) {
            const int count = std::min(8, group_count - done);
            const unsigned planes = view % 4 ? Frustum::all_planes : 0x15u;
            for (bool gathered : {false, true}) {
                for (std::uint32_t &g : gather)
                    g = arrays.slot(any(rng));
                choice::LaneScores scalar, avx2;
                std::memset(&avx2, 0xA5, sizeof avx2);
                const std::uint32_t *from = gathered ? gather.data() : nullptr;
                const std::uint32_t start = group_slot + std::uint32_t(done);
                choice::score_lanes_scalar(lanes, from, start, count, v, planes, scalar);
                choice::score_lanes_avx2(lanes, from, start, count, v, planes, avx2);
                ASSERT_TRUE(same_bits(scalar, avx2)) << "view " << view << ", first " << start << ", count " << count
                                                     << (gathered ? ", gathered" : "");
                EXPECT_EQ(scalar.keep >> count, 0u) << "a lane past the batch kept";
                ++compared;
                for (int i = 0; i < count; ++i)
                    (scalar.keep >> i & 1 ? kept : dropped) += 1;
            }
        }
    }
    // Both answers came up often enough to be compared.
    EXPECT_GT(kept, 1000);
    EXPECT_GT(dropped, 1000);
    EXPECT_GT(compared, 4000);
}

// The nodes' bounds and frustum sides eight at a time: the twins equal bit
// for bit, and the sides and crossing planes those of Frustum::classify,
// on boxes inside, across and outside the frustum, around the eye and
// across the near plane, flat ones among them, for every batch size.
TEST(ChoiceKernels, BoxBoundsAndSidesAgreeBitForBitAndWithTheFrustum)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-2.0f, 1.5f);
    const int boxes = 1000;
    std::vector<float> coordinates(6 * (boxes + 8), 0.0f);
    choice::BoxArrays arrays;
    std::vector<Aabb> list;
    for (int axis = 0; axis < 3; ++axis) {
        arrays.min[axis] = &coordinates[std::size_t(axis) * (boxes + 8)];
        arrays.max[axis] = &coordinates[std::size_t(3 + axis) * (boxes + 8)];
    }
    for (int i = 0; i < boxes; ++i) {
        const glm::vec3 centre(20.0f * unit(rng), 20.0f * unit(rng), 20.0f * unit(rng));
        glm::vec3 half(std::pow(10.0f, exponent(rng)), std::pow(10.0f, exponent(rng)), std::pow(10.0f, exponent(rng)));
        if (i % 7 == 0)
            half[i % 3] = 0.0f;   // flat
        const Aabb box = Aabb::of(centre - half, centre + half);
        list.push_back(box);
        for (int axis = 0; axis < 3; ++axis) {
            coordinates[std::size_t(axis) * (boxes + 8) + std::size_t(i)] = box.min[axis];
            coordinates[std::size_t(3 + axis) * (boxes + 8) + std::size_t(i)] = box.max[axis];
        }
    }
    const bool avx2 = DepthRasterizer::avx2_supported();
    int compared = 0, outside = 0, crossing = 0, inside = 0;
    for (int view = 0; view < 16; ++view) {
        const Frame frame(random_camera(rng, view), 64, 48);
        const choice::ChoiceView v = view_of(frame);
        for (std::uint32_t first = 0; first < std::uint32_t(boxes); first += 1 + first % 8) {
            const int count = int(std::min<std::uint32_t>(1 + first % 8, std::uint32_t(boxes) - first));
            const unsigned planes = view % 4 ? Frustum::all_planes : 0x2Bu;
            choice::LaneBounds scalar, lanes;
            std::memset(&lanes, 0xA5, sizeof lanes);
            choice::bound_boxes_scalar(arrays, first, count, v, planes, scalar);
            if (avx2) {
                choice::bound_boxes_avx2(arrays, first, count, v, planes, lanes);
                ASSERT_EQ(std::memcmp(&scalar, &lanes, sizeof lanes), 0) << "view " << view << ", first " << first;
            }
            for (int i = 0; i < count; ++i) {
                unsigned expected = planes;
                const Frustum::Side side = frame.frustum.classify(list[first + std::uint32_t(i)], expected);
                ASSERT_EQ(scalar.outside >> i & 1u, unsigned(side == Frustum::Side::outside))
                    << "view " << view << ", box " << first + std::uint32_t(i);
                ASSERT_EQ(scalar.crossing[i], expected) << "view " << view << ", box " << first + std::uint32_t(i);
                (side == Frustum::Side::outside ? outside : side == Frustum::Side::inside ? inside : crossing) += 1;
            }
            EXPECT_EQ(scalar.outside >> count, 0u) << "a box past the batch outside";
            ++compared;
        }
    }
    EXPECT_GT(outside, 1000);
    EXPECT_GT(crossing, 1000);
    EXPECT_GT(inside, 100);
    EXPECT_GT(compared, 2000);
}
