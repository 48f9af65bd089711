#include "gl/occlusion_unit.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "gl/extensions.h"

namespace occu::gl {

namespace {
constexpr std::size_t record_words = 8;        // NOHC, PHC, x, y and z extents
constexpr GLuint list_terminator = 0xFFFFFFFFu;  // ends an overflowed verbose list
}  // namespace

bool OcclusionUnit::available()
{
    return has_extension("GL_MESAX_occlusion_unit");
}

OcclusionUnit::OcclusionUnit()
{
    if (!available())
        throw std::runtime_error("this GL context lacks GL_MESAX_occlusion_unit (run on occu's patched Mesa)");
    Scissors_ = reinterpret_cast<PFNGLSCISSORSMESAXPROC>(get_proc_address("glScissorsMESAX"));
    OcclusionBuffers_ = reinterpret_cast<PFNGLOCCLUSIONBUFFERSMESAXPROC>(get_proc_address("glOcclusionBuffersMESAX"));
    if (!Scissors_ || !OcclusionBuffers_)
        throw std::runtime_error("GL_MESAX_occlusion_unit is advertised but its entry points are missing");
    GLint max = 0;
    glGetIntegerv(GL_MAX_OCCLUSION_TILES_MESAX, &max);
    max_tiles_ = max;
}

OcclusionPass::OcclusionPass(const OcclusionUnit &unit, OcclusionMode mode, const std::vector<PixelRect> &tiles,
                             const std::vector<std::size_t> &list_pixels)
    : unit_(unit), mode_(mode), tiles_(std::max<std::size_t>(1, tiles.size()))
{
    if (tiles.size() > std::size_t(unit.max_tiles_))
        throw std::invalid_argument(std::to_string(tiles.size()) + " occlusion tiles, the unit has " +
                                    std::to_string(unit.max_tiles_));
    if (list_pixels.size() > 1 && list_pixels.size() != tiles_)
        throw std::invalid_argument("verbose list sizes for " + std::to_string(list_pixels.size()) + " tiles, the pass has " +
                                    std::to_string(tiles_));
    // One allocation for the pass: tile i's buffer is sizes[i] words of it
    // at its own offset (spec, section 5.X), not an allocation per tile.
    offsets_.assign(tiles_ + 1, 0);
    for (std::size_t i = 0; i < tiles_; ++i) {
        const std::size_t pixels = list_pixels.empty() ? 0 : list_pixels[list_pixels.size() == 1 ? 0 : i];
        // Room for the pairs and the terminator of an overflowed list.
        offsets_[i + 1] = offsets_[i] + record_words + (mode == OcclusionMode::verbose ? 2 * pixels + 1 : 0);
    }
    words_.reset(new GLuint[offsets_[tiles_]]);
    std::vector<GLuint *> buffers(tiles_);
    std::vector<GLsizei> sizes(tiles_);
    for (std::size_t i = 0; i < tiles_; ++i) {
        buffers[i] = words_.get() + offsets_[i];
        sizes[i] = GLsizei(offsets_[i + 1] - offsets_[i]);
    }
    std::vector<GLint> rects;
    for (const PixelRect &t : tiles)
        rects.insert(rects.end(), {t.x0, t.y0, t.width(), t.height()});
    unit.OcclusionBuffers_(GLsizei(tiles_), sizes.data(), buffers.data());
    unit.Scissors_(GLsizei(tiles.size()), rects.empty() ? nullptr : rects.data());
    glRenderMode(mode == OcclusionMode::brief ? GL_BRIEF_OCCLUSION_MESAX : GL_VERBOSE_OCCLUSION_MESAX);
}

OcclusionPass::~OcclusionPass()
{
    if (!ended_)
        end();
}

const std::vector<OcclusionRecord> &OcclusionPass::end()
{
    if (ended_)
        return records_;
    ended_ = true;
    glRenderMode(GL_RENDER);
    unit_.Scissors_(0, nullptr);
    records_.resize(tiles_);
    for (std::size_t i = 0; i < tiles_; ++i) {
        const GLuint *w = words_.get() + offsets_[i];
        OcclusionRecord &r = records_[i];
        r.nohc = w[0];
        r.phc = w[1];
        r.x_min = w[2];
        r.x_max = w[3];
        r.y_min = w[4];
        r.y_max = w[5];
        r.z_min = w[6];
        r.z_max = w[7];
        if (mode_ != OcclusionMode::verbose)
            continue;
        // All NOHC pairs when they fit, else as many as fit before a terminator.
        const std::size_t room = (offsets_[i + 1] - offsets_[i] - record_words) / 2;
        const std::size_t listed = std::min<std::size_t>(r.nohc, room);
        r.overflowed = std::size_t(r.nohc) > room;
        r.pixels.reserve(listed);
        for (std::size_t k = 0; k < listed; ++k) {
            const GLuint x = w[record_words + 2 * k], y = w[record_words + 2 * k + 1];
            if (x == list_terminator) {
                r.overflowed = true;
                break;
            }
            r.pixels.push_back({x, y});
        }
    }
    return records_;
}

}  // namespace occu::gl
