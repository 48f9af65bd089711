// SPDX-License-Identifier: MIT
// The scene's own triangles as occluders: see triangle_occluders.h.
#include "occluders/triangle_occluders.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace occu {

TriangleOccluders::TriangleOccluders(const Scene &scene, const Settings &settings, std::size_t least_budget,
                                     const Hierarchy *hierarchy)
    : hierarchy_(hierarchy), budget_(least_budget)
{
    if (settings.knows("occluder-triangles"))
        budget_ = std::max(budget_, std::size_t(settings.integer("occluder-triangles")));
    // The first frame takes the whole budget; with adapt-triangles the
    // frames after take what the last one needed, down to the least
    // budget asked for (scene-triangles' on a level) or adapted_least.
    most_budget_ = least_budget_ = budget_;
    if (settings.knows("adapt-triangles") && settings.on("adapt-triangles"))
        least_budget_ = std::max(least_budget, std::min(budget_, adapted_least));
    if (budget_ == 0)
        return;
    // The groups: each leaf's occluder triangles (the hierarchy puts them
    // first), or every occluder mesh's in one. A see-through mesh hides
    // nothing (Mesh::occluder).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> refs;   // mesh, first index
    // Returns the group's largest twice world area (0: no group).
    const auto add_group = [&]() {
        Group g;
        g.first = std::uint32_t(corners_.size() / 3);
        g.slot = arrays_.start_group();
        std::vector<std::pair<float, std::size_t>> order;
        for (std::size_t i = 0; i < refs.size(); ++i) {
            const Mesh &mesh = scene.meshes[refs[i].first];
            const std::uint32_t *idx = mesh.indices.data() + refs[i].second;
            const glm::vec3 &a = mesh.positions[idx[0]], &b = mesh.positions[idx[1]], &c = mesh.positions[idx[2]];
            // One with no area (or a coordinate not finite) hides nothing.
            const float twice = glm::length(glm::cross(b - a, c - a));
            if (twice > 0.0f && std::isfinite(twice))
                order.emplace_back(twice, i);
        }
        std::stable_sort(order.begin(), order.end(), std::greater<>());
        for (const auto &[twice, i] : order) {
            const Mesh &mesh = scene.meshes[refs[i].first];
            const std::uint32_t *idx = mesh.indices.data() + refs[i].second;
            for (int v = 0; v < 3; ++v) {
                corners_.push_back(mesh.positions[idx[v]]);
                bounds_.expand(corners_.back());
            }
            const glm::vec3 *p = &corners_[corners_.size() - 3];
            arrays_.add(p, glm::cross(p[1] - p[0], p[2] - p[0]), twice);
        }
        g.count = std::uint32_t(order.size());
        if (g.count > 0)
            groups_.push_back(g);
        refs.clear();
        return order.empty() ? 0.0f : order.front().first;
    };
    if (hierarchy) {
        const auto &nodes = hierarchy->nodes();
        openings_.assign(nodes.size(), Opening{});
        for (std::size_t n = 0; n < nodes.size(); ++n) {
            const HierarchyNode &node = nodes[n];
            if (!node.leaf()) {
                openings_[n].group = {node.first_child, node.child_count, inner_node};
                continue;
            }
            for (std::uint32_t i = node.first_triangle; i < node.first_triangle + node.occluder_triangles; ++i)
                refs.emplace_back(hierarchy->triangles()[i].mesh, hierarchy->triangles()[i].first_index);
            openings_[n].largest = add_group();
            if (openings_[n].largest > 0.0f)
                openings_[n].group = groups_.back();
        }
        // Children follow their parents in the node array.
        for (std::size_t n = nodes.size(); n-- > 0;)
            for (std::uint32_t c = 0; c < nodes[n].child_count; ++c)
                openings_[n].largest = std::max(openings_[n].largest, openings_[nodes[n].first_child + c].largest);
        const std::size_t stride = nodes.size() + 8;
        node_box_coordinates_.assign(6 * stride, 0.0f);
        for (int axis = 0; axis < 3; ++axis) {
            float *lo = &node_box_coordinates_[std::size_t(axis) * stride];
            float *hi = &node_box_coordinates_[std::size_t(3 + axis) * stride];
            for (std::size_t n = 0; n < nodes.size(); ++n) {
                lo[n] = nodes[n].bounds.min[axis];
                hi[n] = nodes[n].bounds.max[axis];
            }
            node_boxes_.min[axis] = lo;
            node_boxes_.max[axis] = hi;
        }
    } else {
        for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
            if (!scene.meshes[m].occluder)
                continue;
            for (std::size_t t = 0; t + 2 < scene.meshes[m].indices.size(); t += 3)
                refs.emplace_back(std::uint32_t(m), std::uint32_t(t));
        }
        add_group();
    }
    arrays_.finish();
    lanes_ = arrays_.lanes();
    score_lanes_ = DepthRasterizer::avx2_supported() ? choice::score_lanes_avx2 : choice::score_lanes_scalar;
    bound_boxes_ = DepthRasterizer::avx2_supported() ? choice::bound_boxes_avx2 : choice::bound_boxes_scalar;
    taken_again_.assign(arrays_.size(), 0);
    // With merged coverage, the triangle across each edge (GL draws a
    // sample on a shared edge with one of the two), among the occluder
    // triangles of every mesh: equal positions are transformed alike.
    if (settings.knows("coverage") && settings.text("coverage") == "merged")
        across_ = shared_edge_opposites(corners_);
}

