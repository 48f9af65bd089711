/* SPDX-License-Identifier: MIT */
/*
 * A small piglit-compatible test harness for occu's own tests on OSMesa.
 *
 * Each test is one small program about one behaviour. It prints the result
 * lines piglit's runner parses ("PIGLIT: {...}") and exits with the code
 * piglit reads: 0 for pass and skip, 1 for fail; with OCCU_SKIP_EXIT_CODE=77
 * in the environment (meson test sets it) a skip exits 77, meson's skip.
 *
 * Conventions: window coordinates as in OpenGL (origin bottom-left); the
 * default framebuffer is RGBA8 with 24-bit depth and 8-bit stencil, made by
 * piglit_osmesa_init. The flags -auto and -fbo that piglit's runner passes
 * are accepted: every occu test is automatic and off-screen.
 */
#ifndef OCCU_PIGLIT_UTIL_H
#define OCCU_PIGLIT_UTIL_H

#include <stdbool.h>

#include <GL/gl.h>
#include <GL/glext.h>

#ifdef __cplusplus
extern "C" {
#endif

enum piglit_result {
    PIGLIT_PASS,
    PIGLIT_FAIL,
    PIGLIT_SKIP,
};

/* Makes a compatibility-profile OSMesa context of width x height and makes it
 * current. Fails the test (never returns) when that is impossible. */
void piglit_osmesa_init(int argc, char **argv, int width, int height);

extern int piglit_width, piglit_height;

/* Prints the final result line and exits. A PASS is reported as FAIL when a
 * subtest failed, and as SKIP when subtests were reported and every one of
 * them skipped, as piglit's runner reads such a test. */
void piglit_report_result(enum piglit_result result) __attribute__((noreturn));
/* Prints one subtest's result line. */
void piglit_report_subtest_result(enum piglit_result result, const char *format, ...)
    __attribute__((format(printf, 2, 3)));
/* Combines results: FAIL wins over PASS, PASS over SKIP. */
enum piglit_result piglit_merge_result(enum piglit_result a, enum piglit_result b);

/* Skips the test (never returns) unless the context advertises `name`. */
void piglit_require_extension(const char *name);
bool piglit_is_extension_supported(const char *name);

/* Entry point of the current context's GL, or NULL. */
void (*piglit_get_proc_address(const char *name))(void);

/* A program of one GLSL fragment shader (compatibility profile); 0 when it
 * does not compile or link, or GL 2.0 is missing (the log is printed). */
GLuint piglit_build_fragment_program(const char *source);

/* A program of a GLSL vertex and fragment shader, either NULL for the
 * fixed-function stage; 0 as for piglit_build_fragment_program. */
GLuint piglit_build_simple_program(const char *vertex_source, const char *fragment_source);

/* True when glGetError() is `expected`; prints what it got otherwise. */
bool piglit_check_gl_error(GLenum expected);

/* Probes: true when every pixel of the rectangle matches `expected` within
 * `tolerance` per channel (0..255 units); prints the first mismatch. */
bool piglit_probe_rect_rgba_ub(int x, int y, int w, int h, const unsigned char expected[4], int tolerance);

#ifdef __cplusplus
}
#endif

#endif
