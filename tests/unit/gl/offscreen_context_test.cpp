// SPDX-License-Identifier: MIT
// Runs once per driver (meson sets GALLIUM_DRIVER); checks that the context
// really is that driver on the patched Mesa, and occu's conventions hold.
#include "gl/offscreen_context.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <link.h>
#include <string>
#include <stdexcept>

#include "gl/extensions.h"
#include "gl/gl_headers.h"

using namespace occu::gl;

namespace {
std::string requested_driver()
{
    const char *d = std::getenv("GALLIUM_DRIVER");
    return d ? d : "";
}
}  // namespace

namespace {

// The directory of the loaded shared object whose file name starts `name`.
std::string loaded_from(const std::string &name)
{
    struct Search {
        std::string name, dir;
    } search{name, ""};
    dl_iterate_phdr(
        [](dl_phdr_info *info, std::size_t, void *data) {
            auto *s = static_cast<Search *>(data);
            const std::string path = info->dlpi_name ? info->dlpi_name : "";
            const std::size_t slash = path.rfind('/');
            if (slash != std::string::npos && path.compare(slash + 1, s->name.size(), s->name) == 0) {
                s->dir = path.substr(0, slash);
                return 1;
            }
            return 0;
        },
        &search);
    return search.dir;
}

}  // namespace

// libOSMesa's own libglapi comes from the patched Mesa too, not from the
// system (whose unpatched one its NEEDED would find without the link to it).
TEST(OffscreenContext, LoadsThePatchedMesasGlapiBesideItsOSMesa)
{
    OffscreenContext ctx(4, 4);
    const std::string osmesa = loaded_from("libOSMesa.so"), glapi = loaded_from("libglapi.so");
    ASSERT_FALSE(osmesa.empty());
    ASSERT_FALSE(glapi.empty());
    EXPECT_EQ(glapi, osmesa);
}

TEST(ParseDriver, KnownNamesAndAClearError)
{
    EXPECT_EQ(parse_driver("softpipe"), Driver::softpipe);
    EXPECT_EQ(parse_driver("llvmpipe"), Driver::llvmpipe);
    try {
        parse_driver("swrast");
        FAIL() << "no exception";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("'swrast'"), std::string::npos) << e.what();
    }
}

TEST(OffscreenContext, RejectsBadSizesWithoutMakingAContext)
{
    EXPECT_THROW(OffscreenContext(0, 10), std::invalid_argument);
    EXPECT_THROW(OffscreenContext(10, -1), std::invalid_argument);
}

TEST(OffscreenContext, RendersOnTheRequestedDriver)
{
    const std::string wanted = requested_driver();
    if (wanted.empty())
        GTEST_SKIP() << "GALLIUM_DRIVER is not set";
    select_driver(parse_driver(wanted));
    OffscreenContext ctx(32, 16);
    EXPECT_NE(ctx.renderer().find(wanted), std::string::npos) << ctx.renderer();
    // Switching drivers inside one process is impossible in Mesa; say so.
    const Driver other = wanted == "softpipe" ? Driver::llvmpipe : Driver::softpipe;
    EXPECT_THROW(select_driver(other), std::logic_error);
}

TEST(OffscreenContext, PixelsAreBottomRowFirst)
{
    OffscreenContext ctx(8, 4);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 8, 1);  // the bottom row in GL's window coordinates
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glFinish();
    const std::uint8_t *p = ctx.pixels();
    EXPECT_EQ(p[0], 255);                // row 0 of the buffer: bottom, white
    EXPECT_EQ(p[8 * 4 * 3], 0);          // row 3: top, black
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST(OffscreenContext, ReportsACompatibilityContextWithExtensions)
{
    OffscreenContext ctx(4, 4);
    const auto exts = current_extensions();
    EXPECT_GT(exts.size(), 50u);
    EXPECT_TRUE(has_extension("GL_ARB_occlusion_query"));
    GLint mask = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    glGetError();  // GL < 3.2 has no profile mask; then it stays 0
    EXPECT_EQ(mask & GL_CONTEXT_CORE_PROFILE_BIT, 0);
}
