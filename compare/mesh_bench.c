/* refray-mesh-bench: refray's intersection core against Embree on the very same rays
 * (issue 10, shared/bench/SCENES.md §1 "mesh"). Both sides get the triangles of one scene
 * loaded by refray's reader, the primary rays of its camera (one through each pixel centre) and
 * the shadow rays refray's renderer shoots: from every primary hit whose geometric normal
 * (facing the ray) sees the light, from the hit point moved off the surface by refray's offset
 * policy, to the light. refray answers with rf_tracer_intersect / rf_tracer_occluded (double
 * precision, watertight), Embree 3 with rtcIntersect1 / rtcOccluded1 (single rays, float). The
 * primary rays also go four at a time, four neighbouring pixels of a row as refray's renderer
 * groups them at one sample: rf_tracer_intersect4 against Embree's rtcIntersect4 (each packet
 * API against the other; refray's answers are checked against its single rays).
 * Times: the BVH build (the scene commit for Embree) and each ray pass, with 1 and 2 threads,
 * medians of --runs runs; the ratios are refray's throughput over Embree's (above 1: refray is
 * faster) and Embree's build time over refray's. Without Embree (built only when Debian's
 * libembree-dev is installed) refray's side is measured alone.
 *
 * refray's offset (2e-15 of the hit point's coordinates) puts a shadow ray's origin closer to its
 * surface than float arithmetic resolves: Embree reports many of those rays occluded by their
 * own triangle, and stops early. A second set of shadow rays starts at P + 1e-4 N, as the
 * SCENES.md anchor does, where both agree; both sets are timed. Memory: the scene model and
 * the tracer per triangle, and the peak growth of the process while building.
 *
 * usage: refray-mesh-bench SCENE [--runs N] [--threads LIST] */
#include <math.h>
#include <sys/resource.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "refray/camera.h"
#include "refray/parallel.h"
#include "refray/render.h"
#include "refray/scene_io.h"

#ifdef RF_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static long peak_kb(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct {
    RfRay *rays;
    double *t_max;  /* shadow rays: the distance to the light (exclusive) */
    int count;
    int *answer;    /* primary: primitive hit or -1; shadow: 1 occluded */
} RaySet;

/* ---- refray ------------------------------------------------------------------------------- */

enum { CHUNKS = 256 };

/* The first ray of chunk c of a ray set (c = CHUNKS: its end). */
static int chunk_start(const RaySet *set, int c) { return (int)((long long)set->count * c / CHUNKS); }

/* The median over `runs` passes of fn over the chunks of a ray set (times: room for runs). */
static double timed_passes(int runs, int threads, RfTaskFn fn, void *job, double *times)
{
    for (int r = 0; r < runs; r++) {
        double s = now();
        rf_parallel_for(CHUNKS, threads, fn, NULL, job);
        times[r] = now() - s;
    }
    return median(times, runs);
}

typedef struct {
    const RfTracer *tracer;
    const RaySet *set;
    RfSurfaceHit *hits; /* primary only */
} RefrayJob;

static int refray_primary(void *ctx, int chunk, int thread)
{
    RefrayJob *j = ctx;
    int lo = chunk_start(j->set, chunk), hi = chunk_start(j->set, chunk + 1);
    (void)thread;
    for (int i = lo; i < hi; i++)
        j->set->answer[i] = rf_tracer_intersect(j->tracer, &j->set->rays[i], 0.0, HUGE_VAL, &j->hits[i]);
    return 0;
}

/* the chunk's primary rays in groups of four consecutive ones (a short group at its end) */
static int refray_primary4(void *ctx, int chunk, int thread)
{
    RefrayJob *j = ctx;
    int lo = chunk_start(j->set, chunk), hi = chunk_start(j->set, chunk + 1);
    const double t_min[4] = {0.0, 0.0, 0.0, 0.0};
    (void)thread;
    for (int i = lo; i < hi; i += 4) {
        int n = hi - i < 4 ? hi - i : 4;
        unsigned hit = rf_tracer_intersect4(j->tracer, &j->set->rays[i], (1u << n) - 1, t_min, &j->hits[i]);
        for (int l = 0; l < n; l++)
            j->set->answer[i + l] = (hit >> l) & 1 ? j->hits[i + l].prim : -1;
    }
    return 0;
}

static int refray_shadow(void *ctx, int chunk, int thread)
{
    RefrayJob *j = ctx;
    int lo = chunk_start(j->set, chunk), hi = chunk_start(j->set, chunk + 1);
    (void)thread;
    for (int i = lo; i < hi; i++)
        j->set->answer[i] = rf_tracer_occluded(j->tracer, &j->set->rays[i], 0.0, j->set->t_max[i]);
    return 0;
}

