/* Ear clipping of a simple polygon in the plane, in about linear time for the polygons scenes
 * hold (issue 13: the rasterizer's first version rescanned every vertex for every ear, O(n^2)
 * to O(n^3): 15.6 s for a 100k-vertex star). The tracer cuts non-convex polygons into these
 * triangles, the rasterizer draws them.
 *
 * Three things make it fast without changing what counts as an ear:
 *  - the vertices form a ring (next/prev), and the search for the next ear continues just past
 *    the last one cut, instead of starting over;
 *  - only non-convex vertices (reflex or flat, signed area <= 0) can lie inside or on an ear of a
 *    simple polygon (Meisters' two-ears argument: a convex vertex inside would make the ear's
 *    diagonal cross the boundary), so only they are tested;
 *  - those tests look only at the vertices in the grid cells under the ear's bounding box; the
 *    grid holds the non-convex vertices alone, about one per cell, and is rebuilt over those
 *    left whenever their number halves (the late ears are large); an ear visits, row by row,
 *    only the cells it crosses.
 * Measured (one core): a regular 100k-vertex star, the whole refray-raster run 15.6 s before,
 * 0.12 s now; a random star (sorted angles, radii in [0.2, 1]: every ear a long sliver) 100k
 * vertices 0.18 s, 1M 5.1 s -- each sliver crosses ~sqrt(n) cells there, the one superlinear
 * part left (a grid over all vertices visiting whole bounding boxes: 0.79 s at 100k).
 * Cutting an ear only makes its two neighbours' corners smaller, so a vertex's non-convex flag
 * is recomputed there and nowhere else. A polygon that is not simple can run out of ears; the
 * rest is then fanned, as before, rather than dropped. */
#include "refray/geometry.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
    const double *u, *v;
    int n;
    double sgn; /* the polygon's orientation: every ear keeps it */
    int *next, *prev;
    unsigned char *blocker; /* alive and not strictly convex: may lie in an ear */
    int blockers, gridded;  /* how many there are, and how many the grid was built with */
    /* the grid over the blockers: cell (i, j) holds cell_items[cell_start[c] .. cell_start[c + 1]) */
    int gw, gh;
    double u0, v0, cu, cv; /* origin and inverse cell sizes */
    int *cell_start, *cell_items, *cell_of_item;
} Ears;

/* twice the signed area of (a, b, c), times the orientation: > 0 is a convex corner at b */
static inline double corner(const Ears *e, int a, int b, int c)
{
    const double *u = e->u, *v = e->v;
    return e->sgn * ((u[b] - u[a]) * (v[c] - v[a]) - (v[b] - v[a]) * (u[c] - u[a]));
}

/* The cell of coordinate x, clamped to the grid (in double first: an ear reaches far beyond the
 * blockers' grid, and a double beyond int's range has no int; found by fuzzing) */
static int cell_of(double x, double x0, double inv, int count)
{
    double f = (x - x0) * inv;
    if (!(f >= 0.0))
        return 0;
    return f < (double)count ? (int)f : count - 1;
}

/* The grid over the current blockers, about one per cell (counting sort into the cells). */
static void grid_build(Ears *e)
{
    const double *u = e->u, *v = e->v;
    double ulo = INFINITY, uhi = -INFINITY, vlo = INFINITY, vhi = -INFINITY;
    int count = 0;
    for (int k = 0; k < e->n; k++)
        if (e->blocker[k]) {
            ulo = fmin(ulo, u[k]), uhi = fmax(uhi, u[k]);
            vlo = fmin(vlo, v[k]), vhi = fmax(vhi, v[k]);
            count++;
        }
    e->gridded = count;
    e->gw = e->gh = 1;
    e->u0 = count ? ulo : 0.0, e->v0 = count ? vlo : 0.0;
    double du = count ? uhi - ulo : 0.0, dv = count ? vhi - vlo : 0.0, side = sqrt(du * dv / (count + 1));
    if (!(side > 0.0))
        side = fmax(du, dv) / (count + 1);
    if (side > 0.0) {
        e->gw = (int)fmin(du / side, 2048.0) + 1;
        e->gh = (int)fmin(dv / side, 2048.0) + 1;
    }
    e->cu = du > 0.0 ? e->gw / du : 0.0;
    e->cv = dv > 0.0 ? e->gh / dv : 0.0;
    int cells = e->gw * e->gh;
    for (int c = 0; c <= cells; c++)
        e->cell_start[c] = 0;
    for (int k = 0; k < e->n; k++)
        if (e->blocker[k]) {
            e->cell_of_item[k] = cell_of(v[k], e->v0, e->cv, e->gh) * e->gw + cell_of(u[k], e->u0, e->cu, e->gw);
            e->cell_start[e->cell_of_item[k] + 1]++;
        }
    for (int c = 0; c < cells; c++)
        e->cell_start[c + 1] += e->cell_start[c];
    for (int k = 0; k < e->n; k++) /* each start moves on to the next cell's while filling */
        if (e->blocker[k])
            e->cell_items[e->cell_start[e->cell_of_item[k]]++] = k;
    for (int c = cells; c > 0; c--) /* so move them back */
        e->cell_start[c] = e->cell_start[c - 1];
    e->cell_start[0] = 0;
}

