#include "scene/field.h"

#include <random>
#include <stdexcept>

#include "scene/palette.h"

namespace occu {

Scene generate_field(const FieldOptions &o)
{
    if (o.count_x < 1 || o.count_z < 1 || !(o.post_size > 0.0f) || !(o.ledge_depth >= 0.0f) ||
        !(o.spacing > o.post_size + 2.0f * o.ledge_depth) || !(o.min_height > 0.0f) || !(o.max_height >= o.min_height))
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
            hue = (hue + 1 + std::uint32_t(rng() % (facade_hue_count() - 1))) % facade_hue_count();
            const BuildingColours colours = building_colours(hue, unit(rng), unit(rng));
            Mesh m;
            m.color = colours.wall;
            append_box(m, Aabb::of(lo, hi));
            // The top in the roof colour, the sides in the wall's.
            for (std::size_t v = 0; v < m.positions.size(); ++v)
                m.colors.push_back(m.normals[v].y > 0.5f ? colours.roof : colours.wall);
            // The ledge halfway up, one box per face, as the city's buildings
            // have at every floor (scene/city.cpp).
            m.color = colours.trim;
            const float y = lo.y + 0.5f * height, t = 0.15f, d = o.ledge_depth;
            append_box(m, Aabb::of({lo.x - d, y, lo.z - d}, {hi.x + d, y + t, lo.z}));
            append_box(m, Aabb::of({lo.x - d, y, hi.z}, {hi.x + d, y + t, hi.z + d}));
            append_box(m, Aabb::of({lo.x - d, y, lo.z}, {lo.x, y + t, hi.z}));
            append_box(m, Aabb::of({hi.x, y, lo.z}, {hi.x + d, y + t, hi.z}));
            m.color = colours.wall;
            m.update_bounds();
            scene.meshes.push_back(std::move(m));
            PrismOccluder p;
            p.outline = {{lo.x, lo.z}, {hi.x, lo.z}, {hi.x, hi.z}, {lo.x, hi.z}};
            p.bottom = lo.y;
            p.top = double(hi.y);
            scene.prism_occluders.push_back(std::move(p));
        }
    Mesh ground;
    ground.name = "ground";
    ground.color = street_colour();
    append_box(ground, Aabb::of({0.0f, -1.0f, 0.0f}, {o.count_x * o.spacing, 0.0f, o.count_z * o.spacing}));
    scene.meshes.push_back(std::move(ground));
    scene.update_bounds();
    return scene;
}

}  // namespace occu