/* ---- Embree ------------------------------------------------------------------------------- */

#ifdef RF_HAVE_EMBREE
typedef struct {
    RTCScene scene;
    const RaySet *set;
} EmbreeJob;

static struct RTCRay embree_ray(const RfRay *r, float tfar)
{
    struct RTCRay ray;
    ray.org_x = (float)r->origin.x;
    ray.org_y = (float)r->origin.y;
    ray.org_z = (float)r->origin.z;
    ray.dir_x = (float)r->dir.x;
    ray.dir_y = (float)r->dir.y;
    ray.dir_z = (float)r->dir.z;
    ray.tnear = 0.0f;
    ray.tfar = tfar;
    ray.mask = ~0u;
    ray.flags = 0;
    ray.time = 0.0f;
    return ray;
}

static int embree_primary(void *ctx, int chunk, int thread)
{
    EmbreeJob *j = ctx;
    int lo = chunk_start(j->set, chunk), hi = chunk_start(j->set, chunk + 1);
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    (void)thread;
    for (int i = lo; i < hi; i++) {
        struct RTCRayHit rh;
        rh.ray = embree_ray(&j->set->rays[i], INFINITY);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(j->scene, &ic, &rh);
        j->set->answer[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : (int)rh.hit.primID;
    }
    return 0;
}

/* the same groups through rtcIntersect4 (an idle lane is marked invalid) */
static int embree_primary4(void *ctx, int chunk, int thread)
{
    EmbreeJob *j = ctx;
    int lo = chunk_start(j->set, chunk), hi = chunk_start(j->set, chunk + 1);
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    (void)thread;
    for (int i = lo; i < hi; i += 4) {
        int n = hi - i < 4 ? hi - i : 4, valid[4];
        struct RTCRayHit4 rh;
        for (int l = 0; l < 4; l++) {
            struct RTCRay one = embree_ray(&j->set->rays[i + (l < n ? l : 0)], INFINITY);
            valid[l] = l < n ? -1 : 0;
            rh.ray.org_x[l] = one.org_x, rh.ray.org_y[l] = one.org_y, rh.ray.org_z[l] = one.org_z;
            rh.ray.dir_x[l] = one.dir_x, rh.ray.dir_y[l] = one.dir_y, rh.ray.dir_z[l] = one.dir_z;
            rh.ray.tnear[l] = one.tnear, rh.ray.tfar[l] = one.tfar, rh.ray.time[l] = one.time;
            rh.ray.mask[l] = one.mask, rh.ray.id[l] = (unsigned)l, rh.ray.flags[l] = one.flags;
            rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect4(valid, j->scene, &ic, &rh);
        for (int l = 0; l < n; l++)
            j->set->answer[i + l] = rh.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID ? -1 : (int)rh.hit.primID[l];
    }
    return 0;
}

static int embree_shadow(void *ctx, int chunk, int thread)
{
    EmbreeJob *j = ctx;
    int lo = chunk_start(j->set, chunk), hi = chunk_start(j->set, chunk + 1);
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    (void)thread;
    for (int i = lo; i < hi; i++) {
        struct RTCRay ray = embree_ray(&j->set->rays[i], (float)j->set->t_max[i]);
        rtcOccluded1(j->scene, &ic, &ray);
        j->set->answer[i] = ray.tfar < 0.0f;
    }
    return 0;
}

/* The scene's triangles as one Embree mesh (vertices rounded to float); a scene of anything
 * but triangles and convex polygons (fanned) is refused. */
static int embree_mesh(const RfScene *sc, float **verts, unsigned **idx, int *nv, int *nt)
{
    size_t tris = 0;
    for (size_t i = 0; i < sc->prim_count; i++) {
        const RfPrimitive *p = &sc->prims[i];
        if ((p->type != RF_PRIM_TRIANGLE && p->type != RF_PRIM_POLYGON) || (p->flags & RF_PRIM_NONCONVEX) ||
            (p->flags & RF_PRIM_IN_OBJECT))
            return 0;
        tris += (size_t)p->u.poly.count - 2;
    }
    *verts = malloc(sizeof **verts * 3 * (sc->vertex_count + 1));
    *idx = malloc(sizeof **idx * 3 * (tris + 1));
    if (!*verts || !*idx)
        return 0;
    for (size_t v = 0; v < sc->vertex_count; v++) {
        (*verts)[3 * v] = (float)sc->vertices[v].x;
        (*verts)[3 * v + 1] = (float)sc->vertices[v].y;
        (*verts)[3 * v + 2] = (float)sc->vertices[v].z;
    }
    size_t t = 0;
    for (size_t i = 0; i < sc->prim_count; i++) {
        const RfPrimitive *p = &sc->prims[i];
        for (int k = 0; k + 2 < p->u.poly.count; k++, t++) {
            (*idx)[3 * t] = (unsigned)p->u.poly.first;
            (*idx)[3 * t + 1] = (unsigned)(p->u.poly.first + (size_t)k + 1);
            (*idx)[3 * t + 2] = (unsigned)(p->u.poly.first + (size_t)k + 2);
        }
    }
    *nv = (int)sc->vertex_count;
    *nt = (int)tris;
    return 1;
}
#endif

/* ---- the benchmark ------------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    const char *path = NULL;
    int runs = 5, thread_list[8] = {1, 2}, n_threads = 2;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
            runs = atoi(argv[++i]);
        } else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
            n_threads = 0;
            for (char *s = argv[++i]; *s && n_threads < 8;) {
                thread_list[n_threads++] = (int)strtol(s, &s, 10);
                if (*s == ',')
                    s++;
                else
                    break;
            }
        } else if (argv[i][0] != '-' && !path) {
            path = argv[i];
        } else {
            fprintf(stderr, "usage: refray-mesh-bench SCENE [--runs N] [--threads 1,2]\n");
            return 2;
        }
    }
    if (!path || runs < 1 || runs > 100 || n_threads < 1) {
        fprintf(stderr, "usage: refray-mesh-bench SCENE [--runs N] [--threads 1,2]\n");
        return 2;
    }
    for (int k = 0; k < n_threads; k++)
        if (thread_list[k] < 1 || thread_list[k] > 256) {
            fprintf(stderr, "refray-mesh-bench: thread counts must be in 1..256\n");
            return 2;
        }
    char err[1024];
    RfScene sc;
    double t0 = now();
    if (rf_scene_load(path, NULL, &sc, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    double load = now() - t0;
    if (sc.light_count != 1 || sc.lights[0].kind != RF_LIGHT_POINT) {
        fprintf(stderr, "refray-mesh-bench: %s: the benchmark needs exactly one point light\n", path);
        rf_scene_free(&sc);
        return 1;
    }
    /* the rays: primary through the pixel centres, as rf_render shoots them (hither 0) */
    int w = sc.render.width, h = sc.render.height;
    RfCamera cam;
    RfWindow win = rf_scene_camera_window(&sc.camera, w, h);
    rf_camera_init(&cam, sc.camera.eye, sc.camera.target, sc.camera.up, win.d, win.l, win.r, win.b, win.t, w, h);
    RaySet prim = {malloc(sizeof(RfRay) * (size_t)w * h), NULL, w * h, malloc(sizeof(int) * (size_t)w * h)};
    RfSurfaceHit *hits = malloc(sizeof *hits * (size_t)w * h);
    if (!prim.rays || !prim.answer || !hits) {
        fprintf(stderr, "refray-mesh-bench: out of memory\n");
        return 1;
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            prim.rays[(size_t)y * w + x] = rf_camera_ray(&cam, x + 0.5, y + 0.5, 0.0, 0.0);

    printf("refray-mesh-bench: %s, %zu primitives, %dx%d primary rays, medians of %d runs\n", path,
           sc.prim_count, w, h, runs);
    printf("load (refray's reader): %.3f s\n\n", load);
    printf("%-24s %8s %12s %12s %8s\n", "step", "threads", "refray", "Embree", "ratio");
    RaySet shadow = {NULL, NULL, 0, NULL}, shadow4 = {NULL, NULL, 0, NULL};
    int hits_refray = 0, occluded_refray = 0, occluded4_refray = 0;
    long rss_loaded = peak_kb(), rss_built = 0;
    size_t tracer_bytes = 0;
    double *times = malloc(sizeof *times * (size_t)runs);
    for (int k = 0; k < n_threads; k++) {
        int th = thread_list[k];
        RfTracerOptions topt = rf_tracer_options_default();
        topt.threads = th;
        RfTracer *tr = NULL;
        for (int r = 0; r < runs; r++) {
            rf_tracer_free(tr);
            tr = NULL;
            double s = now();
            if (rf_tracer_create_opts(&sc, &topt, &tr) != RF_OK) {
                fprintf(stderr, "refray-mesh-bench: building the tracer failed\n");
                return 1;
            }
            times[r] = now() - s;
            if (!rss_built) {
                rss_built = peak_kb();
                tracer_bytes = rf_tracer_bytes(tr);
            }
        }
        double rf_build = median(times, runs);
        RefrayJob rj = {tr, &prim, hits};
        double rf_prim = timed_passes(runs, th, refray_primary, &rj, times);
        /* groups of four: the same answers as the single rays, checked */
        int *single = malloc(sizeof(int) * (size_t)prim.count);
        if (!single) {
            fprintf(stderr, "refray-mesh-bench: out of memory\n");
            return 1;
        }
        memcpy(single, prim.answer, sizeof(int) * (size_t)prim.count);
        double rf_prim4 = timed_passes(runs, th, refray_primary4, &rj, times);
        if (memcmp(single, prim.answer, sizeof(int) * (size_t)prim.count) != 0) {
            fprintf(stderr, "refray-mesh-bench: rf_tracer_intersect4 disagrees with rf_tracer_intersect\n");
            return 1;
        }
        free(single);
        if (!shadow.rays) { /* the shadow rays of the renderer, from refray's hits */
            RaySet *set[2] = {&shadow, &shadow4};
            for (int k2 = 0; k2 < 2; k2++) {
                set[k2]->rays = malloc(sizeof(RfRay) * (size_t)w * h);
                set[k2]->t_max = malloc(sizeof(double) * (size_t)w * h);
                set[k2]->answer = malloc(sizeof(int) * (size_t)w * h);
            }
            RfVec3 lp = sc.lights[0].position;
            for (int i = 0; i < prim.count; i++) {
                if (prim.answer[i] < 0)
                    continue;
                hits_refray++;
                RfVec3 l = rf_vec3_sub(lp, hits[i].point);
                double dist = rf_vec3_length(l);
                l = rf_vec3_scale(l, 1.0 / dist);
                if (rf_vec3_dot(hits[i].normal, l) <= 0.0)
                    continue;
                for (int k2 = 0; k2 < 2; k2++) {
                    RfRay sr = rf_ray(rf_hit_offset_origin(&hits[i], l, k2 ? 1e-4 : 0.0), l);
                    set[k2]->rays[set[k2]->count] = sr;
                    set[k2]->t_max[set[k2]->count++] = rf_vec3_length(rf_vec3_sub(lp, sr.origin));
                }
            }
        }
        double rf_shadow = 0, rf_shadow4 = 0;
        for (int k2 = 0; k2 < 2; k2++) {
            RefrayJob sj = {tr, k2 ? &shadow4 : &shadow, NULL};
            *(k2 ? &rf_shadow4 : &rf_shadow) = timed_passes(runs, th, refray_shadow, &sj, times);
        }
        occluded_refray = occluded4_refray = 0;
        for (int i = 0; i < shadow.count; i++) {
            occluded_refray += shadow.answer[i];
            occluded4_refray += shadow4.answer[i];
        }
        rf_tracer_free(tr);
        double em_build = NAN, em_prim = NAN, em_prim4 = NAN, em_shadow = NAN, em_shadow4 = NAN;
        int hits_embree = -1, hits4_embree = -1, occluded_embree = -1, occluded4_embree = -1;
#ifdef RF_HAVE_EMBREE
        {
            char cfg[64];
            snprintf(cfg, sizeof cfg, "threads=%d", th);
            RTCDevice dev = rtcNewDevice(cfg);
            float *verts = NULL;
            unsigned *idx = NULL;
            int nv = 0, nt = 0;
            if (!dev || !embree_mesh(&sc, &verts, &idx, &nv, &nt)) {
                fprintf(stderr, "refray-mesh-bench: Embree cannot take this scene (triangles only)\n");
                return 1;
            }
            RTCScene scene = NULL;
            for (int r = 0; r < runs; r++) {
                if (scene)
                    rtcReleaseScene(scene);
                double s = now();
                scene = rtcNewScene(dev);
                RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
                rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, verts, 0,
                                           3 * sizeof(float), (size_t)nv);
                rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, idx, 0,
                                           3 * sizeof(unsigned), (size_t)nt);
                rtcCommitGeometry(g);
                rtcAttachGeometry(scene, g);
                rtcReleaseGeometry(g);
                rtcCommitScene(scene);
                times[r] = now() - s;
            }
            em_build = median(times, runs);
            RaySet eprim = prim, eshadow = shadow, eshadow4 = shadow4;
            eprim.answer = malloc(sizeof(int) * (size_t)prim.count);
            eshadow.answer = malloc(sizeof(int) * (size_t)(shadow.count + 1));
            eshadow4.answer = malloc(sizeof(int) * (size_t)(shadow.count + 1));
            EmbreeJob ej = {scene, &eprim}, es = {scene, &eshadow}, es4 = {scene, &eshadow4};
            em_prim = timed_passes(runs, th, embree_primary, &ej, times);
            hits_embree = 0;
            for (int i = 0; i < prim.count; i++)
                hits_embree += eprim.answer[i] >= 0;
            em_prim4 = timed_passes(runs, th, embree_primary4, &ej, times);
            hits4_embree = 0;
            for (int i = 0; i < prim.count; i++)
                hits4_embree += eprim.answer[i] >= 0;
            em_shadow = timed_passes(runs, th, embree_shadow, &es, times);
            em_shadow4 = timed_passes(runs, th, embree_shadow, &es4, times);
            occluded_embree = occluded4_embree = 0;
            for (int i = 0; i < shadow.count; i++) {
                occluded_embree += eshadow.answer[i];
                occluded4_embree += eshadow4.answer[i];
            }
            free(eprim.answer);
            free(eshadow.answer);
            free(eshadow4.answer);
            rtcReleaseScene(scene);
            rtcReleaseDevice(dev);
            free(verts);
            free(idx);
        }
#endif
        printf("%-24s %8d %10.3f s %10.3f s %7.2fx\n", "build", th, rf_build, em_build, em_build / rf_build);
        printf("%-24s %8d %8.2f M/s %8.2f M/s %7.2fx\n", "primary rays", th, prim.count / rf_prim * 1e-6,
               prim.count / em_prim * 1e-6, em_prim / rf_prim);
        printf("%-24s %8d %8.2f M/s %8.2f M/s %7.2fx\n", "primary, groups of 4", th, prim.count / rf_prim4 * 1e-6,
               prim.count / em_prim4 * 1e-6, em_prim4 / rf_prim4);
        printf("%-24s %8d %8.2f M/s %8.2f M/s %7.2fx\n", "shadow rays", th, shadow.count / rf_shadow * 1e-6,
               shadow.count / em_shadow * 1e-6, em_shadow / rf_shadow);
        printf("%-24s %8d %8.2f M/s %8.2f M/s %7.2fx\n", "shadow rays, 1e-4 offset", th,
               shadow4.count / rf_shadow4 * 1e-6, shadow4.count / em_shadow4 * 1e-6, em_shadow4 / rf_shadow4);
        printf("%-24s %8d %8.2f M/s %8.2f M/s %7.2fx\n", "primary + shadow", th,
               (prim.count + shadow.count) / (rf_prim + rf_shadow) * 1e-6,
               (prim.count + shadow.count) / (em_prim + em_shadow) * 1e-6, (em_prim + em_shadow) / (rf_prim + rf_shadow));
        if (k == n_threads - 1) {
            printf("\nrays: %d primary (refray hits %d", prim.count, hits_refray);
            if (hits_embree >= 0)
                printf(", Embree %d, in groups of 4 %d", hits_embree, hits4_embree);
            printf("), %d shadow (refray occluded %d", shadow.count, occluded_refray);
            if (occluded_embree >= 0)
                printf(", Embree %d", occluded_embree);
            printf("; with the 1e-4 offset refray %d", occluded4_refray);
            if (occluded4_embree >= 0)
                printf(", Embree %d", occluded4_embree);
            printf(")\n");
            size_t tris = (size_t)rf_scene_triangle_count(&sc).rendered;
            size_t scene_bytes = sizeof(RfPrimitive) * sc.prim_count + sizeof(RfVec3) * (sc.vertex_count + sc.normal_count);
            printf("memory per triangle: scene model %.0f B, tracer %.0f B (BVH nodes, triangle blocks with float and\n"
                   "double vertices), peak growth while building %.0f B\n",
                   (double)scene_bytes / tris, (double)tracer_bytes / tris, (rss_built - rss_loaded) * 1024.0 / tris);
        }
    }
#ifndef RF_HAVE_EMBREE
    printf("\n(Embree is not installed: apt-get install libembree-dev, then make bench, adds its column)\n");
#endif
    printf("ratio: refray's speed over Embree's (above 1: refray faster); reproduce: %s %s --runs %d\n", argv[0], path, runs);
    free(times);
    free(prim.rays);
    free(prim.answer);
    free(hits);
    free(shadow.rays);
    free(shadow.t_max);
    free(shadow.answer);
    free(shadow4.rays);
    free(shadow4.t_max);
    free(shadow4.answer);
    rf_scene_free(&sc);
    return 0;
}
