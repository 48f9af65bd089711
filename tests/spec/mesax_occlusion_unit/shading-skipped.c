/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit and fragment shading in an occlusion pass (spec
 * issue 14). One full-window rectangle, depth test off.
 *
 * Conformance: a pass must shade whenever what the shader does changes the
 * counts or must be seen by the application.
 *   render-mode-shades               GL_RENDER runs the shader once per
 *                                    fragment (the reference: the
 *                                    invocation count can fail)
 *   alpha-test-needs-shading         the alpha test reads the shader's alpha
 *   discarding-shader-runs           discards change PHC
 *   atomic-shader-that-may-discard-runs
 *                                    a shader that increments an atomic
 *                                    counter and may discard: the counter
 *                                    ends at one increment per fragment, as
 *                                    in GL_RENDER
 *   image-store-shader-that-may-discard-runs
 *   buffer-store-shader-that-may-discard-runs
 *                                    the same for a shader that stores into
 *                                    an image or a shader storage buffer:
 *                                    the words stored in a brief pass equal
 *                                    those stored in GL_RENDER
 *   atomic-shader-runs-{brief,verbose}
 *                                    the same without the discard: the
 *                                    shader's only effect besides colour is
 *                                    its side effect, which must still
 *                                    happen (section 5.X: a shader that
 *                                    writes memory runs in a pass).
 * Performance: an optional optimisation that the spec permits and the occu
 * drivers implement, which is what makes a pass cheaper than GL_RENDER.
 *   performance-{brief,verbose}-pass-skips-plain-shader
 *                                    a shader that can neither discard nor
 *                                    write depth, with the alpha test off,
 *                                    is not run (FRAGMENT_SHADER_INVOCATIONS
 *                                    of ARB_pipeline_statistics_query is 0)
 */
#include "ou_util.h"

#define W 32
#define H 32
#ifndef GL_FRAGMENT_SHADER_INVOCATIONS_ARB
#define GL_FRAGMENT_SHADER_INVOCATIONS_ARB 0x82F4
#endif

static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;
static PFNGLUSEPROGRAMPROC UseProgram;
static GLuint query;
static bool have_statistics;

static void draw_all(void) { ou_rect(0, 0, W, H, 0.5f); }

/* Draws the rectangle in `mode` (GL_RENDER or an occlusion mode). */
static void
draw_in_mode(GLenum mode)
{
    static GLuint record[8 + 2 * W * H];
    GLuint *buffers[1] = {record};
    GLsizei size = 8 + 2 * W * H;
    OcclusionBuffersMESAX(1, &size, buffers);
    if (mode != GL_RENDER)
        glRenderMode(mode);
    draw_all();
    if (mode != GL_RENDER)
        glRenderMode(GL_RENDER);
}

/* Fragment shader invocations of the rectangle in `mode`. */
static GLuint
invocations(GLenum mode)
{
    GLuint n = 0;
    BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query);
    draw_in_mode(mode);
    EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &n);
    return n;
}

static void
check_invocations(GLuint program, GLenum mode, bool skipped, const char *name)
{
    if (!have_statistics) {
        ou_subtest_unsupported(name, "GL_ARB_pipeline_statistics_query");
        return;
    }
    UseProgram(program);
    const GLuint n = invocations(mode);
    UseProgram(0);
    const bool ok = skipped ? n == 0 : n >= W * H;
    if (!ok)
        printf("%s: %u fragment shader invocations, expected %s\n", name, n, skipped ? "0" : ">= 1024");
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
}

/* The atomic counter after drawing the rectangle in `mode` with `program`;
 * ~0u on a GL error. */
