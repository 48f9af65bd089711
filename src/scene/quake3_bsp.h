// SPDX-License-Identifier: MIT
// Quake III Arena levels (IBSP version 46, as id's q3map and its
// successors write them and Debian's OpenArena data ships them) read by
// occu itself. assimp 5.2.5's BSP importer makes meshes its own validation
// refuses ("aiMesh::mFaces[0]::mIndices[0] is out of range") on OpenArena's
// levels, and a level is more than triangles: its BSP tree, leaves,
// clusters and the compiler's cluster-to-cluster visibility (the PVS) are
// what a culler is judged against on such scenes.
//
// The format (from Kekoa Proudfoot's "Unofficial Quake 3 Map Specs"): a
// header ("IBSP", version 46, a directory of 17 lumps, each an offset and
// a length in bytes), then the lumps, little-endian records of 4-byte
// ints and floats. Every read is bounded: a lump must lie inside the file
// and hold whole records, and every index one record holds into another
// lump (a face's texture, vertices and meshverts, a node's plane and
// children, a leaf's faces, a model's faces) must lie inside that lump;
// otherwise the level is refused with a message naming the file and the
// lump (and the record). A vertex, plane or visdata record that is not
// finite or not consistent is refused the same way; the file is never
// partly used.
//
// What is drawn. Faces of type 1 (planar polygons) and 3 (triangle
// meshes, misc_model geometry the compiler baked in) as the triangles
// their meshverts list; faces of type 2 (Bezier patches: a grid of
// width x height control points, odd sizes, read as (width-1)/2 x
// (height-1)/2 biquadratic pieces of 3x3 points) tessellated into
// `patch_segments` x `patch_segments` quads a piece (one segment along a
// direction in which the whole patch is straight and evenly
// parameterized, which is then exact: OpenArena's arches and pipes are
// often curved one way only); faces of type 4
// (billboards: flares, sprites) are not drawn, nor faces whose texture's
// surface flags say SURF_NODRAW (0x80; clip, caulk, trigger and hint
// brushes), nor triangles whose corners are collinear to float precision
// (scene/scene.h: collinear_corners; a polygon fanned from an end of an
// edge holding a T-junction's vertex makes them). Faces whose texture says
// SURF_SKY (0x4) are drawn where they
// are, opaque and unlit (Mesh::shaded false), in a sky colour: Quake III
// draws the sky's images at infinity through exactly those faces, so a
// player sees sky there and nothing behind them (a level may hold several
// arenas, each sealed in its own box of sky brushes: OpenArena's delta).
// Faces of every model are drawn, the world (model 0) and the
// brush entities (doors, platforms: at their resting place).
//
// Translucency, from the format alone (a BSP records each texture's
// compiled surface flags and content flags, not its shader's blending):
// a face is see-through -- drawn, but never an occluder (Mesh::occluder
// false) -- when its texture's content flags hold CONTENTS_TRANSLUCENT
// (0x20000000: q3map sets it for `surfaceparm trans`, which every shader
// drawn with blending or alpha testing must carry for the compiler's
// visibility to see through it), CONTENTS_WATER (0x20) or CONTENTS_FOG
// (0x40; water and fog volumes are drawn blended), or its surface flags
// hold SURF_ALPHASHADOW (0x10000: the lighting compiler casts per-pixel
// alpha-tested shadows from it). Lava and slime are opaque (Quake III's
// MASK_OPAQUE). A shader that blends without any of these marks (a decal,
// a flame) is taken as opaque: nothing in the BSP tells it apart.
//
// The look (Quake3Options::look): texture and lightmap coordinates and
// vertex colours per vertex (interpolated over patches as positions are),
// the faces' lightmap pages into one atlas (Scene::images), meshes one a
// texture and lightmapping; the pictures themselves, scene/quake3_look.h.
//
// Coordinates. Quake's world is right-handed, z up, in game units (one
// inch, by id's scale: a player stands 56 units tall); occu's is
// right-handed, y up, in metres (geometry/aabb.h). A Quake point
// (x, y, z) is occu's 0.0254 * (x, z, -y): a rotation (it keeps windings
// and handedness) and a scale. Every position, plane, box and spawn point
// of the Level it makes (scene/level.h) is in occu's coordinates. Triangles are wound
// counter-clockwise seen from their front (occu's convention; the file's
// meshverts are clockwise, as Quake III's renderer culls).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/level.h"
#include "scene/scene.h"

namespace occu {

struct Quake3Options {
    // Quads along each direction of each 3x3 biquadratic patch piece,
    // 1..64. 8 is the finest q3map2 makes of a curve when it turns
    // patches into meshes itself (-patchmeta: up to 3 halvings a piece);
    // Quake III's renderer subdivides until the chord is within 4 units
    // of the curve, which for OpenArena's pillars and arches is 4 to 16.
    int patch_segments = 8;
    // Whether to read what the look of the level needs (Mesh::texcoords,
    // lightmap_coords, vertex_light, lightmapped; the lightmaps into one
    // atlas, Scene::images and lightmap_atlas): each face's texture
    // coordinates, its lightmap (lump 14, 128 x 128 RGB pages, brightened
    // as Quake III's renderer does by default: doubled, scaled back to the
    // largest channel where one would clip) or, for a face without one,
    // its vertex colours. Meshes are then one a texture and lightmapping.
    // The textures' pictures come from the pk3 files (scene/quake3_look.h).
    // load_scene reads a model's pictures under the same flag
    // (scene/scene_file.h).
    bool look = false;
};

// Reads a level from `bytes` (a .bsp file's, or a pk3 member's). `source`
// names it in messages ("maps/x.bsp", "pak.pk3:maps/x.bsp"). Returns its
// drawn faces as meshes of `scene` (one a texture, named by it, coloured
// by the palette, `occluder` false for see-through textures; bounds
// updated) and sets scene.level to the level (scene/level.h). Throws std::runtime_error
// beginning "cannot read scene '<source>': Quake III BSP: " and naming the
// lump. Warnings (normals replaced) go to `warnings`.
Scene read_quake3_bsp(const std::string &source, const std::vector<char> &bytes, const Quake3Options &options,
                      std::vector<std::string> &warnings);

// Whether `bytes` begins as an IBSP file ("IBSP" magic).
bool looks_like_ibsp(const std::vector<char> &bytes);

}  // namespace occu
