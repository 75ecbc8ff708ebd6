/* `refray chromaticity`: the CIE 1931 xy chromaticity diagram of §1.5 (PNG or SVG, drawn with
 * cairo), and `refray metamers`: the metamerism example of §1.3.1 as numbers and a plot. */
#include "cli.h"
#include "args.h"
#include "exit_codes.h"

#include <cairo-svg.h>
#include <cairo.h>
#include <fontconfig/fontconfig.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "refray/color.h"
#include "refray/transfer.h"

#define MAX_MARKS 32

typedef struct {
    RfVec2 primaries[3], white, points[MAX_MARKS], maps[MAX_MARKS];
    int n_points, n_maps, size, svg;
    RfGamutMethod method;
    const char *out, *gamut_name;
} Opts;

/* The plot: x in [X0, X1], y in [Y0, Y1], equal scale on both axes. */
#define X0 (-0.02)
#define X1 0.82
#define Y0 (-0.02)
#define Y1 0.92

typedef struct {
    double scale, left, top;
} Frame;

static double fx(const Frame *f, double x) { return f->left + (x - X0) * f->scale; }
static double fy(const Frame *f, double y) { return f->top + (Y1 - y) * f->scale; }

static int parse_xy(const char *s, RfVec2 *p)
{
    char *end;
    p->x = strtod(s, &end);
    if (end == s || (*end != ',' && *end != ' '))
        return 1;
    s = end + 1;
    p->y = strtod(s, &end);
    while (*end == ' ')
        end++;
    return end == s || (*end != 0 && *end != ';') || !isfinite(p->x) || !isfinite(p->y);
}

static int parse_primaries(const char *s, RfVec2 p[3])
{
    for (int i = 0; i < 3; i++) {
        if (parse_xy(s, &p[i]))
            return 1;
        s = strchr(s, ';');
        if (i < 2 && !s)
            return 1;
        if (s)
            s++;
    }
    return s != NULL && *s != 0;
}

/* Writes the surface's picture to path through a temporary name (no partial output file). */
typedef void (*DrawFn)(cairo_t *cr, const void *data, int w, int h);

static int render(const char *path, int svg, int w, int h, DrawFn draw, const void *data)
{
    size_t n = strlen(path) + 16;
    char *tmp = malloc(n);
    if (!tmp)
        return 1;
    snprintf(tmp, n, "%s.tmp%s", path, svg ? ".svg" : ".png");
    cairo_surface_t *s = svg ? cairo_svg_surface_create(tmp, w, h)
                             : cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
    cairo_t *cr = cairo_create(s);
    draw(cr, data, w, h);
    cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);
    if (!svg && st == CAIRO_STATUS_SUCCESS)
        st = cairo_surface_write_to_png(s, tmp);
    cairo_surface_finish(s);
    if (st == CAIRO_STATUS_SUCCESS)
        st = cairo_surface_status(s);
    cairo_surface_destroy(s);
    /* frees cairo's and fontconfig's caches, so that leak checkers see a clean exit */
    cairo_debug_reset_static_data();
    FcFini();
    int rc = 0;
    if (st != CAIRO_STATUS_SUCCESS || rename(tmp, path) != 0) {
        fprintf(stderr, "refray: cannot write %s: %s\n", path,
                st != CAIRO_STATUS_SUCCESS ? cairo_status_to_string(st) : "rename failed");
        remove(tmp);
        rc = 1;
    }
    free(tmp);
    return rc;
}

static void text_at(cairo_t *cr, double x, double y, double ax, double ay, const char *s)
{
    cairo_text_extents_t e;
    cairo_text_extents(cr, s, &e);
    cairo_move_to(cr, x - ax * e.width - e.x_bearing, y - ay * e.height - e.y_bearing);
    cairo_show_text(cr, s);
}

/* The locus (1 nm, 360..830) closed by the purple line, as the current path. */
static void locus_path(cairo_t *cr, const Frame *f)
{
    for (int l = RF_LOCUS_FIRST_NM; l <= RF_LOCUS_LAST_NM; l++) {
        RfVec2 p;
        rf_locus(l, &p);
        if (l == RF_LOCUS_FIRST_NM)
            cairo_move_to(cr, fx(f, p.x), fy(f, p.y));
        else
            cairo_line_to(cr, fx(f, p.x), fy(f, p.y));
    }
    cairo_close_path(cr);
}