std::size_t TriangleOccluders::render(const Frame &frame, DepthRasterizer &raster)
{
    const std::vector<std::uint32_t> &indices = choose(frame);
    const std::size_t count = indices.size() / 3;
    if (count == 0)
        return 0;
    drawn_across_.clear();
    if (!across_.empty())
        for (std::uint32_t i : indices)
            drawn_across_.push_back(across_[i]);
    const std::uint64_t before = raster.stats().rasterized;
    raster.render_triangles(corners_.data(), indices.data(), count, across_.empty() ? nullptr : drawn_across_.data());
    if (least_budget_ < most_budget_)
        budget_ = adapted_budget(std::size_t(raster.stats().rasterized - before), least_budget_, most_budget_);
    return count;
}

std::size_t TriangleOccluders::adapted_budget(std::size_t reached, std::size_t least, std::size_t most)
{
    // Five quarters of them, rounded up.
    return std::clamp(reached + (reached + 3) / 4, least, std::max(least, most));
}

float TriangleOccluders::bound_per_area(const Aabb &box, float &nearest_w) const
{
    const choice::ChoiceView &v = view_;
    nearest_w = v.w_row.w;
    for (int axis = 0; axis < 3; ++axis)
        nearest_w += std::min(v.w_row[axis] * box.min[axis], v.w_row[axis] * box.max[axis]);
    float far_squared = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const float d = std::max(std::fabs(v.eye[axis] - box.min[axis]), std::fabs(box.max[axis] - v.eye[axis]));
        far_squared += d * d;
    }
    const float farthest = std::sqrt(far_squared);
    const float scale = std::abs(v.area_scale) * farthest;
    if (nearest_w > v.near)
        return scale / (nearest_w * nearest_w * nearest_w);
    // Across the near plane: a triangle wholly beyond it has every w
    // above the near distance, one across it the score below.
    return std::max(scale / (v.near * v.near * v.near), 1.0f / (v.near * v.near));
}

void TriangleOccluders::take(float score, std::uint32_t t, std::uint32_t slot, float nearest_w)
{
    if (full() && !(score > smallest_chosen()))
        return;
    // The best `budget_` in a min-heap: its top, once full, is the score
    // to beat.
    const auto smaller_first = [](const Chosen &a, const Chosen &b) { return a.score > b.score; };
    if (full())
        std::pop_heap(chosen_.begin(), chosen_.end(), smaller_first);
    else
        chosen_.emplace_back();
    // std::push_heap of the new one at the back, the same sift up (a parent
    // that scores more moves down into the hole), written out so that the
    // new one stays in registers: std::push_heap reads it back from the
    // memory just written field by field, a store-forwarding stall.
    std::size_t hole = chosen_.size() - 1;
    while (hole > 0) {
        const std::size_t parent = (hole - 1) / 2;
        if (!(chosen_[parent].score > score))
            break;
        chosen_[hole] = chosen_[parent];
        hole = parent;
    }
    chosen_[hole] = Chosen{score, t, slot, nearest_w};
}

