// The strategy registry (culling/registry.h): one line per family, in the
// order help lists them. A new paper's strategies are a folder beside this
// file, one line here, and their sources in src/meson.build.
#include "culling/registry.h"

#include "strategies/bartz_occlusion_unit/family.h"
#include "strategies/baselines/family.h"
#include "strategies/bittner_coherent_hierarchical_culling/family.h"
#include "strategies/leone_occluder_skins/family.h"
#include "strategies/moller_haines_occlusion_culling/family.h"
#include "strategies/poon_wang_opacity_maps/family.h"
#include "strategies/wonka_view_cells/family.h"

namespace occu {

const std::vector<StrategyFamily> &strategy_families()
{
    static const std::vector<StrategyFamily> families = {
        strategies::no_culling_family(),        // none
        strategies::frustum_culling_family(),   // vfc
        strategies::ideal_family(),             // ideal: the oracle's visible leaves, the floor
        strategies::occlusion_unit_family(),    // ou: Bartz, Meissner and Huettner 1998
        strategies::coherent_hierarchical_culling_family(),  // chc: Bittner et al. 2004, Mattausch et al. 2008
        strategies::hp_occlusion_test_family(), // hp: Moeller and Haines, the HP occlusion test
        strategies::hierarchical_z_buffer_family(),       // hzb: Moeller and Haines (Greene)
        strategies::hierarchical_occlusion_map_family(),  // hom: Moeller and Haines (Zhang)
        strategies::shadow_frustum_family(),    // shadow: Moeller and Haines (Hudson et al.)
        strategies::supporting_plane_family(),  // planes: Moeller and Haines (Coorg and Teller)
        strategies::opacity_map_family(),       // om: Poon and Wang
        strategies::occluder_skins_family(),    // skins: Leone et al.
        strategies::view_cell_family(),         // pvs: Wonka, Wimmer and Schmalstieg
    };
    return families;
}

}  // namespace occu