static GLuint
atomic_count(GLuint program, GLenum mode)
{
    PFNGLBUFFERSUBDATAPROC BufferSubData = glBufferSubData;
    PFNGLGETBUFFERSUBDATAPROC GetBufferSubData =
        glGetBufferSubData;
    PFNGLMEMORYBARRIERPROC MemoryBarrier = glMemoryBarrier;
    const GLuint zero = 0;
    GLuint n = 0;
    BufferSubData(GL_ATOMIC_COUNTER_BUFFER, 0, sizeof(zero), &zero);
    UseProgram(program);
    draw_in_mode(mode);
    UseProgram(0);
    MemoryBarrier(GL_ATOMIC_COUNTER_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    GetBufferSubData(GL_ATOMIC_COUNTER_BUFFER, 0, sizeof(n), &n);
    return piglit_check_gl_error(GL_NO_ERROR) ? n : ~0u;
}

static void
test_atomic_counter_shaders(void)
{
    static const char *names[] = {"atomic-shader-that-may-discard-runs", "atomic-shader-runs-brief",
                                  "atomic-shader-runs-verbose"};
    if (!piglit_is_extension_supported("GL_ARB_shader_atomic_counters") ||
        !piglit_is_extension_supported("GL_ARB_shading_language_420pack")) {
        for (int i = 0; i < 3; ++i)
            ou_subtest_unsupported(names[i], "GL_ARB_shader_atomic_counters with GL_ARB_shading_language_420pack");
        return;
    }
    static const char header[] = "#version 130\n"
                                 "#extension GL_ARB_shader_atomic_counters : require\n"
                                 "#extension GL_ARB_shading_language_420pack : require\n"
                                 "layout(binding = 0, offset = 0) uniform atomic_uint fragments;\n";
    /* gl_FragCoord.x is never negative: the discard can happen, never does. */
    char may_discard[512], plain[512];
    snprintf(may_discard, sizeof(may_discard),
             "%svoid main() { atomicCounterIncrement(fragments); if (gl_FragCoord.x < 0.0) discard;"
             " gl_FragColor = vec4(1.0); }\n",
             header);
    snprintf(plain, sizeof(plain), "%svoid main() { atomicCounterIncrement(fragments); gl_FragColor = vec4(1.0); }\n",
             header);
    const GLuint programs[2] = {piglit_build_simple_program(NULL, may_discard), piglit_build_simple_program(NULL, plain)};
    if (!programs[0] || !programs[1]) {
        for (int i = 0; i < 3; ++i)
            subtest(false, names[i]);
        return;
    }

    PFNGLGENBUFFERSPROC GenBuffers = glGenBuffers;
    PFNGLBINDBUFFERPROC BindBuffer = glBindBuffer;
    PFNGLBUFFERDATAPROC BufferData = glBufferData;
    PFNGLBINDBUFFERBASEPROC BindBufferBase = glBindBufferBase;
    GLuint buffer;
    GenBuffers(1, &buffer);
    BindBuffer(GL_ATOMIC_COUNTER_BUFFER, buffer);
    BufferData(GL_ATOMIC_COUNTER_BUFFER, sizeof(GLuint), NULL, GL_DYNAMIC_DRAW);
    BindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, buffer);

    /* GL_RENDER's count is the reference: one increment per fragment. */
    const GLuint render = atomic_count(programs[1], GL_RENDER);
    if (render != W * H)
        printf("GL_RENDER: the atomic counter is %u, expected %d\n", render, W * H);

    GLuint n = atomic_count(programs[0], GL_BRIEF_OCCLUSION_MESAX);
    if (n != render)
        printf("%s: the atomic counter is %u, GL_RENDER's %u\n", names[0], n, render);
    subtest(render == W * H && n == render, names[0]);

    const GLenum modes[2] = {GL_BRIEF_OCCLUSION_MESAX, GL_VERBOSE_OCCLUSION_MESAX};
    for (int m = 0; m < 2; ++m) {
        n = atomic_count(programs[1], modes[m]);
        if (n != render)
            printf("%s: the atomic counter is %u, GL_RENDER's %u\n", names[1 + m], n, render);
        subtest(render == W * H && n == render, names[1 + m]);
    }
}

/* A shader that may discard and stores 1 for its fragment into an image or
 * a buffer: the stored words after a brief pass equal those after
 * GL_RENDER, one per fragment. */
static const char *store_header = "#version 130\n"
                                  "#extension GL_ARB_shading_language_420pack : require\n";

static bool
stores_match_render(const char *name, GLuint program, void (*reset)(void), void (*read)(GLuint *))
{
    static GLuint render[W * H], pass[W * H];
    reset();
    UseProgram(program);
    draw_in_mode(GL_RENDER);
    UseProgram(0);
    read(render);
    reset();
    UseProgram(program);
    draw_in_mode(GL_BRIEF_OCCLUSION_MESAX);
    UseProgram(0);
    read(pass);
    GLuint stored = 0;
    for (int i = 0; i < W * H; ++i)
        stored += render[i] != 0;
    const bool ok = piglit_check_gl_error(GL_NO_ERROR) && stored > 0 && !memcmp(render, pass, sizeof(pass));
    if (!ok) {
        GLuint in_pass = 0;
        for (int i = 0; i < W * H; ++i)
            in_pass += pass[i] != 0;
        printf("%s: %u words stored in GL_RENDER, %u in the pass\n", name, stored, in_pass);
    }
    return ok;
}

static GLuint image_texture, storage_buffer;

static void
reset_image(void)
{
    static const GLuint zero[W * H];
    glBindTexture(GL_TEXTURE_2D, image_texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, W, H, GL_RED_INTEGER, GL_UNSIGNED_INT, zero);
}

static void
read_image(GLuint *words)
{
    PFNGLMEMORYBARRIERPROC MemoryBarrier = glMemoryBarrier;
    MemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glBindTexture(GL_TEXTURE_2D, image_texture);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, words);
}

static void
reset_buffer(void)
{
    static const GLuint zero[W * H];
    PFNGLBUFFERSUBDATAPROC BufferSubData = glBufferSubData;
    BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zero), zero);
}

static void
read_buffer(GLuint *words)
{
    PFNGLMEMORYBARRIERPROC MemoryBarrier = glMemoryBarrier;
    PFNGLGETBUFFERSUBDATAPROC GetBufferSubData =
        glGetBufferSubData;
    MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, W * H * sizeof(GLuint), words);
}