/* a, b, c is an ear: strictly convex at b, and no blocking vertex inside or on it (collinear
 * ones too). A flat corner is never cut: a triangle of zero area would take the polygon's edges
 * a-b and b-c with it, and the neighbour sharing those edges would meet the diagonal a-c
 * instead, a T-junction where the watertight test cannot promise anything (tracer.c). Once a
 * neighbour is cut, the flat corner turns convex. */
static int is_ear(const Ears *e, int a, int b, int c)
{
    if (!(corner(e, a, b, c) > 0.0))
        return 0;
    const double *u = e->u, *v = e->v;
    double ulo = fmin(u[a], fmin(u[b], u[c])), uhi = fmax(u[a], fmax(u[b], u[c]));
    double vlo = fmin(v[a], fmin(v[b], v[c])), vhi = fmax(v[a], fmax(v[b], v[c]));
    int j0 = cell_of(vlo, e->v0, e->cv, e->gh), j1 = cell_of(vhi, e->v0, e->cv, e->gh);
    const int t[3] = {a, b, c};
    for (int j = j0; j <= j1; j++) {
        /* the cells of this row that the triangle meets: the u-extent of the triangle within the
         * row's strip (its vertices there, and its edges clipped to the strip), padded by a
         * quarter cell against rounding; a diagonal sliver then costs its length in cells, not
         * its bounding box's area */
        double s0 = e->cv > 0.0 ? e->v0 + j / e->cv : -INFINITY, s1 = e->cv > 0.0 ? e->v0 + (j + 1) / e->cv : INFINITY;
        double pad = e->cv > 0.0 ? 0.25 / e->cv : 0.0;
        s0 -= pad, s1 += pad;
        double rlo = INFINITY, rhi = -INFINITY;
        for (int k = 0; k < 3; k++) {
            int p = t[k], q = t[(k + 1) % 3];
            double pv = v[p], qv = v[q], lo = fmax(fmin(pv, qv), s0), hi = fmin(fmax(pv, qv), s1);
            if (lo > hi)
                continue; /* the edge misses the strip */
            if (pv == qv) {
                rlo = fmin(rlo, fmin(u[p], u[q])), rhi = fmax(rhi, fmax(u[p], u[q]));
                continue;
            }
            double slope = (u[q] - u[p]) / (qv - pv), ua = u[p] + (lo - pv) * slope, ub = u[p] + (hi - pv) * slope;
            rlo = fmin(rlo, fmin(ua, ub)), rhi = fmax(rhi, fmax(ua, ub));
        }
        if (rlo > rhi)
            continue;
        double upad = e->cu > 0.0 ? 0.25 / e->cu : 0.0;
        int i0 = cell_of(fmax(rlo - upad, ulo), e->u0, e->cu, e->gw), i1 = cell_of(fmin(rhi + upad, uhi), e->u0, e->cu, e->gw);
        for (int i = i0; i <= i1; i++) {
            int cell = j * e->gw + i;
            for (int k = e->cell_start[cell]; k < e->cell_start[cell + 1]; k++) {
                int q = e->cell_items[k];
                if (!e->blocker[q] || q == a || q == b || q == c)
                    continue;
                if (u[q] < ulo || u[q] > uhi || v[q] < vlo || v[q] > vhi)
                    continue;
                if (corner(e, a, b, q) >= 0.0 && corner(e, b, c, q) >= 0.0 && corner(e, c, a, q) >= 0.0)
                    return 0;
            }
        }
    }
    return 1;
}

