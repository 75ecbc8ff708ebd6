/* librefray example: load a scene, render it, write a linear OpenEXR -- what
 * `refray render SCENE -o OUT.exr --width W --height H` does, through the public API only.
 *   render_scene SCENE OUT.exr W H
 * Prints the image size, the rays traced and the centre pixel. */
#include <stdio.h>
#include <stdlib.h>

#include <refray/image.h>
#include <refray/render.h>
#include <refray/scene_io.h>

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: render_scene SCENE OUT.exr W H\n");
        return 2;
    }
    char err[512];
    RfScene scene;
    if (rf_scene_load(argv[1], NULL, &scene, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    RfRenderOptions opt = rf_render_options_default(); /* the scene's settings ... */
    opt.width = atoi(argv[3]);                          /* ... at this size */
    opt.height = atoi(argv[4]);
    RfImage img;
    RfRenderStats stats;
    RfStatus st = rf_render(&scene, &opt, &img, &stats);
    rf_scene_free(&scene);
    if (st != RF_OK) {
        fprintf(stderr, "render: %s\n", rf_status_str(st));
        return 1;
    }
    if (rf_exr_write(argv[2], &img, NULL, 0, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        rf_image_free(&img);
        return 1;
    }
    const float *c = img.data + ((size_t)(img.height / 2) * img.width + img.width / 2) * img.channels;
    printf("%dx%d, %llu primary rays, centre %.9g %.9g %.9g\n", img.width, img.height,
           (unsigned long long)stats.primary_rays, c[0], c[1], c[2]);
    rf_image_free(&img);
    return 0;
}
