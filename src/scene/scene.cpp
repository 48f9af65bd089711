// SPDX-License-Identifier: MIT
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

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

void require_finite_vertices(const Mesh &mesh, std::size_t mesh_number, const std::string &source)
{
    auto finite = [](const glm::vec3 &p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
    const auto first = std::find_if_not(mesh.positions.begin(), mesh.positions.end(), finite);
    if (first == mesh.positions.end())
        return;
    const auto count = std::count_if(first, mesh.positions.end(), [&](const glm::vec3 &p) { return !finite(p); });
    char coordinates[96];
    std::snprintf(coordinates, sizeof(coordinates), "(%g, %g, %g)", double(first->x), double(first->y),
                  double(first->z));
    const std::string name = mesh.name.empty() ? std::to_string(mesh_number) + " (unnamed)" : "'" + mesh.name + "'";
    throw std::runtime_error(source + ": vertex " + std::to_string(first - mesh.positions.begin()) + " of mesh " +
                             name + " is " + coordinates + ", not finite; " + std::to_string(count) + " of " +
                             std::to_string(mesh.positions.size()) +
                             " vertices of that mesh are not finite (occu needs finite coordinates)");
}

void require_finite_vertices(const Scene &scene, const std::string &source)
{
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        require_finite_vertices(scene.meshes[m], m, source);
}

bool collinear_corners(const glm::vec3 &a, const glm::vec3 &b, const glm::vec3 &c)
{
    const glm::dvec3 p(a), q(b), r(c);
    const double longest = std::max({glm::length(q - p), glm::length(r - q), glm::length(p - r)});
    const glm::dvec3 m = glm::max(glm::max(glm::abs(p), glm::abs(q)), glm::abs(r));
    const double step = std::max({m.x, m.y, m.z}) * double(std::numeric_limits<float>::epsilon());
    // Twice the area is the longest edge times the height over it.
    return glm::length(glm::cross(q - p, r - p)) <= longest * step;
}

std::size_t remove_collinear_triangles(Mesh &mesh)
{
    std::size_t kept = 0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t *i = &mesh.indices[t];
        if (collinear_corners(mesh.positions[i[0]], mesh.positions[i[1]], mesh.positions[i[2]]))
            continue;
        std::copy(i, i + 3, mesh.indices.begin() + std::ptrdiff_t(kept));
        kept += 3;
    }
    const std::size_t removed = (mesh.indices.size() - kept) / 3;
    mesh.indices.resize(kept);
    return removed;
}

void append_box(Mesh &mesh, const Aabb &box)
{
    // Outward normals in aabb_faces' order: -x, +x, -y, +y, -z, +z.
    static const glm::vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (int f = 0; f < 6; ++f) {
        const auto base = std::uint32_t(mesh.positions.size());
        for (int c : aabb_faces[f]) {
            mesh.positions.push_back(box.corner(c));
            mesh.normals.push_back(normals[f]);
            if (!mesh.colors.empty())
                mesh.colors.push_back(mesh.color);
        }
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    mesh.bounds.expand(box);
}

}  // namespace occu