/* Approximate colours of the horseshoe: xy at Y = 1 to linear sRGB, negative parts lifted
 * (desaturated) and the brightest channel scaled to 1, then the sRGB curve. */
static cairo_surface_t *fill_image(const Frame *f, int w, int h)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    RfMat3 m = rf_rgb_to_xyz_matrix(RF_RGB_SRGB), inv;
    rf_mat3_inverse(m, &inv);
    unsigned char *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    cairo_surface_flush(img);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double x = X0 + (i + 0.5 - f->left) / f->scale, y = Y1 - (j + 0.5 - f->top) / f->scale;
            uint32_t px = 0xffffff;
            if (y > 1e-3) {
                RfVec3 c = rf_mat3_mul_vec(inv, rf_vec3(x / y, 1.0, (1.0 - x - y) / y));
                double mn = fmin(c.x, fmin(c.y, c.z));
                if (mn < 0.0)
                    c = rf_vec3(c.x - mn, c.y - mn, c.z - mn);
                double mx = fmax(c.x, fmax(c.y, c.z));
                if (mx > 0.0) {
                    long r = rf_quantize(rf_srgb_encode(c.x / mx), 8);
                    long g = rf_quantize(rf_srgb_encode(c.y / mx), 8);
                    long b = rf_quantize(rf_srgb_encode(c.z / mx), 8);
                    px = (uint32_t)(r << 16 | g << 8 | b);
                }
            }
            memcpy(data + (size_t)j * (size_t)stride + (size_t)i * 4, &px, 4);
        }
    cairo_surface_mark_dirty(img);
    return img;
}

static void draw_grid(cairo_t *cr, const Frame *f)
{
    char buf[16];
    cairo_set_line_width(cr, 1.0);
    cairo_set_font_size(cr, f->scale * 0.016);
    for (int k = 0; k <= 9; k++) {
        double v = k / 10.0;
        cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
        if (v <= 0.8) {
            cairo_move_to(cr, fx(f, v), fy(f, 0));
            cairo_line_to(cr, fx(f, v), fy(f, 0.9));
        }
        cairo_move_to(cr, fx(f, 0), fy(f, v));
        cairo_line_to(cr, fx(f, 0.8), fy(f, v));
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
        snprintf(buf, sizeof buf, "%.1f", v);
        if (v <= 0.8)
            text_at(cr, fx(f, v), fy(f, 0) + 6, 0.5, 0.0, buf);
        text_at(cr, fx(f, 0) - 6, fy(f, v), 1.0, 0.5, buf);
    }
    cairo_set_font_size(cr, f->scale * 0.022);
    text_at(cr, fx(f, 0.8), fy(f, 0) + f->scale * 0.045, 1.0, 0.0, "x");
    text_at(cr, fx(f, 0) - f->scale * 0.05, fy(f, 0.9), 0.5, 0.0, "y");
}

static const int label_nm[] = {460, 470, 475, 480, 485, 490, 495, 500, 505, 510, 520, 530, 540,
                               550, 560, 570, 580, 590, 600, 610, 620, 640, 700};

static void draw_locus_labels(cairo_t *cr, const Frame *f, RfVec2 centre)
{
    char buf[16];
    cairo_set_font_size(cr, f->scale * 0.016);
    for (size_t i = 0; i < sizeof label_nm / sizeof label_nm[0]; i++) {
        RfVec2 p, a, b;
        int l = label_nm[i];
        rf_locus(l, &p);
        rf_locus(l - 1, &a);
        rf_locus(l + 1, &b);
        /* outward normal of the locus; it points away from the centre of the horseshoe */
        double nx = b.y - a.y, ny = -(b.x - a.x), len = hypot(nx, ny);
        nx /= len, ny /= len;
        if (nx * (p.x - centre.x) + ny * (p.y - centre.y) < 0)
            nx = -nx, ny = -ny;
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_line_width(cr, 1.2);
        cairo_move_to(cr, fx(f, p.x), fy(f, p.y));
        cairo_line_to(cr, fx(f, p.x + 0.012 * nx), fy(f, p.y + 0.012 * ny));
        cairo_stroke(cr);
        snprintf(buf, sizeof buf, "%d", l);
        text_at(cr, fx(f, p.x + 0.02 * nx), fy(f, p.y + 0.02 * ny), 0.5 - 0.5 * nx, 0.5 + 0.5 * ny, buf);
    }
}

