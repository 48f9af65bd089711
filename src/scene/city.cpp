// SPDX-License-Identifier: MIT
#include "scene/city.h"

#include <random>

#include "scene/palette.h"

namespace occu {

namespace {

// One building: a body and a ledge around it at every floor (the facade
// detail, which is what makes buildings expensive to draw and cheap to cull).
// Walls in the building's colour, a little darker at street level, the roof
// and the ledges in colours of their own.
Mesh building(const glm::vec3 &corner, const glm::vec3 &size, int floors, const BuildingColours &colours)
{
    Mesh m;
    m.color = colours.wall;
    append_box(m, Aabb::of(corner, corner + size));
    for (std::size_t v = 0; v < m.positions.size(); ++v)
        if (m.normals[v].y > 0.5f)
            m.colors.push_back(colours.roof);
        else
            m.colors.push_back(m.positions[v].y <= corner.y ? colours.wall * 0.8f : colours.wall);
    m.color = colours.trim;   // append_box gives the ledges' vertices this
    const float floor_height = size.y / float(floors);
    const float depth = 0.4f, thickness = 0.25f;
    for (int f = 1; f < floors; ++f) {
        const float y = corner.y + f * floor_height;
        const glm::vec3 lo = corner, hi = corner + size;
        // Four ledges, one per facade, sticking out by `depth`.
        append_box(m, Aabb::of({lo.x - depth, y, lo.z - depth}, {hi.x + depth, y + thickness, lo.z}));
        append_box(m, Aabb::of({lo.x - depth, y, hi.z}, {hi.x + depth, y + thickness, hi.z + depth}));
        append_box(m, Aabb::of({lo.x - depth, y, lo.z}, {lo.x, y + thickness, hi.z}));
        append_box(m, Aabb::of({hi.x, y, lo.z}, {hi.x + depth, y + thickness, hi.z}));
    }
    m.color = colours.wall;
    m.update_bounds();
    return m;
}

}  // namespace

Scene generate_city(const CityOptions &o)
{
    Scene scene;
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    // Colours from a generator of their own, so that the buildings' shapes
    // do not depend on the palette.
    std::mt19937 paint(o.seed ^ 0x9e3779b9u);
    std::uint32_t hue = 0;

    // One grid of blocks, generated once and then copied (as the papers'
    // models copy a block): lots of 4 x 4 around a courtyard per block.
    std::vector<Mesh> grid;
    std::vector<PrismOccluder> grid_occluders;
    const int lots = 4;
    const float lot = (o.block_size - o.street_width) / lots;
    for (int bz = 0; bz < o.blocks_z; ++bz)
        for (int bx = 0; bx < o.blocks_x; ++bx) {
            const glm::vec3 origin{bx * o.block_size + 0.5f * o.street_width, 0.0f,
                                   bz * o.block_size + 0.5f * o.street_width};
            for (int lz = 0; lz < lots; ++lz)
                for (int lx = 0; lx < lots; ++lx) {
                    const bool ring = lx == 0 || lz == 0 || lx == lots - 1 || lz == lots - 1;
                    if (!ring)
                        continue;   // courtyard
                    const int floors = 4 + int(unit(rng) * 14.0f);
                    const float inset = 0.5f + unit(rng) * 1.5f;
                    const glm::vec3 corner = origin + glm::vec3(lx * lot + inset, 0.0f, lz * lot + inset);
                    const glm::vec3 size{lot - 2 * inset, floors * 3.2f, lot - 2 * inset};
                    unit(rng);   // was the building's grey; drawn still, so that later buildings keep their shapes
                    // Never the hue of the lot before.
                    hue = (hue + 1 + std::uint32_t(paint() % (facade_hue_count() - 1))) % facade_hue_count();
                    const float variation = unit(paint), roof = unit(paint);
                    const BuildingColours colours = building_colours(hue, variation, roof);
                    grid.push_back(building(corner, size, floors, colours));
                    // The building's box without its ledges: solid, inside its mesh.
                    PrismOccluder f;
                    const glm::dvec2 lo(corner.x, corner.z), hi(corner.x + size.x, corner.z + size.z);
                    f.outline = {{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}};
                    f.bottom = corner.y;
                    f.top = double(corner.y + size.y);
                    grid_occluders.push_back(std::move(f));
                }
        }

    const glm::vec3 grid_size{o.blocks_x * o.block_size, 0.0f, o.blocks_z * o.block_size};
    for (int cz = 0; cz < o.copies; ++cz)
        for (int cx = 0; cx < o.copies; ++cx) {
            const glm::vec3 offset{cx * grid_size.x, 0.0f, cz * grid_size.z};
            for (const Mesh &b : grid) {
                Mesh m = b;
                for (glm::vec3 &p : m.positions)
                    p += offset;
                m.update_bounds();
                scene.meshes.push_back(std::move(m));
            }
            for (const PrismOccluder &b : grid_occluders) {
                PrismOccluder f = b;
                for (glm::dvec2 &p : f.outline)
                    p += glm::dvec2(offset.x, offset.z);
                scene.prism_occluders.push_back(std::move(f));
            }
        }

    // The ground under everything.
    Mesh ground;
    ground.name = "ground";
    ground.color = street_colour();
    append_box(ground, Aabb::of({0.0f, -1.0f, 0.0f}, {o.copies * grid_size.x, 0.0f, o.copies * grid_size.z}));
    scene.meshes.push_back(std::move(ground));
    scene.update_bounds();
    return scene;
}

}  // namespace occu
