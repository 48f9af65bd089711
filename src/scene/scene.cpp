#include "scene/scene.h"

namespace occu {

void Mesh::update_bounds()
{
    bounds = Aabb{};
    for (const glm::vec3 &p : positions)
        bounds.expand(p);
}

std::size_t Scene::triangle_count() const
{
    std::size_t n = 0;
    for (const Mesh &m : meshes)
        n += m.triangle_count();
    return n;
}

void Scene::update_bounds()
{
    bounds = Aabb{};
    for (Mesh &m : meshes) {
        m.update_bounds();
        bounds.expand(m.bounds);
    }
}

void append_box(Mesh &mesh, const Aabb &box)
{
    // Each face: outward normal, then its four corners counter-clockwise
    // seen from outside (corner index bits: x, y, z).
    struct Face {
        glm::vec3 normal;
        int corners[4];
    };
    static const Face faces[6] = {
        {{-1, 0, 0}, {0, 4, 6, 2}}, {{1, 0, 0}, {1, 3, 7, 5}}, {{0, -1, 0}, {0, 1, 5, 4}},
        {{0, 1, 0}, {2, 6, 7, 3}},  {{0, 0, -1}, {0, 2, 3, 1}}, {{0, 0, 1}, {4, 5, 7, 6}},
    };
    for (const Face &f : faces) {
        const auto base = std::uint32_t(mesh.positions.size());
        for (int c : f.corners) {
            mesh.positions.push_back(box.corner(c));
            mesh.normals.push_back(f.normal);
        }
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    mesh.bounds.expand(box);
}

}  // namespace occu