static void marker(cairo_t *cr, const Frame *f, RfVec2 p, double r, int filled)
{
    cairo_new_sub_path(cr);
    cairo_arc(cr, fx(f, p.x), fy(f, p.y), r, 0, 2 * RF_PI);
    if (filled)
        cairo_fill_preserve(cr);
    cairo_stroke(cr);
}

static void draw_diagram(cairo_t *cr, const void *data, int w, int h)
{
    const Opts *o = data;
    RfVec2 prim[3]; /* a local copy: GCC 12 with -fsanitize misjudges the size of o->primaries */
    memcpy(prim, o->primaries, sizeof prim);
    Frame f;
    double margin = o->size * 0.07;
    f.scale = (o->size - 2 * margin) / (Y1 - Y0);
    f.left = margin;
    f.top = margin;
    char buf[96];
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_grid(cr, &f);

    /* the horseshoe, filled with approximate colours */
    cairo_surface_t *img = fill_image(&f, w, h);
    cairo_save(cr);
    locus_path(cr, &f);
    cairo_clip(cr);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);

    /* the locus and the purple line */
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.6);
    locus_path(cr, &f);
    cairo_stroke(cr);
    RfVec2 a, b;
    rf_locus(RF_LOCUS_FIRST_NM, &a);
    rf_locus(RF_LOCUS_LAST_NM, &b);
    double dash[2] = {6, 4};
    cairo_set_source_rgb(cr, 0.3, 0.0, 0.3);
    cairo_set_line_width(cr, 2.0);
    cairo_set_dash(cr, dash, 2, 0);
    cairo_move_to(cr, fx(&f, a.x), fy(&f, a.y));
    cairo_line_to(cr, fx(&f, b.x), fy(&f, b.y));
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
    cairo_set_font_size(cr, f.scale * 0.016);
    {
        double t = 0.55, px = a.x + t * (b.x - a.x), py = a.y + t * (b.y - a.y);
        text_at(cr, fx(&f, px) + 4, fy(&f, py) + 6, 0.0, 0.0, "purple line");
    }
    draw_locus_labels(cr, &f, rf_vec2(0.33, 0.33));

    /* the device gamut */
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_line_width(cr, 1.8);
    cairo_new_path(cr); /* show_text leaves a current point behind */
    for (int i = 0; i < 3; i++)
        cairo_line_to(cr, fx(&f, o->primaries[i].x), fy(&f, o->primaries[i].y));
    cairo_close_path(cr);
    cairo_stroke(cr);
    cairo_set_font_size(cr, f.scale * 0.018);
    text_at(cr, fx(&f, o->primaries[0].x) + 10, fy(&f, o->primaries[0].y) + 4, 0.0, 0.0,
            strcmp(o->gamut_name, "sRGB") == 0 ? "sRGB" : "gamut");

    /* the white point */
    cairo_set_line_width(cr, 1.5);
    cairo_set_source_rgb(cr, 1, 1, 1);
    marker(cr, &f, o->white, 5, 1);
    cairo_set_source_rgb(cr, 0, 0, 0);
    marker(cr, &f, o->white, 5, 0);
    text_at(cr, fx(&f, o->white.x) + 8, fy(&f, o->white.y) + 4, 0.0, 0.0, "W");

    /* the given points with their dominant wavelength */
    cairo_set_font_size(cr, f.scale * 0.016);
    for (int i = 0; i < o->n_points; i++) {
        RfDominant d;
        RfVec2 p = o->points[i];
        if (rf_dominant_wavelength(p, o->white, &d) != RF_OK)
            continue;
        cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
        cairo_set_line_width(cr, 1.2);
        cairo_set_dash(cr, dash, 2, 0);
        cairo_move_to(cr, fx(&f, o->white.x), fy(&f, o->white.y));
        cairo_line_to(cr, fx(&f, d.boundary.x), fy(&f, d.boundary.y));
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
        marker(cr, &f, d.boundary, 3, 1);
        cairo_set_source_rgb(cr, 1, 1, 0.2);
        marker(cr, &f, p, 5, 1);
        cairo_set_source_rgb(cr, 0, 0, 0);
        marker(cr, &f, p, 5, 0);
        if (d.on_purple_line)
            snprintf(buf, sizeof buf, "C%d: %.1f nm (c), p = %.2f", i + 1, d.lambda_nm, d.purity);
        else
            snprintf(buf, sizeof buf, "C%d: %.1f nm, p = %.2f", i + 1, d.lambda_nm, d.purity);
        text_at(cr, fx(&f, p.x) + 8, fy(&f, p.y) - 6, 0.0, 1.0, buf);
    }

    /* gamut-mapped points: the line each moved along */
    for (int i = 0; i < o->n_maps; i++) {
        RfVec2 p = o->maps[i], q;
        if (rf_gamut_map(p, prim, o->white, o->method, &q) != RF_OK)
            continue;
        cairo_set_source_rgb(cr, 0.8, 0.0, 0.0);
        cairo_set_line_width(cr, 2.0);
        if (o->method == RF_GAMUT_TOWARD_WHITE) { /* the line to the white point, thin */
            cairo_save(cr);
            cairo_set_line_width(cr, 0.8);
            cairo_set_dash(cr, dash, 2, 0);
            cairo_move_to(cr, fx(&f, q.x), fy(&f, q.y));
            cairo_line_to(cr, fx(&f, o->white.x), fy(&f, o->white.y));
            cairo_stroke(cr);
            cairo_restore(cr);
        }
        cairo_move_to(cr, fx(&f, p.x), fy(&f, p.y));
        cairo_line_to(cr, fx(&f, q.x), fy(&f, q.y));
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 1, 1, 1);
        marker(cr, &f, p, 5, 1);
        cairo_set_source_rgb(cr, 0.8, 0, 0);
        marker(cr, &f, p, 5, 0);
        marker(cr, &f, q, 4, 1);
        snprintf(buf, sizeof buf, "M%d -> (%.3f, %.3f)", i + 1, q.x, q.y);
        text_at(cr, fx(&f, p.x) + 8, fy(&f, p.y) + 4, 0.0, 0.0, buf);
    }

    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, f.scale * 0.024);
    text_at(cr, w / 2.0, margin * 0.45, 0.5, 0.5, "CIE 1931 xy chromaticity diagram (2\xc2\xb0 observer)");
}