void TriangleOccluders::scan(const Group &g, float per_area, float nearest_w, unsigned planes)
{
    // Beyond the near plane a triangle's own plane bounds its score:
    // area_scale (n . (e - p0)) over the box's nearest w cubed.
    const bool beyond_near = nearest_w > view_.near;
    const float nearest_cubed = nearest_w * nearest_w * nearest_w;
    choice::LaneScores lanes;
    for (std::uint32_t done = 0; done < g.count; done += 8) {
        const std::uint32_t first = g.first + done, slot = g.slot + done;
        if (full() && !(lanes_.at(choice::twice_area, slot) * per_area > smallest_chosen()))
            return;
        // Eight scored at once; what depends on the budget's smallest
        // score, which rises as triangles are taken, is tested one by one,
        // on the kept lanes alone: the group is largest first and the score
        // to beat does not move over the lanes skipped, so where a skipped
        // lane's bound falls short, the next kept lane's does too.
        const int count = int(std::min<std::uint32_t>(8, g.count - done));
        score_lanes_(lanes_, nullptr, slot, count, view_, planes, lanes);
        for (unsigned kept = lanes.keep; kept != 0; kept &= kept - 1) {
            const int i = __builtin_ctz(kept);
            const std::uint32_t t = first + std::uint32_t(i);
            if (full() && !(lanes_.at(choice::twice_area, slot + std::uint32_t(i)) * per_area > smallest_chosen()))
                return;
            if (taken_again_[t])
                continue;
            const float most = lanes.most[i];
            if (beyond_near && (!(most > 0.0f) || (full() && !(most > smallest_chosen() * nearest_cubed))))
                continue;
            take(lanes.score[i], t, slot + std::uint32_t(i), lanes.nearest_w[i]);
        }
    }
}

void TriangleOccluders::prefetch_best() const
{
    if (candidates_.empty())
        return;
    const Group &g = candidates_.front().open;
    if (g.slot != inner_node) {
        const char *block = reinterpret_cast<const char *>(lanes_.blocks + g.slot / 8 * choice::block_floats);
        constexpr std::size_t block_bytes = choice::block_floats * sizeof(float);
        for (std::size_t byte = 0; byte < block_bytes; byte += 64)
            __builtin_prefetch(block + byte);
        __builtin_prefetch(block + block_bytes - 1);
        __builtin_prefetch(&taken_again_[g.first]);
    } else {
        for (int axis = 0; axis < 3; ++axis) {
            __builtin_prefetch(node_boxes_.min[axis] + g.first);
            __builtin_prefetch(node_boxes_.max[axis] + g.first);
        }
        __builtin_prefetch(&openings_[g.first]);
        __builtin_prefetch(&openings_[g.first + g.count - 1]);
    }
}

void TriangleOccluders::offer(std::uint32_t first, std::uint32_t count, unsigned planes)
{
    const auto smaller_bound = [](const Candidate &a, const Candidate &b) { return a.bound < b.bound; };
    choice::LaneBounds lanes;
    for (std::uint32_t done = 0; done < count; done += 8) {
        const std::uint32_t batch = first + done;
        const int in_batch = int(std::min<std::uint32_t>(8, count - done));
        bound_boxes_(node_boxes_, batch, in_batch, view_, planes, lanes);
        for (int i = 0; i < in_batch; ++i) {
            const Opening &o = openings_[batch + std::uint32_t(i)];
            if (!(o.largest > 0.0f))
                continue;
            const float bound = o.largest * lanes.per_area[i];
            if ((full() && !(bound > smallest_chosen())) || (lanes.outside >> i & 1u))
                continue;
            candidates_.push_back({bound, o.group, lanes.crossing[i], lanes.per_area[i], lanes.nearest_w[i]});
            std::push_heap(candidates_.begin(), candidates_.end(), smaller_bound);
        }
    }
}

