// SPDX-License-Identifier: MIT
// A Quake III level's own visibility: the potentially visible set its map
// compiler stored (q3map -vis). The compiler splits the level's empty
// space into the convex leaves of its BSP tree, groups them into clusters
// joined by portals, and records for every cluster the clusters seen
// through any sequence of portals: Teller and Sequin's cell-portal
// visibility ("Visibility preprocessing for interactive walkthroughs",
// SIGGRAPH 1991; cells, portals and per-cell PVS as Wonka, Wimmer and
// Schmalstieg 2000 describe them in section 1.2). At run time Quake III's
// renderer finds the eye's cluster by descending the BSP tree and draws a
// surface when it lies in a leaf of a cluster that cluster sees.
//   bsp-pvs   does the same over occu's hierarchy: the eye's leaf by
//             descending the tree (scene/level.h: Level::leaf_at),
//             its cluster's row of the visibility data, and a hierarchy node
//             drawn (opened) when one of its triangles belongs to a face that
//             lies in a leaf of a visible cluster; the rest is occluded, and
//             what lies outside the frustum view-culled. No per-frame
//             occlusion work: the set is looked up once per cluster.
//             Fallbacks, as Quake III's renderer: an eye in no cluster
//             (outside the level, inside a solid: cluster < 0) or a level
//             without visibility data draws every cluster (view-frustum
//             culling). Faces of brush entities (doors, platforms: models
//             other than 0) lie in no leaf and are always drawn; a world face
//             in no leaf of any cluster is never drawn (Quake III never draws
//             it either). The compiler's set says what the level's solids
//             hide, but a solid's faces on a side no player should see are
//             often not drawn (caulk: nodraw), and an eye on that side sees
//             through the solid in occu's frames: from random eyes in open
//             leaves (cluster >= 0) of OpenArena's oa_minia and czest2ctf the
//             set culls leaves the oracle sees and the frames lose pixels
//             (docs/real-scenes.md). From the spawn points, where players
//             stand, it loses none: with a level's sky faces drawn as the
//             walls they are to a player (scene/quake3_bsp.h), every view of
//             spawn:2 of every level of Debian's OpenArena data keeps every
//             pixel (the test level-spawns-pvs-lossless) but one, where the
//             level's author left a side of a solid brush that players see
//             caulked (nodraw) and the eye looks into the solid: the game
//             draws nothing there either (docs/real-scenes.md, "Every spawn
//             point of every level"). So it is conservative for spawn routes,
//             not for every eye: the family is not declared conservative, and
//             runs compare its frames with the unculled ones. The run's
//             summary counts the frames of each kind.
// Needs a Quake III level (scene.level); refuses other scenes.
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily bsp_pvs_family();

}  // namespace occu::strategies