enum { OPT_PRIMARIES = RF_OPT_ID, OPT_WHITE, OPT_POINT, OPT_MAP, OPT_METHOD, OPT_SIZE };

static const RfOpt chroma_opts[] = {
    {"output", 'o', "FILE", "the diagram: .png or .svg", NULL},
    {"primaries", OPT_PRIMARIES, "x,y;x,y;x,y", "gamut triangle (default sRGB 0.64,0.33;0.30,0.60;0.15,0.06)",
     "three x,y pairs separated by ';'"},
    {"white", OPT_WHITE, "x,y", "white point (default 1/3,1/3, the script's)", "x,y: two numbers"},
    {"point", OPT_POINT, "x,y", "a colour; its dominant wavelength is drawn (repeatable, up to 32)",
     "x,y: two numbers (32 points at most)"},
    {"map", OPT_MAP, "x,y", "a colour mapped into the gamut (repeatable, up to 32)",
     "x,y: two numbers (32 points at most)"},
    {"method", OPT_METHOD, "toward-white|nearest", "gamut mapping (default toward-white)", "toward-white or nearest"},
    {"size", OPT_SIZE, "N", "picture size in pixels (default 900)", "an integer in [200, 8000]"},
    RF_OPT_TABLE_END,
};

static const RfOpt *const chroma_tables[] = {chroma_opts, NULL};

