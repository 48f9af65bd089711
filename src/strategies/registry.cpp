// SPDX-License-Identifier: MIT
// The strategy registry (culling/registry.h): one line per family, in the
// order help lists them. A new paper's strategies are a folder beside this
// file, one line here, and their sources in src/meson.build.
#include "culling/registry.h"

#include "strategies/bartz_occlusion_unit/family.h"
#include "strategies/baselines/family.h"
#include "strategies/bittner_coherent_hierarchical_culling/family.h"
#include "strategies/coorg_teller_supporting_planes/family.h"
#include "strategies/greene_hierarchical_z_buffer/family.h"
#include "strategies/hudson_shadow_frusta/family.h"
#include "strategies/leone_occluder_skins/family.h"
#include "strategies/poon_wang_opacity_maps/family.h"
#include "strategies/scott_hp_occlusion_test/family.h"
#include "strategies/teller_sequin_cell_portal_visibility/family.h"
#include "strategies/wonka_view_cells/family.h"
#include "strategies/zhang_hierarchical_occlusion_maps/family.h"

namespace occu {

const std::vector<StrategyFamily> &strategy_families()
{
    static const std::vector<StrategyFamily> families = with_occluder_sources({
        strategies::no_culling_family(),        // none
        strategies::frustum_culling_family(),   // vfc
        strategies::ideal_family(),             // ideal: the oracle's visible leaves, the floor
        strategies::occlusion_unit_family(),    // ou: Bartz, Meissner and Huettner 1998
        strategies::coherent_hierarchical_culling_family(),  // chc: Bittner et al. 2004, Mattausch et al. 2008
        strategies::hp_occlusion_test_family(), // hp: Scott, Olsen and Gannett 1998, the HP occlusion test
        strategies::hierarchical_z_buffer_family(),       // hzb: Greene, Kass and Miller 1993
        strategies::hierarchical_occlusion_map_family(),  // hom: Zhang et al. 1997
        strategies::shadow_frustum_family(),    // shadow: Hudson et al. 1997
        strategies::supporting_plane_family(),  // planes: Coorg and Teller 1997
        strategies::opacity_map_family(),       // om: Poon and Wang
        strategies::occluder_skins_family(),    // skins: Leone et al.
        strategies::view_cell_family(),         // pvs: Wonka, Wimmer and Schmalstieg 2000
        strategies::bsp_pvs_family(),           // bsp-pvs: Quake III's PVS, Teller and Sequin 1991
    });
    return families;
}

}  // namespace occu
