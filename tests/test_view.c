/* refray-view under Xvfb (issue 15): the window shows the tracer's converged image, the same as
 * `refray render`'s PNG to one 8-bit code (the display's gamma is applied on the GPU, the PNG's
 * on the CPU: pow may round the other way), and the OpenGL view is refray-raster's image; driven
 * by real X events, every key, the mouse and the reload work. Runs when xvfb-run (and for the
 * interactive part xdotool) is installed; CI installs both. */
#define _XOPEN_SOURCE 700
#include "rf_test.h"

#include <stdlib.h>
#include <unistd.h>

static void t_view_screenshot(void)
{
    int code;
    if (!rf_test_have("xvfb-run")) {
        fprintf(stderr, "  skipped: xvfb-run is not installed (apt-get install xvfb xauth)\n");
        return;
    }
    char bin[1100], view[1100], raster[1100], dir[] = "/tmp/rf_view_XXXXXX", cmd[4096];
    if (!rf_test_tool("refray", bin, sizeof bin) || !rf_test_tool("refray-view", view, sizeof view) ||
        !rf_test_tool("refray-raster", raster, sizeof raster) || !mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "no %s or no temporary folder", rf_test_bin());
        return;
    }
    /* Under the sanitizer build, leak checking is off for the viewer's processes only: Mesa's GLX
     * driver keeps blocks to the end whose stacks name no module (compare/lsan.supp says more);
     * ASan's other checks stay on. */
    /* --help lists every key */
    snprintf(cmd, sizeof cmd, "%s --help", view);
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    static const char *const keys[] = {"T / G / D", "L ", "[ ]", "- =", "left drag", "right drag", "wheel", "R ",
                                       "C ", "click", "S ", "Esc"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        RF_CHECK(strstr(out, keys[k]) != NULL);
    /* the reference command: refray (tracer cases) or refray-raster, on the same scene at 160 x 120 */
    static const struct {
        const char *what, *scene, *view_args;
        int raster;
        const char *ref_args;
    } cases[] = {
        /* the tracer at 4 spp: a 1-sample pass first, then the converged one */
        {"tracer", "scenes/whitted.rf", "--samples 4", 0, "--samples 4 --quiet"},
        {"raster", "scenes/whitted.rf", "--local --show raster", 1, ""},
        /* --two-sided on both views: the SPD teapot's lid gap shows the pot's inside (16 pixels
         * at this size), not the sky */
        {"tracer two-sided", "scenes/spd/teapot.nff", "--local --two-sided", 0, "--local --two-sided --quiet"},
        {"raster two-sided", "scenes/spd/teapot.nff", "--local --two-sided --show raster", 1, "--two-sided"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(cmd, sizeof cmd, "%s%s %s --width 160 --height 120 %s -o %s/ref.exr --png %s/ref.png",
                 cases[i].raster ? raster : bin, cases[i].raster ? "" : " render", cases[i].scene, cases[i].ref_args,
                 dir, dir);
        rf_test_run(cmd, &code);
        RF_CHECK_EQ_INT(code, 0);
        snprintf(cmd, sizeof cmd,
                 "ASAN_OPTIONS=detect_leaks=0 timeout 120 xvfb-run -a -s '-screen 0 640x480x24' %s %s --width 160 --height 120 %s "
                 "--screenshot %s/shot.png --timeout 90 2>&1 && %s diff %s/shot.png %s/ref.png --space display --kv",
                 view, cases[i].scene, cases[i].view_args, dir, bin, dir, dir);
        out = rf_test_run(cmd, &code);
        double mx = rf_test_diff_kv(out, "max_abs"), pct = rf_test_diff_kv(out, "pct_above_255");
        fprintf(stderr, "  %s view against its reference PNG (display codes): max %.4g, %.4g %% off by more than 1/255\n",
                cases[i].what, mx, pct);
        /* compared as the 8-bit codes the two PNGs hold: at most one code apart */
        if (!(mx <= 1.0 / 255 + 1e-6 && pct == 0.0))
            rf_test_fail(__FILE__, __LINE__, "%s: screenshot differs: %s", cases[i].what, out);
        rf_test_checks++;
    }
    /* real X events through xdotool: keys, a click, a drag, a broken and a repaired edit, saving
     * (the converged image bit for bit refray render's), quitting (tests/view_interactive.sh) */
    if (!rf_test_have("xdotool")) {
        fprintf(stderr, "  skipped the interactive part: xdotool is not installed (apt-get install xdotool)\n");
    } else {
        snprintf(cmd, sizeof cmd, "rm -rf %s/* && ASAN_OPTIONS=detect_leaks=0 timeout 180 xvfb-run -a -s '-screen 0 640x480x24' sh tests/view_interactive.sh %s %s %s %s 2>&1",
                 dir, view, bin, raster, dir);
        out = rf_test_run(cmd, &code);
        if (code != 0 || !strstr(out, "all work"))
            rf_test_fail(__FILE__, __LINE__, "tests/view_interactive.sh (exit %d):\n%s", code, out);
        rf_test_checks++;
    }
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    rf_test_run(cmd, &code);
}

const RfTest rf_tests_view[] = {
    {"view_screenshot", t_view_screenshot},
    RF_TEST_END,
};