static const RfCommand chroma_cmd = {
    "refray chromaticity",
    "refray chromaticity -o FILE.png|FILE.svg [options]\n",
    "Draws the CIE 1931 xy diagram (§1.5): the spectral locus labelled in nm, the purple\n"
    "line, the white point, a device gamut, points with their dominant wavelength and\n"
    "gamut-mapped points; prints the numbers it drew.\n",
    chroma_tables,
    "exit: 0 ok, 2 a point cannot be computed (it is the white point), 4 the picture cannot be\n"
    "written, 5 usage (README: Exit codes)\n",
};

int rf_cmd_chromaticity(int argc, char **argv)
{
    Opts o;
    memset(&o, 0, sizeof o);
    memcpy(o.primaries, rf_srgb_primaries, sizeof o.primaries);
    o.white = rf_vec2(1.0 / 3.0, 1.0 / 3.0);
    o.size = 900;
    o.gamut_name = "sRGB";
    RfOptParser p;
    int key;
    rf_opt_init(&p, &chroma_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *v = p.value;
        int bad = 0;
        if (key == RF_OPT_EXIT)
            return p.exit_code;
        if (key == 'o')
            o.out = v;
        else if (key == OPT_PRIMARIES)
            bad = parse_primaries(v, o.primaries), o.gamut_name = "given primaries";
        else if (key == OPT_WHITE)
            bad = parse_xy(v, &o.white);
        else if (key == OPT_POINT)
            bad = o.n_points >= MAX_MARKS || parse_xy(v, &o.points[o.n_points++]);
        else if (key == OPT_MAP)
            bad = o.n_maps >= MAX_MARKS || parse_xy(v, &o.maps[o.n_maps++]);
        else if (key == OPT_METHOD) {
            bad = strcmp(v, "toward-white") != 0 && strcmp(v, "nearest") != 0;
            o.method = strcmp(v, "nearest") == 0 ? RF_GAMUT_NEAREST : RF_GAMUT_TOWARD_WHITE;
        } else if (key == OPT_SIZE)
            bad = !rf_arg_int(v, 200, 8000, &o.size);
        if (bad)
            return rf_opt_bad_value(&p);
    }
    int bad = rf_opt_operand(&p, NULL, NULL);
    if (bad)
        return bad;
    if (!o.out)
        return rf_opt_usage_error(&chroma_cmd, "missing the output: -o FILE.png or -o FILE.svg");
    if (!rf_arg_image_format("refray chromaticity", "-o", o.out, RF_IMAGE_PNG | RF_IMAGE_SVG))
        return RF_EXIT_USAGE;
    o.svg = rf_arg_image_format("refray chromaticity", "-o", o.out, RF_IMAGE_SVG | RF_IMAGE_PNG) == RF_IMAGE_SVG;
    double bary[3];
    if (rf_gamut_barycentric(o.white, o.primaries, bary) != RF_OK) {
        fprintf(stderr, "refray chromaticity: the primaries are collinear\n");
        return RF_EXIT_USAGE;
    }
    /* the numbers behind the picture */
    printf("white (%.6f, %.6f); gamut (%s) (%.4f, %.4f) (%.4f, %.4f) (%.4f, %.4f)\n", o.white.x,
           o.white.y, o.gamut_name, o.primaries[0].x, o.primaries[0].y, o.primaries[1].x,
           o.primaries[1].y, o.primaries[2].x, o.primaries[2].y);
    for (int i = 0; i < o.n_points; i++) {
        RfDominant d;
        RfStatus st = rf_dominant_wavelength(o.points[i], o.white, &d);
        if (st != RF_OK) {
            fprintf(stderr, "refray chromaticity: point %d (%g, %g): %s\n", i + 1, o.points[i].x,
                    o.points[i].y, st == RF_ERR_DEGENERATE ? "is the white point" : "white point outside the locus");
            return RF_EXIT_FAIL;
        }
        printf("C%d (%.4f, %.4f): dominant %.4f nm%s, purity %.4f, complementary ", i + 1,
               o.points[i].x, o.points[i].y, d.lambda_nm, d.on_purple_line ? " (purple: minus complementary)" : "",
               d.purity);
        if (d.has_complementary)
            printf("%.4f nm\n", d.complementary_nm);
        else
            printf("none (purple line)\n");
    }
    for (int i = 0; i < o.n_maps; i++) {
        RfVec2 q;
        if (rf_gamut_map(o.maps[i], o.primaries, o.white, o.method, &q) != RF_OK) {
            fprintf(stderr, "refray chromaticity: toward-white needs the white point inside the gamut\n");
            return RF_EXIT_FAIL;
        }
        printf("M%d (%.4f, %.4f) -> (%.6f, %.6f), %s, shift %.6f\n", i + 1, o.maps[i].x, o.maps[i].y,
               q.x, q.y, o.method == RF_GAMUT_NEAREST ? "nearest" : "toward white",
               hypot(q.x - o.maps[i].x, q.y - o.maps[i].y));
    }
    if (render(o.out, o.svg, o.size, o.size, draw_diagram, &o))
        return RF_EXIT_FILE;
    printf("wrote %s\n", o.out);
    return 0;
}

