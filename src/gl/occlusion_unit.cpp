// SPDX-License-Identifier: MIT
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

bool OcclusionUnit::async_available()
{
    return has_extension("GL_MESAX_occlusion_unit_async");
}

bool OcclusionUnit::conservative_available()
{
    return has_extension("GL_MESAX_occlusion_unit_conservative");
}

OcclusionUnit::OcclusionUnit() : OcclusionUnit(true) {}

GLenum OcclusionUnit::render_mode(OcclusionMode mode) const
{
    switch (mode) {
    case OcclusionMode::verbose:
        return GL_VERBOSE_OCCLUSION_MESAX;
    case OcclusionMode::conservative:
        return conservative_ ? GL_CONSERVATIVE_OCCLUSION_MESAX : GL_BRIEF_OCCLUSION_MESAX;
    case OcclusionMode::brief:
        break;
    }
    return GL_BRIEF_OCCLUSION_MESAX;
}

OcclusionUnit::OcclusionUnit(bool allow_native_async)
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
    conservative_ = conservative_available();
    // The asynchronous entry points only where the context advertises them:
    // OSMesaGetProcAddress answers for names a driver does not implement
    // too (glapi's dispatch stubs), so a non-null pointer proves nothing.
    if (!allow_native_async || !async_available())
        return;
    GenPasses_ = reinterpret_cast<PFNGLGENOCCLUSIONPASSESMESAXPROC>(get_proc_address("glGenOcclusionPassesMESAX"));
    DeletePasses_ =
        reinterpret_cast<PFNGLDELETEOCCLUSIONPASSESMESAXPROC>(get_proc_address("glDeleteOcclusionPassesMESAX"));
    BeginPass_ = reinterpret_cast<PFNGLBEGINOCCLUSIONPASSMESAXPROC>(get_proc_address("glBeginOcclusionPassMESAX"));
    EndPass_ = reinterpret_cast<PFNGLENDOCCLUSIONPASSMESAXPROC>(get_proc_address("glEndOcclusionPassMESAX"));
    GetPassiv_ = reinterpret_cast<PFNGLGETOCCLUSIONPASSIVMESAXPROC>(get_proc_address("glGetOcclusionPassivMESAX"));
    BeginConditionalTile_ = reinterpret_cast<PFNGLBEGINCONDITIONALRENDEROCCLUSIONTILEMESAXPROC>(
        get_proc_address("glBeginConditionalRenderOcclusionTileMESAX"));
    EndConditionalTile_ = reinterpret_cast<PFNGLENDCONDITIONALRENDEROCCLUSIONTILEMESAXPROC>(
        get_proc_address("glEndConditionalRenderOcclusionTileMESAX"));
    if (!GenPasses_ || !DeletePasses_ || !BeginPass_ || !EndPass_ || !GetPassiv_ || !BeginConditionalTile_ ||
        !EndConditionalTile_)
        throw std::runtime_error("GL_MESAX_occlusion_unit_async is advertised but its entry points are missing");
}

void OcclusionUnit::validate(std::size_t tiles, std::size_t list_sizes) const
{
    if (tiles > std::size_t(max_tiles_))
        throw std::invalid_argument(std::to_string(tiles) + " occlusion tiles, the unit has " + std::to_string(max_tiles_));
    const std::size_t records = std::max<std::size_t>(1, tiles);
    if (list_sizes > 1 && list_sizes != records)
        throw std::invalid_argument("verbose list sizes for " + std::to_string(list_sizes) + " tiles, the pass has " +
                                    std::to_string(records));
}

RecordBuffers::RecordBuffers(OcclusionMode mode, std::size_t tiles, const std::vector<std::size_t> &list_pixels)
    : mode_(mode), tiles_(std::max<std::size_t>(1, tiles))
{
    // One allocation for the pass: tile i's buffer is sizes[i] words of it
    // at its own offset (spec, section 5.X), not an allocation per tile.
    offsets_.assign(tiles_ + 1, 0);
    for (std::size_t i = 0; i < tiles_; ++i) {
        const std::size_t pixels = list_pixels.empty() ? 0 : list_pixels[list_pixels.size() == 1 ? 0 : i];
        // Room for the pairs and the terminator of an overflowed list.
        offsets_[i + 1] = offsets_[i] + record_words + (mode == OcclusionMode::verbose ? 2 * pixels + 1 : 0);
    }
    words_.reset(new GLuint[offsets_[tiles_]]);
}

void RecordBuffers::bind(const OcclusionUnit &unit) const
{
    std::vector<GLuint *> buffers(tiles_);
    std::vector<GLsizei> sizes(tiles_);
    for (std::size_t i = 0; i < tiles_; ++i) {
        buffers[i] = words_.get() + offsets_[i];
        sizes[i] = GLsizei(offsets_[i + 1] - offsets_[i]);
    }
    unit.OcclusionBuffers_(GLsizei(tiles_), sizes.data(), buffers.data());
}

