// SPDX-License-Identifier: MIT
// What a Quake III level holds, counted from the scene occu read
// (scene/quake3_bsp.h), for the benches that choose levels by it and
// report them (occu-bench-level-load, occu-bench-real-scenes;
// docs/real-scenes.md): one CSV row a level.
#pragma once

#include <cstdio>
#include <string>

#include "scene/level.h"
#include "scene/scene.h"

namespace occu {

struct LevelStatistics {
    std::size_t triangles = 0, meshes = 0, see_through_meshes = 0, see_through_triangles = 0, faces = 0,
                drawn_patches = 0, patches = 0, see_through_faces = 0, billboards = 0, hidden_faces = 0, leaves = 0,
                open_leaves = 0, spawns = 0;
    int clusters = 0;
    glm::vec3 size{0.0f};   // the scene's bounds, metres

    // The CSV columns of row(), without a leading or trailing comma.
    static const char *columns()
    {
        return "triangles,meshes,see_through_meshes,see_through_triangles,faces,drawn_patches,patches,"
               "see_through_faces,billboards,hidden_faces,leaves,open_leaves,clusters,spawns,size_x_m,size_y_m,"
               "size_z_m";
    }
    std::string row() const
    {
        char text[400];
        std::snprintf(text, sizeof(text), "%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%d,%zu,%.1f,%.1f,%.1f",
                      triangles, meshes, see_through_meshes, see_through_triangles, faces, drawn_patches, patches,
                      see_through_faces, billboards, hidden_faces, leaves, open_leaves, clusters, spawns,
                      double(size.x), double(size.y), double(size.z));
        return text;
    }
};

// The statistics of `scene`, a level (scene.level set).
inline LevelStatistics level_statistics(const Scene &scene)
{
    const Level &level = *scene.level;
    LevelStatistics s;
    s.triangles = scene.triangle_count();
    s.meshes = scene.meshes.size();
    for (const Mesh &m : scene.meshes)
        if (!m.occluder) {
            ++s.see_through_meshes;
            s.see_through_triangles += m.triangle_count();
        }
    s.faces = level.faces.size();
    for (const Level::Face &f : level.faces)
        s.drawn_patches += f.type == 2 && f.mesh >= 0;
    s.patches = level.patch_count;
    s.see_through_faces = level.see_through_face_count;
    s.billboards = level.billboard_count;
    s.hidden_faces = level.hidden_face_count;
    s.leaves = level.leaves.size();
    for (const Level::Leaf &l : level.leaves)
        s.open_leaves += l.cluster >= 0;
    s.clusters = level.cluster_count;
    s.spawns = level.spawns.size();
    s.size = scene.bounds.extent();
    return s;
}

}  // namespace occu