/* ---- refray metamers ---- */

enum { MET_FIRST = 400, MET_N = 301 };

typedef struct {
    double p1[MET_N], p2[MET_N];
    int size;
} Metamers;

static void draw_metamers(cairo_t *cr, const void *data, int w, int h)
{
    const Metamers *m = data;
    double left = w * 0.1, right = w * 0.96, top = h * 0.2, bottom = h * 0.86;
    double ymax = 0.0;
    char buf[64];
    for (int i = 0; i < MET_N; i++)
        ymax = fmax(ymax, fmax(m->p1[i], m->p2[i]));
    ymax = ceil(ymax * 2.0) / 2.0;
#define MX(l) (left + ((l) - 380.0) / (720.0 - 380.0) * (right - left))
#define MY(v) (bottom - (v) / ymax * (bottom - top))
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_font_size(cr, h * 0.028);
    cairo_set_line_width(cr, 1.0);
    for (int l = 400; l <= 700; l += 50) {
        cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
        cairo_move_to(cr, MX(l), top);
        cairo_line_to(cr, MX(l), bottom);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
        snprintf(buf, sizeof buf, "%d", l);
        text_at(cr, MX(l), bottom + 6, 0.5, 0.0, buf);
    }
    for (double v = 0.0; v <= ymax + 1e-9; v += 0.5) {
        cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
        cairo_move_to(cr, left, MY(v));
        cairo_line_to(cr, right, MY(v));
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
        snprintf(buf, sizeof buf, "%.1f", v);
        text_at(cr, left - 6, MY(v), 1.0, 0.5, buf);
    }
    text_at(cr, (left + right) / 2, bottom + h * 0.06, 0.5, 0.0, "wavelength (nm)");
    /* the CIE 1931 ȳ for orientation */
    cairo_set_source_rgba(cr, 0.2, 0.6, 0.2, 0.5);
    cairo_set_line_width(cr, 1.5);
    cairo_new_path(cr);
    for (int l = 380; l <= 720; l++)
        cairo_line_to(cr, MX(l), MY(rf_cmf_at(RF_CMF_XYZ_1931, l).y * ymax * 0.5));
    cairo_stroke(cr);
    const double *curves[2] = {m->p1, m->p2};
    const double col[2][3] = {{0.1, 0.2, 0.8}, {0.85, 0.3, 0.0}};
    for (int k = 0; k < 2; k++) {
        cairo_set_source_rgb(cr, col[k][0], col[k][1], col[k][2]);
        cairo_set_line_width(cr, 2.5);
        cairo_move_to(cr, MX(MET_FIRST - 1), MY(0));
        for (int i = 0; i < MET_N; i++)
            cairo_line_to(cr, MX(MET_FIRST + i), MY(curves[k][i]));
        cairo_line_to(cr, MX(MET_FIRST + MET_N), MY(0));
        cairo_stroke(cr);
    }
    cairo_set_font_size(cr, h * 0.03);
    cairo_set_source_rgb(cr, col[0][0], col[0][1], col[0][2]);
    text_at(cr, right, top - h * 0.08, 1.0, 0.5, "P1: flat, 400-700 nm");
    cairo_set_source_rgb(cr, col[1][0], col[1][1], col[1][2]);
    text_at(cr, right, top - h * 0.035, 1.0, 0.5, "P2: its metamer (same XYZ and LMS)");
    cairo_set_source_rgba(cr, 0.2, 0.6, 0.2, 0.9);
    text_at(cr, left + 6, top - h * 0.035, 0.0, 0.5, "CIE 1931 y-bar (scaled)");
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, h * 0.036);
    text_at(cr, w / 2.0, h * 0.045, 0.5, 0.5, "Metamers (\xc2\xa7" "1.3.1): different spectra, one colour");