static void set_blocker(Ears *e, int k, int on)
{
    e->blockers += on - e->blocker[k];
    e->blocker[k] = (unsigned char)on;
}

int rf_triangulate_polygon_2d(const double *u, const double *v, int n, int *out)
{
    if (n < 3)
        return 0;
    Ears e = {u, v, n, 1.0, NULL, NULL, NULL, 0, 0, 1, 1, 0, 0, 0, 0, NULL, NULL, NULL};
    double area = 0.0;
    for (int k = 0; k < n; k++)
        area += u[k] * v[(k + 1) % n] - u[(k + 1) % n] * v[k];
    e.sgn = area >= 0.0 ? 1.0 : -1.0;
    /* at most 2049^2 cells, and about one per blocker */
    size_t max_cells = (size_t)n + 2 * 2049 + 2;
    e.next = malloc(sizeof *e.next * (size_t)n);
    e.prev = malloc(sizeof *e.prev * (size_t)n);
    e.blocker = calloc((size_t)n, 1);
    e.cell_start = malloc(sizeof *e.cell_start * (max_cells + 1));
    e.cell_items = malloc(sizeof *e.cell_items * (size_t)n);
    e.cell_of_item = malloc(sizeof *e.cell_of_item * (size_t)n);
    int nt = -1;
    if (!e.next || !e.prev || !e.blocker || !e.cell_start || !e.cell_items || !e.cell_of_item)
        goto done;
    for (int k = 0; k < n; k++) {
        e.next[k] = (k + 1) % n;
        e.prev[k] = (k + n - 1) % n;
    }
    for (int k = 0; k < n; k++)
        set_blocker(&e, k, corner(&e, e.prev[k], k, e.next[k]) <= 0.0);
    grid_build(&e);

    nt = 0;
    int m = n, b = 0, misses = 0;
    while (m > 3 && misses < m) {
        int a = e.prev[b], c = e.next[b];
        if (!is_ear(&e, a, b, c)) {
            b = c;
            misses++;
            continue;
        }
        out[3 * nt] = a, out[3 * nt + 1] = b, out[3 * nt + 2] = c, nt++;
        e.next[a] = c, e.prev[c] = a, m--;
        set_blocker(&e, b, 0);
        set_blocker(&e, a, corner(&e, e.prev[a], a, c) <= 0.0);
        set_blocker(&e, c, corner(&e, a, c, e.next[c]) <= 0.0);
        if (2 * e.blockers < e.gridded)
            grid_build(&e);
        b = e.next[c]; /* on past c, as earcut does: cutting every other corner keeps ears small
                          (staying at a would fan around c, with ears as wide as the polygon) */
        misses = 0;
    }
    /* the last triangle, or a fan of what no ear could be cut from (a polygon that is not simple) */
    for (int k = e.next[b], first = b; e.next[k] != first; k = e.next[k])
        out[3 * nt] = first, out[3 * nt + 1] = k, out[3 * nt + 2] = e.next[k], nt++;
done:
    free(e.next), free(e.prev), free(e.blocker), free(e.cell_start), free(e.cell_items), free(e.cell_of_item);
    return nt;
}

int rf_triangulate_polygon(const RfVec3 *v, int n, int *out)
{
    if (n < 3)
        return 0;
    /* in the coordinate plane that drops the largest component of Newell's normal, with the
     * polygon's own orientation: every triangle keeps the polygon's winding (its facing side) */
    RfVec3 nn = rf_vec3(0, 0, 0);
    for (int k = 0; k < n; k++)
        nn = rf_vec3_add(nn, rf_vec3_cross(v[k], v[(k + 1) % n]));
    int drop = fabs(nn.x) > fabs(nn.y) ? (fabs(nn.x) > fabs(nn.z) ? 0 : 2) : (fabs(nn.y) > fabs(nn.z) ? 1 : 2);
    double *u = malloc(sizeof *u * (size_t)n), *w = malloc(sizeof *w * (size_t)n);
    int nt = -1;
    if (u && w) {
        for (int k = 0; k < n; k++) {
            u[k] = drop == 0 ? v[k].y : v[k].x;
            w[k] = drop == 2 ? v[k].y : v[k].z;
        }
        nt = rf_triangulate_polygon_2d(u, w, n, out);
    }
    free(u), free(w);
    return nt;
}