void RecordBuffers::parse(std::vector<OcclusionRecord> &records) const
{
    records.resize(tiles_);
    for (std::size_t i = 0; i < tiles_; ++i) {
        const GLuint *w = words_.get() + offsets_[i];
        OcclusionRecord &r = records[i];
        if (mode_ == OcclusionMode::conservative) {
            // Word 0 only (a brief record where the context lacks the mode).
            r = OcclusionRecord{};
            r.nohc = w[0] != 0;
            r.x_min = r.y_min = r.z_min = 0xFFFFFFFFu;
            continue;
        }
        r.nohc = w[0];
        r.phc = w[1];
        r.x_min = w[2];
        r.x_max = w[3];
        r.y_min = w[4];
        r.y_max = w[5];
        r.z_min = w[6];
        r.z_max = w[7];
        r.pixels.clear();
        r.overflowed = false;
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
}

namespace {
std::vector<GLint> tile_rects(const std::vector<PixelRect> &tiles)
{
    std::vector<GLint> rects;
    for (const PixelRect &t : tiles)
        rects.insert(rects.end(), {t.x0, t.y0, t.width(), t.height()});
    return rects;
}
}  // namespace

OcclusionPass::OcclusionPass(const OcclusionUnit &unit, OcclusionMode mode, const std::vector<PixelRect> &tiles,
                             const std::vector<std::size_t> &list_pixels)
    : unit_(unit)
{
    unit.validate(tiles.size(), list_pixels.size());
    buffers_ = RecordBuffers(mode, tiles.size(), list_pixels);
    buffers_.bind(unit);
    const std::vector<GLint> rects = tile_rects(tiles);
    unit.Scissors_(GLsizei(tiles.size()), rects.empty() ? nullptr : rects.data());
    glRenderMode(unit.render_mode(mode));
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
    buffers_.parse(records_);
    return records_;
}

AsyncOcclusionPass::AsyncOcclusionPass(const OcclusionUnit &unit) : unit_(unit)
{
    if (unit.native_async())
        unit.GenPasses_(1, &name_);
}

AsyncOcclusionPass::~AsyncOcclusionPass()
{
    if (state_ == State::open)
        end();
    // Deleting a pass whose records were never read drops them; the
    // buffers captured at Begin are written only by a Get, so freeing them
    // with the object is safe.
    if (name_)
        unit_.DeletePasses_(1, &name_);
}

void AsyncOcclusionPass::begin(OcclusionMode mode, const std::vector<PixelRect> &tiles,
                               const std::vector<std::size_t> &list_pixels)
{
    if (state_ == State::open)
        throw std::logic_error("an occlusion pass begun twice without end()");
    unit_.validate(tiles.size(), list_pixels.size());
    buffers_ = RecordBuffers(mode, tiles.size(), list_pixels);
    buffers_.bind(unit_);
    const std::vector<GLint> rects = tile_rects(tiles);
    unit_.Scissors_(GLsizei(tiles.size()), rects.empty() ? nullptr : rects.data());
    const GLenum gl_mode = unit_.render_mode(mode);
    if (name_)
        unit_.BeginPass_(gl_mode, name_);   // tiles and buffers captured here
    else
        glRenderMode(gl_mode);
    state_ = State::open;
}

void AsyncOcclusionPass::end()
{
    if (state_ != State::open)
        throw std::logic_error("end() of an occlusion pass that is not open");
    if (name_) {
        unit_.EndPass_();   // back to GL_RENDER, no wait, nothing written
        unit_.Scissors_(0, nullptr);
        state_ = State::ended;
        return;
    }
    glRenderMode(GL_RENDER);   // the emulation: waits and writes the records now
    unit_.Scissors_(0, nullptr);
    buffers_.parse(records_);
    state_ = State::read;
}

bool AsyncOcclusionPass::available()
{
    if (state_ == State::read)
        return true;
    if (state_ != State::ended)
        return false;
    GLint ready = GL_FALSE;
    unit_.GetPassiv_(name_, GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, &ready);
    return ready == GL_TRUE;
}

const std::vector<OcclusionRecord> &AsyncOcclusionPass::records()
{
    if (state_ == State::ended) {
        GLint overflowed = 0;
        unit_.GetPassiv_(name_, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);   // waits, writes the buffers
        buffers_.parse(records_);
        state_ = State::read;
    }
    if (state_ != State::read)
        throw std::logic_error("records() of an occlusion pass that was not ended");
    return records_;
}

ConditionalTileRender::ConditionalTileRender(AsyncOcclusionPass &pass, std::size_t tile, std::uint32_t min_nohc,
                                             float min_ratio, bool wait)
    : unit_(pass.unit_), native_(pass.native())
{
    if (native_) {
        unit_.BeginConditionalTile_(pass.name_, GLuint(tile), min_nohc, min_ratio, wait ? GL_QUERY_WAIT : GL_QUERY_NO_WAIT);
        return;
    }
    // The emulated pass's records are read at its end, so they are always
    // available and NO_WAIT decides as WAIT does.
    const std::vector<OcclusionRecord> &records = pass.records();
    if (tile >= records.size())
        throw std::invalid_argument("conditional rendering on tile " + std::to_string(tile) + " of a pass of " +
                                    std::to_string(records.size()));
    draws_ = passes(records[tile], min_nohc, min_ratio);
}

ConditionalTileRender::~ConditionalTileRender()
{
    if (native_)
        unit_.EndConditionalTile_();
}

}  // namespace occu::gl
