/* SPDX-License-Identifier: MIT */
/*
 * A small piglit-compatible test harness for occu's own tests on OSMesa.
 *
 * It mimics the part of piglit's piglit-util-gl.h and piglit-framework-gl.h
 * the tests use, with the same names and signatures, so that the same test
 * sources build on it (tools/test: a fresh machine cannot fetch piglit) and
 * inside a piglit source tree on piglit's own framework
 * (tools/check-in-piglit.sh). A test is piglit's shape:
 *
 *   PIGLIT_GL_TEST_CONFIG_BEGIN
 *           config.supports_gl_compat_version = 10;
 *           config.window_width = 32;
 *           ...
 *   PIGLIT_GL_TEST_CONFIG_END
 *   enum piglit_result piglit_display(void) { ... }
 *   void piglit_init(int argc, char **argv) { ... }
 *
 * Here the window is an OSMesa buffer of window_width x window_height (RGBA8,
 * with 24-bit depth and 8-bit stencil when the visual asks for them, an
 * accumulation buffer for PIGLIT_GL_VISUAL_ACCUM); piglit_winsys_fbo is 0.
 * Under piglit's runner with -fbo, piglit renders into an FBO of the same
 * size and formats instead, and piglit_winsys_fbo names it: a test that
 * binds the window's framebuffer back binds piglit_winsys_fbo.
 *
 * Each program prints the result lines piglit's runner parses
 * ("PIGLIT: {...}") and exits with the code piglit reads: 0 for pass and
 * skip, 1 for fail; with OCCU_SKIP_EXIT_CODE=77 in the environment (meson
 * test sets it) a skip exits 77, meson's skip. -auto and -fbo are taken out
 * of argv as piglit does; every other argument reaches piglit_init.
 *
 * piglit_osmesa_init is occu's alone: the few tests that compare drivers in
 * child processes (each child makes its own context) or test OSMesa itself
 * have a main of their own and call it.
 */
#ifndef OCCU_PIGLIT_UTIL_GL_H
#define OCCU_PIGLIT_UTIL_GL_H

#include <stdbool.h>

/* Tests call GL functions by name, as piglit's dispatch lets them; libOSMesa
 * exports the core functions and most extensions'. (tests/meson.build
 * defines it on the command line too, for tests that include <GL/glext.h>
 * first, through <GL/osmesa.h>.) */
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#include "GL/mesax_occlusion_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

enum piglit_result {
    PIGLIT_PASS,
    PIGLIT_FAIL,
    PIGLIT_SKIP,
};

/* piglit's visual bits; RGBA, DEPTH, STENCIL and ACCUM are honoured. */
enum piglit_gl_visual {
    PIGLIT_GL_VISUAL_RGB = 0,
    PIGLIT_GL_VISUAL_RGBA = 1 << 0,
    PIGLIT_GL_VISUAL_DOUBLE = 1 << 1,
    PIGLIT_GL_VISUAL_ACCUM = 1 << 2,
    PIGLIT_GL_VISUAL_DEPTH = 1 << 3,
    PIGLIT_GL_VISUAL_STENCIL = 1 << 4,
};

/* piglit's KHR_no_error classification; recorded, not acted on here. */
enum piglit_khr_no_error_support {
    PIGLIT_UNKNOWN_ERROR_STATUS,
    PIGLIT_NO_ERRORS,
    PIGLIT_HAS_ERRORS,
};

struct piglit_gl_test_config {
    /* GL versions times ten, as piglit's: a compatibility context when
     * supports_gl_compat_version is set, else a core one of
     * supports_gl_core_version. */
    int supports_gl_compat_version;
    int supports_gl_core_version;
    int window_width;
    int window_height;
    int window_visual;
    enum piglit_khr_no_error_support khr_no_error_support;
    void (*init)(int argc, char *argv[]);
    enum piglit_result (*display)(void);
};

void piglit_gl_test_config_init(struct piglit_gl_test_config *config);
void piglit_gl_process_args(int *argc, char *argv[], struct piglit_gl_test_config *config);
/* Makes the context, calls init, then display, and reports display's
 * result; never returns. */
void piglit_gl_test_run(int argc, char *argv[], const struct piglit_gl_test_config *config)
    __attribute__((noreturn));

#define PIGLIT_GL_TEST_CONFIG_BEGIN                                  \
    void piglit_init(int argc, char *argv[]);                        \
    enum piglit_result piglit_display(void);                         \
    int main(int argc, char *argv[])                                 \
    {                                                                \
        struct piglit_gl_test_config config;                        \
        piglit_gl_test_config_init(&config);                        \
        config.init = piglit_init;                                  \
        config.display = piglit_display;                            \
        {

#define PIGLIT_GL_TEST_CONFIG_END                                    \
        }                                                            \
        piglit_gl_process_args(&argc, argv, &config);               \
        piglit_gl_test_run(argc, argv, &config);                    \
    }

/* The GL functions the tests call that libOSMesa does not export (the
 * GL_MESAX_occlusion_unit extensions' and three EXT ones): their names are
 * pointers resolved (OSMesaGetProcAddress) once the context exists, NULL
 * when the GL lacks one; piglit's dispatch makes every GL function name such
 * a pointer (tools/check-in-piglit.sh adds the extensions' to its
 * registry). */
