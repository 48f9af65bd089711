// SPDX-License-Identifier: MIT
// The default scene: a city in the manner of the papers' test models
// (Bartz et al. 1998, figure 1; Poon and Wang, section 6): a grid of blocks,
// each a ring of buildings whose facades carry ledges at every floor, so that
// near buildings hide most of the city from street level.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace occu {

struct CityOptions {
    int blocks_x = 7, blocks_z = 7;   // blocks in one grid
    int copies = 1;                   // the grid repeated copies x copies times
    float block_size = 80.0f;         // metres, street to street
    float street_width = 16.0f;
    std::uint32_t seed = 1998;
};

// Deterministic for given options. About 300k triangles with the defaults;
// copies = 4 gives about 4.8 million.
Scene generate_city(const CityOptions &options);

}  // namespace occu
