/*
 * GL_MESAX_occlusion_unit: the extension string, the limits and the
 * initial state of New State / New Implementation Dependent State.
 *
 * Subtests:
 *   max-tiles-at-least-64     MAX_OCCLUSION_TILES_MESAX >= 64
 *   tile-count-initially-0    OCCLUSION_TILE_COUNT_MESAX == 0
 *   render-mode-initially-render
 *   entry-points              both functions resolve (checked by ou_init)
 */
#include "ou_util.h"

int main(int argc, char **argv)
{
    ou_init(argc, argv, 16, 16);
    enum piglit_result result = PIGLIT_PASS, r;

    GLint max_tiles = 0;
    glGetIntegerv(GL_MAX_OCCLUSION_TILES_MESAX, &max_tiles);
    r = max_tiles >= 64 && piglit_check_gl_error(GL_NO_ERROR) ? PIGLIT_PASS : PIGLIT_FAIL;
    if (r == PIGLIT_FAIL)
        printf("MAX_OCCLUSION_TILES_MESAX is %d\n", max_tiles);
    piglit_report_subtest_result(r, "max-tiles-at-least-64");
    result = piglit_merge_result(result, r);

    GLint count = -1;
    glGetIntegerv(GL_OCCLUSION_TILE_COUNT_MESAX, &count);
    r = count == 0 && piglit_check_gl_error(GL_NO_ERROR) ? PIGLIT_PASS : PIGLIT_FAIL;
    piglit_report_subtest_result(r, "tile-count-initially-0");
    result = piglit_merge_result(result, r);

    GLint mode = 0;
    glGetIntegerv(GL_RENDER_MODE, &mode);
    r = mode == GL_RENDER ? PIGLIT_PASS : PIGLIT_FAIL;
    piglit_report_subtest_result(r, "render-mode-initially-render");
    result = piglit_merge_result(result, r);

    piglit_report_subtest_result(PIGLIT_PASS, "entry-points");
    piglit_report_result(result);
}
