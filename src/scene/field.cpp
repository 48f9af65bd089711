// SPDX-License-Identifier: MIT
#include "scene/field.h"

#include <random>
#include <stdexcept>

#include "scene/palette.h"

namespace occu {

Scene generate_field(const FieldOptions &o)
{
    if (o.count_x < 1 || o.count_z < 1 || !(o.post_size > 0.0f) || !(o.spacing > o.post_size) ||
        !(o.min_height > 0.0f) || !(o.max_height >= o.min_height))
        throw std::invalid_argument("field: posts need a positive size and height and room between them");
    Scene scene;
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float margin = 0.5f * o.spacing;
    std::uint32_t hue = 0;
    for (int z = 0; z < o.count_z; ++z)
        for (int x = 0; x < o.count_x; ++x) {
            const float height = o.min_height + unit(rng) * (o.max_height - o.min_height);
            const glm::vec3 lo{margin + x * o.spacing - 0.5f * o.post_size, 0.0f,
                               margin + z * o.spacing - 0.5f * o.post_size};
            const glm::vec3 hi = lo + glm::vec3(o.post_size, height, o.post_size);
            // Never the hue of the post before, as the city's lots.
            hue = (hue + 1 + std::uint32_t(rng() % (facade_hue_count() - 1))) % facade_hue_count();
            const BuildingColours colours = building_colours(hue, unit(rng), unit(rng));
            Mesh m;
            m.color = colours.wall;
            append_box(m, Aabb::of(lo, hi));
            // The top in the roof colour, the sides in the wall's.
            for (std::size_t v = 0; v < m.positions.size(); ++v)
                m.colors.push_back(m.normals[v].y > 0.5f ? colours.roof : colours.wall);
            m.update_bounds();
            scene.meshes.push_back(std::move(m));
            PrismOccluder p;
            p.outline = {{lo.x, lo.z}, {hi.x, lo.z}, {hi.x, hi.z}, {lo.x, hi.z}};
            p.bottom = lo.y;
            p.top = double(hi.y);
            scene.prism_occluders.push_back(std::move(p));
        }
    // The ground: one quad facing up, with nothing under it (the city's is a
    // box 1 m deep): a node holding a face below the ground would have a
    // box reaching under it, which the ground hides where the node shows
    // nothing else, and occlusion tests would find that.
    Mesh ground;
    ground.name = "ground";
    ground.color = street_colour();
    const float gx = o.count_x * o.spacing, gz = o.count_z * o.spacing;
    ground.positions = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, gz}, {gx, 0.0f, gz}, {gx, 0.0f, 0.0f}};
    ground.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
    ground.indices = {0, 1, 2, 0, 2, 3};   // counter-clockwise seen from above
    ground.update_bounds();
    scene.meshes.push_back(std::move(ground));
    scene.update_bounds();
    return scene;
}

}  // namespace occu
