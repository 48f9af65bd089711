// SPDX-License-Identifier: MIT
// Coherent hierarchical culling on the Occlusion Unit: Bittner, Wimmer,
// Piringer and Purgathofer, "Coherent Hierarchical Culling: Hardware
// Occlusion Queries Made Useful" (Eurographics 2004), and Mattausch,
// Bittner and Wimmer, "CHC++: Coherent Hierarchical Culling Revisited"
// (Eurographics 2008), with GL_MESAX_occlusion_unit's tiles for their
// queries and GL_MESAX_occlusion_unit_async's named passes for their
// asynchrony (gl/occlusion_unit.h; emulated on glRenderMode, with the
// same results and every wait in the pass's end, where the context lacks it).
//
// CHC (2004), its algorithm (section numbers are left out here: cited from
// memory, not checked against the papers): the hierarchy is traversed front to back
// (a queue ordered by distance); temporal coherence decides what is
// tested. Nodes that were visible in the previous frame are not waited
// for: a visible leaf is drawn at once, a visible inner node opened at
// once. Nodes that were not (the termination nodes of the previous
// frame's visible front) are tested, and their results are handled when
// they arrive while the traversal goes on; a node found visible is opened
// (or drawn) then. Visibility is pulled up: a visible node makes its
// ancestors visible for the next frame, and an inner node none of whose
// descendants stayed visible is tested as a whole the next frame.
//
// A frame without history (the first, or the first after the switch-off
// kept chc off: nothing was visible in the previous frame) has nothing to
// draw while its tests are pending, so tests issued ahead of the results in
// front of them would all meet an empty depth buffer. There the traversal
// waits as the general algorithm does (Moeller and Haines, figure 2; Bartz
// et al. 1998, section 3): a batch of the nearest nodes, its results, the
// leaves found visible drawn, then the nodes behind them.
//
// CHC++ (2008): previously visible leaves are re-tested only
// every `period` frames, each from its own random offset so that the tests
// spread over frames (their results only classify the leaf for the next
// frame: it is drawn this frame whatever they say), and these tests wait
// in a queue of their own, filling the time the traversal would otherwise
// wait for results (here: the free tiles of passes, and the wait at the
// end of a frame); previously invisible nodes are tested in batches
// (its multiqueries); and tighter bounds: an inner node is tested
// by the boxes of its descendants instead of its own box.
//
// Conditional rendering on a tile (GL_MESAX_occlusion_unit_async; the
// setting `conditional`): a previously invisible leaf may be drawn under the
// condition that its tile of its pass was visible, so that the GL decides
// and nobody waits for the record (CHC++ draws such nodes only once their
// query returns). By default (`waits`) only in place of a wait: when the
// traversal has nothing left but results, none of them an inner node's
// (`always`: right after the pass; `off`: never). The records of passes
// whose results only classify nodes for the next frame (re-tests,
// conditional draws) are not waited for at the frame's end: they are read
// at the next frame's start, which is where they are used.
//
// The strategy is that traversal (coherent_hierarchical_culler.cpp, an
// OwnTraversal of traversal/traversal.h) over an asynchronous culler
// (culling/async_culler.h): the Occlusion Unit's passes
// (occlusion_unit_async_culler.h).
//
// The Occlusion Unit changes two things. A batch is one pass with one tile
// per node (the node's footprint), so every node gets its own count from
// the one pass and nothing is re-tested after a failed multiquery. Tiles
// of a pass may overlap: another node's fragments in a tile can only make
// its node look visible, never occluded, so this stays conservative (as
// ou's passes=shared). A node's tight bounds are drawn in its tile, whose
// rectangle is the union of their footprints.
//
// Conservative at tolerance 0: a node is culled only by its own test
// against depth that belongs to the final frame; nodes taken as visible
// untested (previously visible, too large to test, without a footprint or
// a proxy) are drawn or opened, which costs time, never pixels; and every
// node that was not visible in the previous frame is tested in this one.
// With tolerance t > 0 (CHC++'s visibility threshold; every approximation
// knob of the registry is called tolerance) a node is occluded when
// NOHC <= t * PHC (Bartz et al. 1998, section 5, as ou's tolerance).
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily coherent_hierarchical_culling_family();

}  // namespace occu::strategies