static void
test_image_store(void)
{
    const char *name = "image-store-shader-that-may-discard-runs";
    if (!piglit_is_extension_supported("GL_ARB_shader_image_load_store") ||
        !piglit_is_extension_supported("GL_ARB_shading_language_420pack")) {
        ou_subtest_unsupported(name, "GL_ARB_shader_image_load_store with GL_ARB_shading_language_420pack");
        return;
    }
    char source[512];
    snprintf(source, sizeof(source),
             "%s#extension GL_ARB_shader_image_load_store : require\n"
             "layout(r32ui, binding = 0) uniform writeonly uimage2D stored;\n"
             "void main() { imageStore(stored, ivec2(gl_FragCoord.xy), uvec4(1u));"
             " if (gl_FragCoord.x < 0.0) discard; gl_FragColor = vec4(1.0); }\n",
             store_header);
    const GLuint program = piglit_build_simple_program(NULL, source);
    PFNGLTEXSTORAGE2DPROC TexStorage2D = glTexStorage2D;
    PFNGLBINDIMAGETEXTUREPROC BindImageTexture =
        glBindImageTexture;
    glGenTextures(1, &image_texture);
    glBindTexture(GL_TEXTURE_2D, image_texture);
    TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, W, H);
    BindImageTexture(0, image_texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    subtest(program && stores_match_render(name, program, reset_image, read_image), name);
}

static void
test_buffer_store(void)
{
    const char *name = "buffer-store-shader-that-may-discard-runs";
    if (!piglit_is_extension_supported("GL_ARB_shader_storage_buffer_object") ||
        !piglit_is_extension_supported("GL_ARB_shading_language_420pack")) {
        ou_subtest_unsupported(name, "GL_ARB_shader_storage_buffer_object with GL_ARB_shading_language_420pack");
        return;
    }
    /* The buffer's layout is the implementation's; both draws use the same. */
    char source[512];
    snprintf(source, sizeof(source),
             "%s#extension GL_ARB_shader_storage_buffer_object : require\n"
             "layout(binding = 0) buffer Stored { uint stored[]; };\n"
             "void main() { stored[int(gl_FragCoord.y) * %d + int(gl_FragCoord.x)] = 1u;"
             " if (gl_FragCoord.x < 0.0) discard; gl_FragColor = vec4(1.0); }\n",
             store_header, W);
    const GLuint program = piglit_build_simple_program(NULL, source);
    PFNGLGENBUFFERSPROC GenBuffers = glGenBuffers;
    PFNGLBINDBUFFERPROC BindBuffer = glBindBuffer;
    PFNGLBUFFERDATAPROC BufferData = glBufferData;
    PFNGLBINDBUFFERBASEPROC BindBufferBase = glBindBufferBase;
    GenBuffers(1, &storage_buffer);
    BindBuffer(GL_SHADER_STORAGE_BUFFER, storage_buffer);
    BufferData(GL_SHADER_STORAGE_BUFFER, W * H * sizeof(GLuint), NULL, GL_DYNAMIC_DRAW);
    BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, storage_buffer);
    subtest(program && stores_match_render(name, program, reset_buffer, read_buffer), name);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 20;
    config.window_width = W;
    config.window_height = H;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_NO_ERRORS;

PIGLIT_GL_TEST_CONFIG_END

enum piglit_result
piglit_display(void)
{
    /* piglit_init reports the result. */
    return PIGLIT_FAIL;
}

void
piglit_init(int argc, char **argv)
{
    ou_init();
    UseProgram = glUseProgram;
    have_statistics = piglit_is_extension_supported("GL_ARB_pipeline_statistics_query");
    if (have_statistics) {
        PFNGLGENQUERIESPROC GenQueries = glGenQueries;
        BeginQuery = glBeginQuery;
        EndQuery = glEndQuery;
        GetQueryObjectuiv = glGetQueryObjectuiv;
        GenQueries(1, &query);
    }
    glDisable(GL_DEPTH_TEST);

    const GLuint plain =
        piglit_build_simple_program(NULL, "#version 110\nvoid main() { gl_FragColor = vec4(gl_FragCoord.x / 32.0); }\n");
    const GLuint discards = piglit_build_simple_program(NULL,
        "#version 110\nvoid main() { if (gl_FragCoord.x < 16.0) discard; gl_FragColor = vec4(1.0); }\n");
    if (!plain || !discards) {
        printf("a GLSL 1.10 shader did not build\n");
        piglit_report_result(PIGLIT_FAIL);
    }

    check_invocations(plain, GL_RENDER, false, "render-mode-shades");
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    check_invocations(plain, GL_BRIEF_OCCLUSION_MESAX, false, "alpha-test-needs-shading");
    glDisable(GL_ALPHA_TEST);
    check_invocations(discards, GL_BRIEF_OCCLUSION_MESAX, false, "discarding-shader-runs");
    test_atomic_counter_shaders();
    test_image_store();
    test_buffer_store();

    check_invocations(plain, GL_BRIEF_OCCLUSION_MESAX, true, "performance-brief-pass-skips-plain-shader");
    check_invocations(plain, GL_VERBOSE_OCCLUSION_MESAX, true, "performance-verbose-pass-skips-plain-shader");

    piglit_report_result(result);
}