const std::vector<std::uint32_t> &TriangleOccluders::choose(const Frame &frame)
{
    chosen_.clear();
    if (budget_ == 0 || groups_.empty()) {
        drawn_indices_.clear();
        return drawn_indices_;
    }
    const glm::mat4 &vp = frame.view_projection;
    view_.eye = frame.camera.position;
    view_.w_row = glm::vec4(vp[0][3], vp[1][3], vp[2][3], vp[3][3]);
    const glm::vec3 x_row(vp[0][0], vp[1][0], vp[2][0]), y_row(vp[0][1], vp[1][1], vp[2][1]);
    view_.area_scale = -glm::dot(x_row, glm::cross(y_row, glm::vec3(view_.w_row)));
    view_.near = std::max(frame.camera.near_plane, 1e-6f);
    std::copy(frame.frustum.planes().begin(), frame.frustum.planes().end(), view_.planes);
    // Last frame's choice first: the smallest score to beat starts high.
    const choice::TriangleLanes last{last_chosen_blocks_.data()};
    choice::LaneScores lanes;
    for (std::size_t first = 0; first < last_chosen_.size(); first += 8) {
        const int count = int(std::min<std::size_t>(8, last_chosen_.size() - first));
        score_lanes_(last, nullptr, std::uint32_t(first), count, view_, Frustum::all_planes, lanes);
        for (int i = 0; i < count; ++i) {
            const std::uint32_t t = last_chosen_[first + std::size_t(i)];
            taken_again_[t] = 1;
            if (lanes.keep & (1u << i))
                take(lanes.score[i], t, last_slots_[first + std::size_t(i)], lanes.nearest_w[i]);
        }
    }
    if (!hierarchy_) {
        unsigned planes = Frustum::all_planes;
        if (frame.frustum.classify(bounds_, planes) != Frustum::Side::outside) {
            float nearest_w;
            const float per_area = bound_per_area(bounds_, nearest_w);
            scan(groups_.front(), per_area, nearest_w, planes);
        }
    } else {
        // The nodes best bound first; a leaf is scanned when it comes up.
        const auto smaller_bound = [](const Candidate &a, const Candidate &b) { return a.bound < b.bound; };
        candidates_.clear();
        offer(0, 1, Frustum::all_planes);
        while (!candidates_.empty()) {
            const Candidate c = candidates_.front();
            if (full() && !(c.bound > smallest_chosen()))
                break;
            std::pop_heap(candidates_.begin(), candidates_.end(), smaller_bound);
            candidates_.pop_back();
            prefetch_best();
            if (c.open.slot != inner_node)
                scan(c.open, c.per_area, c.nearest_w, c.planes);
            else
                offer(c.open.first, c.open.count, c.planes);
        }
    }
    for (std::uint32_t t : last_chosen_)
        taken_again_[t] = 0;
    // Nearest first (by the nearest corner's clip w), as a z-buffer fills.
    std::sort(chosen_.begin(), chosen_.end(), [](const Chosen &a, const Chosen &b) { return a.nearest_w < b.nearest_w; });
    last_chosen_.resize(chosen_.size());
    last_slots_.resize(chosen_.size());
    last_chosen_blocks_.resize((chosen_.size() + 7) / 8 * choice::block_floats, 0.0f);
    // Every index is written below: resized from last frame's size, not
    // from empty, the vector fills nothing first (a frame's choice is
    // mostly as large as the last).
    drawn_indices_.resize(3 * chosen_.size());
    for (std::size_t i = 0; i < chosen_.size(); ++i) {
        const std::uint32_t t = chosen_[i].triangle;
        last_chosen_[i] = t;
        last_slots_[i] = chosen_[i].slot;
        choice::copy_slot(lanes_, chosen_[i].slot, last_chosen_blocks_.data(), std::uint32_t(i));
        for (std::uint32_t v = 0; v < 3; ++v)
            drawn_indices_[3 * i + v] = 3 * t + v;
    }
    return drawn_indices_;
}

}  // namespace occu
