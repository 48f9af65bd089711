// SPDX-License-Identifier: MIT
// A level: the one view of a level's data that routes, strategies and
// occluder sources read (Scene::level), whatever read the file. Its BSP
// tree, leaves and the faces each leaf holds (as ranges of the scene's
// meshes), the clusters and their potentially visible set, the world's
// opaque solid brushes, and the player spawn points. Today Quake III's
// IBSP files make it (scene/quake3_bsp.h, which keeps the file's own
// records, such as its textures, to itself): a level's units and axes are
// Quake's, which is why a brush's planes and the conversion below are
// named after it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"

namespace occu {

// Metres per Quake unit.
inline constexpr float quake3_unit_metres = 0.0254f;
// A Quake point (x, y, z) in occu's coordinates.
inline glm::vec3 quake3_to_occu(const glm::vec3 &q)
{
    return quake3_unit_metres * glm::vec3(q.x, q.z, -q.y);
}

// A player spawn point (info_player_deathmatch, info_player_start and the
// team spawns team_CTF_redplayer, team_CTF_blueplayer, team_CTF_redspawn,
// team_CTF_bluespawn).
struct LevelSpawn {
    std::string classname;
    glm::vec3 origin;      // the entity's origin
    glm::vec3 eye;         // where the game puts a player's eye: 9 units above the origin
                           // (its spawn lift) plus the view height, 26 units
    float yaw_degrees = 0; // "angle" (or the yaw of "angles"): counter-clockwise about Quake's z from its +x
    glm::vec3 direction;   // the horizontal unit vector the yaw names
};

// The level's BSP, in occu's coordinates (planes: dot(normal, p) = distance).
struct Level {
    struct Plane {
        glm::vec3 normal;
        float distance;
    };
    struct Node {
        std::int32_t plane;
        // A child >= 0 is a node (always after its parent); < 0 is the leaf
        // -(child + 1). Child 0 is in front of the plane, child 1 behind.
        std::int32_t children[2];
        Aabb bounds;
    };
    struct Leaf {
        std::int32_t cluster;   // < 0: outside the level or inside a solid
        std::int32_t area;
        Aabb bounds;
        std::uint32_t first_leaf_face, leaf_face_count;   // into leaf_faces
    };
    // Where a face of the file went: `mesh` of the scene (-1: not drawn) and
    // its triangles' indices there, [first_index, first_index + index_count).
    struct Face {
        std::int32_t type;      // 1 polygon, 2 patch, 3 mesh, 4 billboard
        std::int32_t texture;
        std::int32_t model;     // 0: the world; others: brush entities
        std::int32_t mesh = -1;
        std::uint32_t first_index = 0, index_count = 0;
    };

    std::vector<Plane> planes;
    std::vector<Node> nodes;        // nodes[0] the root of the world
    std::vector<Leaf> leaves;
    std::vector<std::uint32_t> leaf_faces;   // face indices
    std::vector<Face> faces;
    std::vector<LevelSpawn> spawns;
    // The compiler's potentially visible set: cluster_count bit vectors of
    // bytes_per_cluster bytes. Empty (cluster_count 0) when the level was
    // not vis'ed: then every cluster sees every other.
    std::int32_t cluster_count = 0;
    std::int32_t bytes_per_cluster = 0;
    std::vector<std::uint8_t> visibility;

    // The world's (model 0's) opaque solid brushes: CONTENTS_SOLID (0x1),
    // none of the see-through contents (scene/quake3_bsp.h), no sky side.
    // Their bounds, in occu's coordinates: an eye must keep clear of every
    // one.
    std::vector<Aabb> solid_brush_bounds;
    // The same brushes in Quake's coordinates (the file's planes, inside
    // where dot(normal, p) <= w), for a level's brushes as occluders
    // (occluders/brush_occluders.h).
    struct Brush {
        std::vector<glm::vec4> planes;
        glm::vec3 lo, hi;          // bounds, from its axial (bevel) sides
        std::int32_t number = 0;   // in the brushes lump
    };
    std::vector<Brush> opaque_solids;

    // What the file held that was not drawn or does not hide, counted for
    // statistics.
    std::size_t patch_count = 0, billboard_count = 0, hidden_face_count = 0, see_through_face_count = 0;

    // The leaf holding `p`, by descending the tree from the root.
    std::int32_t leaf_at(const glm::vec3 &p) const;
    // Whether cluster `to` is in the PVS of cluster `from` (true when
    // either is < 0 or the level has no visibility data).
    bool cluster_sees(std::int32_t from, std::int32_t to) const;
};

}  // namespace occu
