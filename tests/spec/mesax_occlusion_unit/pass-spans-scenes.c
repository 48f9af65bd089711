/*
 * GL_MESAX_occlusion_unit: a pass counts every primitive drawn between its
 * begin and end, however much work that is (spec MESAX_occlusion_unit,
 * section 5.X). An implementation that batches work may have to cut a pass
 * into several batches (llvmpipe's scenes hold at most 36 MiB of commands
 * and primitives, about 200 bytes per triangle and bin): the pass must go
 * on in every batch after the first.
 *
 * 256 x 256 window, depth cleared to 1, LESS; an occluder drawn before the
 * pass at z 0.25 over the left half. The pass draws 8 layers of 2 x 2-pixel
 * quads tiling the window (131072 quads, 262144 triangles), alternately at
 * z 0.5 (hidden on the left half) and z 0.125 (visible everywhere); a pass
 * writes no depth, so each layer is tested against the occluder's depth.
 *
 * Tiles: the window; (124, 60) 8 x 8, across the bins at x 128 and y 64
 * and the occluder's edge; the right half. Expected:
 *   window      PHC 8 * 65536, NOHC 4 * 65536 + 4 * 32768
 *   (124, 60)   PHC 8 * 64,    NOHC 4 * 64 + 4 * 32
 *   right half  PHC = NOHC = 8 * 32768
 * Counts, extents and depth exact (0.5 and 0.125 map to themselves,
 * counts-analytic.c).
 *
 * Subtests:
 *   brief-counts-every-primitive     the records, read with RenderMode
 *   async-counts-every-primitive     the same pass with Begin/EndOcclusionPassMESAX
 *                                    and a waiting read
 *
 * The test runs on llvmpipe with LP_NUM_THREADS 0, 1, 2 and 8 too
 * (tests/meson.build).
 */
#include "ou_util.h"

enum { S = 256, LAYERS = 8, TILES = 3 };

static struct ou_async_functions a;
static const GLint tiles[4 * TILES] = {0, 0, S, S, 124, 60, 8, 8, 128, 0, 128, S};
static GLuint records[TILES][OU_BRIEF_SIZE];

static void
draw_layers(void)
{
    glBegin(GL_QUADS);
    for (int l = 0; l < LAYERS; ++l) {
        const float z = l % 2 ? 0.125f : 0.5f;
        for (int y = 0; y < S; y += 2)
            for (int x = 0; x < S; x += 2) {
                glVertex3f(x, y, z);
                glVertex3f(x + 2, y, z);
                glVertex3f(x + 2, y + 2, z);
                glVertex3f(x, y + 2, z);
            }
    }
    glEnd();
}

static void
prepare(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_rect(0, 0, 128, S, 0.25f);
    GLuint *buffers[TILES];
    GLsizei sizes[TILES];
    for (int i = 0; i < TILES; ++i) {
        ou_fill(records[i], OU_BRIEF_SIZE);
        buffers[i] = records[i];
        sizes[i] = OU_BRIEF_SIZE;
    }
    OcclusionBuffersMESAX(TILES, sizes, buffers);
    ScissorsMESAX(TILES, tiles);
}

static bool
check(const char *name)
{
    const GLuint half = LAYERS / 2;
    GLuint e[TILES][OU_BRIEF_SIZE] = {
        {half * S * S + half * S * S / 2, LAYERS * S * S, 0, S - 1, 0, S - 1, ou_depth(0.125), ou_depth(0.5)},
        {half * 64 + half * 32, LAYERS * 64, 124, 131, 60, 67, ou_depth(0.125), ou_depth(0.5)},
        {LAYERS * S * S / 2, LAYERS * S * S / 2, 128, S - 1, 0, S - 1, ou_depth(0.125), ou_depth(0.5)},
    };
    bool ok = true;
    for (int t = 0; t < TILES; ++t) {
        char what[64];
        snprintf(what, sizeof(what), "%s tile %d", name, t);
        ok &= ou_check_record(what, records[t], e[t], 0);
    }
    return ok;
}

int main(int argc, char **argv)
{
    a = ou_init_async(argc, argv, S, S);

    prepare();
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    draw_layers();
    const GLint overflowed = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    subtest(overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR) && check("RenderMode"),
            "brief-counts-every-primitive");

    GLuint pass;
    a.GenOcclusionPasses(1, &pass);
    prepare();
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    draw_layers();
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    GLint async_overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &async_overflowed);
    subtest(async_overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR) && check("async"),
            "async-counts-every-primitive");
    a.DeleteOcclusionPasses(1, &pass);
    piglit_report_result(result);
}
