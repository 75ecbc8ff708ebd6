/* The smallest librefray program: built by the install test with pkg-config alone,
 *   cc hello.c $(pkg-config --cflags --libs refray)
 * Loads a scene, renders it at 32 x 24, prints the library version and pixel (16, 12). */
#include <stdio.h>
#include <refray/render.h>
#include <refray/scene_io.h>
#include <refray/version.h>

int main(int argc, char **argv)
{
    char err[512];
    RfScene scene;
    RfImage img;
    RfRenderStats stats;
    RfRenderOptions opt = rf_render_options_default();
    if (argc != 2 || rf_scene_load(argv[1], NULL, &scene, err, sizeof err) != RF_OK)
        return fprintf(stderr, "usage: hello SCENE (%s)\n", argc == 2 ? err : ""), 1;
    opt.width = 32, opt.height = 24;
    if (rf_render(&scene, &opt, &img, &stats) != RF_OK)
        return 1;
    printf("refray %s: pixel (16, 12) = %.9g %.9g %.9g\n", RF_VERSION, img.data[(12 * 32 + 16) * 3],
           img.data[(12 * 32 + 16) * 3 + 1], img.data[(12 * 32 + 16) * 3 + 2]);
    rf_image_free(&img), rf_scene_free(&scene);
    return 0;
}