#define PIGLIT_OSMESA_UNEXPORTED(X)                                                   \
    X(PFNGLSCISSORSMESAXPROC, glScissorsMESAX)                                      \
    X(PFNGLOCCLUSIONBUFFERSMESAXPROC, glOcclusionBuffersMESAX)                      \
    X(PFNGLGENOCCLUSIONPASSESMESAXPROC, glGenOcclusionPassesMESAX)                  \
    X(PFNGLDELETEOCCLUSIONPASSESMESAXPROC, glDeleteOcclusionPassesMESAX)            \
    X(PFNGLISOCCLUSIONPASSMESAXPROC, glIsOcclusionPassMESAX)                        \
    X(PFNGLBEGINOCCLUSIONPASSMESAXPROC, glBeginOcclusionPassMESAX)                  \
    X(PFNGLENDOCCLUSIONPASSMESAXPROC, glEndOcclusionPassMESAX)                      \
    X(PFNGLGETOCCLUSIONPASSIVMESAXPROC, glGetOcclusionPassivMESAX)                  \
    X(PFNGLBEGINCONDITIONALRENDEROCCLUSIONTILEMESAXPROC, glBeginConditionalRenderOcclusionTileMESAX) \
    X(PFNGLENDCONDITIONALRENDEROCCLUSIONTILEMESAXPROC, glEndConditionalRenderOcclusionTileMESAX) \
    X(PFNGLDEPTHBOUNDSEXTPROC, glDepthBoundsEXT)                                    \
    X(PFNGLGETPOINTERINDEXEDVEXTPROC, glGetPointerIndexedvEXT)                      \
    X(PFNGLGETPOINTERI_VEXTPROC, glGetPointeri_vEXT)
#define PIGLIT_DECLARE_DISPATCH(type, name) extern type piglit_dispatch_##name;
PIGLIT_OSMESA_UNEXPORTED(PIGLIT_DECLARE_DISPATCH)
#undef PIGLIT_DECLARE_DISPATCH
#define glScissorsMESAX piglit_dispatch_glScissorsMESAX
#define glOcclusionBuffersMESAX piglit_dispatch_glOcclusionBuffersMESAX
#define glGenOcclusionPassesMESAX piglit_dispatch_glGenOcclusionPassesMESAX
#define glDeleteOcclusionPassesMESAX piglit_dispatch_glDeleteOcclusionPassesMESAX
#define glIsOcclusionPassMESAX piglit_dispatch_glIsOcclusionPassMESAX
#define glBeginOcclusionPassMESAX piglit_dispatch_glBeginOcclusionPassMESAX
#define glEndOcclusionPassMESAX piglit_dispatch_glEndOcclusionPassMESAX
#define glGetOcclusionPassivMESAX piglit_dispatch_glGetOcclusionPassivMESAX
#define glBeginConditionalRenderOcclusionTileMESAX piglit_dispatch_glBeginConditionalRenderOcclusionTileMESAX
#define glEndConditionalRenderOcclusionTileMESAX piglit_dispatch_glEndConditionalRenderOcclusionTileMESAX
#define glDepthBoundsEXT piglit_dispatch_glDepthBoundsEXT
#define glGetPointerIndexedvEXT piglit_dispatch_glGetPointerIndexedvEXT
#define glGetPointeri_vEXT piglit_dispatch_glGetPointeri_vEXT

/* Makes a compatibility-profile OSMesa context of width x height (RGBA8,
 * depth 24, stencil 8) and makes it current, for tests with a main of their
 * own. Fails the test (never returns) when that is impossible or argv holds
 * an argument other than -auto and -fbo. occu's alone. */
void piglit_osmesa_init(int argc, char **argv, int width, int height);

extern int piglit_width, piglit_height;
/* The window's framebuffer: 0 here, piglit's FBO under piglit with -fbo. */
extern unsigned int piglit_winsys_fbo;

/* Prints the final result line and exits. A PASS is reported as FAIL when a
 * subtest failed, and as SKIP when subtests were reported and every one of
 * them skipped, as piglit's runner reads such a test. */
void piglit_report_result(enum piglit_result result) __attribute__((noreturn));
/* Prints one subtest's result line. */
void piglit_report_subtest_result(enum piglit_result result, const char *format, ...)
    __attribute__((format(printf, 2, 3)));
/* Folds `subtest` into *all: FAIL wins over PASS, PASS over SKIP. */
void piglit_merge_result(enum piglit_result *all, enum piglit_result subtest);

/* Skips the test (never returns) unless the context advertises `name`. */
void piglit_require_extension(const char *name);
bool piglit_is_extension_supported(const char *name);

/* A program of a GLSL vertex and fragment shader, either NULL for the
 * fixed-function stage. As piglit's, it fails the test (never returns) when
 * a shader does not compile or the program does not link (the log is
 * printed), or GL 2.0's entry points are missing. */
GLuint piglit_build_simple_program(const char *vertex_source, const char *fragment_source);

/* True when glGetError() is `expected`; prints what it got otherwise. */
bool piglit_check_gl_error(GLenum expected);

#ifdef __cplusplus
}
#endif

#endif