#undef MX
#undef MY
}

static const RfOpt metamers_opts[] = {
    {"output", 'o', "FILE", "plot the two spectra: .png or .svg", NULL},
    {"size", OPT_SIZE, "N", "plot width in pixels (default 800)", "an integer in [200, 8000]"},
    RF_OPT_TABLE_END,
};

static const RfOpt *const metamers_tables[] = {metamers_opts, NULL};

static const RfCommand metamers_cmd = {
    "refray metamers",
    "refray metamers [-o FILE.png|FILE.svg] [--size N]\n",
    "Builds two clearly different spectra with the same CIE 1931 XYZ and the same CIE 2006\n"
    "LMS (§1.3.1), prints them and their tristimulus values, and plots them.\n",
    metamers_tables,
    "exit: 0 ok, 2 no metamer found, 4 the plot cannot be written, 5 usage (README: Exit codes)\n",
};

int rf_cmd_metamers(int argc, char **argv)
{
    Metamers m;
    const char *out = NULL;
    m.size = 800;
    RfOptParser p;
    int key;
    rf_opt_init(&p, &metamers_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        if (key == RF_OPT_EXIT)
            return p.exit_code;
        if (key == 'o')
            out = p.value;
        else if (key == OPT_SIZE && !rf_arg_int(p.value, 200, 8000, &m.size))
            return rf_opt_bad_value(&p);
    }
    int bad = rf_opt_operand(&p, NULL, NULL);
    if (bad)
        return bad;
    if (out && !rf_arg_image_format("refray metamers", "-o", out, RF_IMAGE_PNG | RF_IMAGE_SVG))
        return RF_EXIT_USAGE;
    double lam[MET_N];
    for (int i = 0; i < MET_N; i++)
        lam[i] = MET_FIRST + i, m.p1[i] = 1.0;
    if (rf_metamer(MET_FIRST, MET_N, m.p1, 0.9, m.p2) != RF_OK) {
        fprintf(stderr, "refray metamers: no metamer found\n");
        return RF_EXIT_FAIL;
    }
    const double *ps[2] = {m.p1, m.p2};
    printf("spectrum  X                   Y                   Z                   L                   M                   S\n");
    for (int k = 0; k < 2; k++) {
        RfVec3 x, l;
        rf_spectrum_integrate(RF_CMF_XYZ_1931, lam, ps[k], MET_N, &x);
        rf_spectrum_integrate(RF_CMF_LMS_2006, lam, ps[k], MET_N, &l);
        printf("P%d        %-19.15g %-19.15g %-19.15g %-19.15g %-19.15g %.15g\n", k + 1, x.x, x.y, x.z,
               l.x, l.y, l.z);
    }
    printf("lambda_nm P1 P2 (every 20 nm; 1 nm in the computation)\n");
    for (int i = 0; i < MET_N; i += 20)
        printf("%d %.1f %.6f\n", MET_FIRST + i, m.p1[i], m.p2[i]);
    if (out) {
        if (render(out, rf_arg_image_format("refray metamers", "-o", out, RF_IMAGE_SVG | RF_IMAGE_PNG) == RF_IMAGE_SVG,
                   m.size, m.size * 5 / 8, draw_metamers, &m))
            return RF_EXIT_FILE;
        printf("wrote %s\n", out);
    }
    return 0;
}
