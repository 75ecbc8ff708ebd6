/* One render kernel: the shading of §3.6-3.8, the distributed ray tracing of §3.10 and the
 * pixel loops of §3.9, compiled with RF_KPARTS (a set of RF_K_*) fixed, so that the compiler
 * drops every part the set leaves out. kernels.c includes this file once per kernel, with
 * RF_KPARTS and RF_KNAME defined. Not a header of its own: no include guard.
 *
 * Each part left out is one that could only have added nothing: a light kind that no light has,
 * a term whose coefficients are all zero, the recursion of a scene that neither reflects nor
 * transmits. Only the sign of a zero can differ on the way (x + 0 for x = -0), and the pixel sum,
 * which starts at +0, erases it, so every kernel writes the general kernel's image bit for bit
 * (tests/test_kernels.c renders every shipped scene both ways). */

#define RF_ON(part) ((RF_KPARTS & (part)) != 0)
/* refray trace's events come from the general kernel only (rf_render picks it for a trace), so
 * the specialised kernels carry no trace code at all */
#ifndef RF_TRACE_ON
#define RF_TRACE_ON(ps) (RF_KPARTS == RF_K_ALL && (ps)->log && (ps)->log->trace)
#define RF_TRACE_ON_JOB(job) (RF_KPARTS == RF_K_ALL && (job)->trace_log && (job)->trace_log->trace)
#endif

static RfRgb RF_KNAME(trace)(const RfKernelJob *job, const RfRay *ray, double t_min, int depth, double weight,
                             RfRenderStats *st, uint64_t *shadow_cache, const RfPathSample *ps);

/* One light sample's §3.6.2 Phong term at the hit: the shadow ray to the light (§3.8; opaque
 * shadows, or filtered by the kt of the surfaces it crosses) and the diffuse and specular terms.
 * 0 when the light does not reach the point. */
static inline int RF_KNAME(light_term)(const RfKernelJob *job, const RfSurfaceHit *h, const RfMaterial *m,
                                       RfVec3 n, RfVec3 v, const RfLightSample *ls, RfRenderStats *st,
                                       uint64_t *cache, const RfPathSample *ps, int li, int j, int depth, RfRgb *term)
{
    RfTraceEvent ev; /* refray trace only */
    if (RF_TRACE_ON(ps)) {
        memset(&ev, 0, sizeof ev);
        ev.kind = RF_TRACE_LIGHT, ev.depth = depth, ev.sample = (int)ps->k, ev.samples = (int)ps->n;
        ev.light = li, ev.light_sample = j, ev.l = ls->l, ev.distance = ls->distance, ev.intensity = ls->i;
        ev.n_dot_l = rf_vec3_dot(n, ls->l), ev.visible = -1, ev.transmittance = rf_rgb(1, 1, 1);
    }
    RfLightSample through; /* filtered shadows: the light that comes through */
    if (rf_kernel_rgb_max(ls->i) <= 0.0)
        return 0;
    if (rf_vec3_dot(h->normal, ls->l) <= 0.0) { /* the light is behind the surface */
        if (RF_TRACE_ON(ps))
            ps->log->trace(ps->log->trace_ctx, &ev);
        return 0;
    }
    if (RF_ON(RF_K_SHADOW) && !job->local_only) {
        RfRay sr = rf_ray(rf_hit_offset_origin(h, ls->l, job->fixed_offset), ls->l);
        double dist = isinf(ls->distance) ? HUGE_VAL
                                          : rf_vec3_length(rf_vec3_sub(rf_vec3_add(h->point,
                                                rf_vec3_scale(ls->l, ls->distance)), sr.origin));
        st->shadow_rays++;
        if (job->filtered_shadows) { /* the light through the transmitting surfaces on the way */
            RfRgb tr = rf_tracer_transmittance_at(job->tracer, &sr, RF_ON(RF_K_MOTION) ? ps->motion : NULL, 0.0,
                                                  dist, cache);
            if (RF_TRACE_ON(ps))
                ev.transmittance = tr;
            if (!(rf_kernel_rgb_max(tr) > 0.0)) {
                if (RF_TRACE_ON(ps)) {
                    ev.visible = 0;
                    ps->log->trace(ps->log->trace_ctx, &ev);
                }
                return 0;
            }
            through = *ls;
            through.i = rf_rgb_mul(ls->i, tr);
            ls = &through;
        } else if (RF_ON(RF_K_MOTION) ? rf_tracer_occluded_cached_at(job->tracer, &sr, ps->motion, 0.0, dist, cache)
                                      : rf_tracer_occluded_cached(job->tracer, &sr, 0.0, dist, cache)) {
            if (RF_TRACE_ON(ps)) {
                ev.visible = 0, ev.transmittance = rf_rgb(0, 0, 0);
                ps->log->trace(ps->log->trace_ctx, &ev);
            }
            return 0;
        }
    }
    /* §3.6.2 Phong, as rf_phong: only positive scalar products contribute */
    double nl = rf_vec3_dot(n, ls->l);
    double diff = nl > 0.0 ? nl : 0.0;
    RfRgb diffuse = rf_rgb_scale(rf_rgb_mul(m->kd, ls->i), diff);
    if (RF_ON(RF_K_SPECULAR)) {
        /* without a highlight (ks = 0) the power would only multiply a zero */
        double rv = job->highlight[h->material] ? rf_vec3_dot(rf_reflect(n, ls->l), v) : 0.0;
        double spec = nl > 0.0 && rv > 0.0 ? pow(rv, m->shininess) : 0.0;
        RfRgb specular = rf_rgb_scale(rf_rgb_mul(m->ks, ls->i), spec);
        *term = rf_rgb_add(diffuse, specular);
        if (RF_TRACE_ON(ps))
            ev.specular = specular;
    } else {
        *term = diffuse;
    }
    if (RF_TRACE_ON(ps)) {
        ev.visible = 1, ev.diffuse = diffuse;
        ps->log->trace(ps->log->trace_ctx, &ev);
    }
    return 1;
}

/* §3.10 soft shadows: the area light's point for uv seen from the hit x (uv: sample j of the
 * light's dimension, rf_kernel_dim, stratified over the light with the camera sample's index).
 * Fills ls as a point light at the sampled point (an element dA seen under theta_l acts as
 * intensity Le cos(theta_l) dA, scene.h), already divided by the number of samples; 0 when the
 * sample sees the light's back or lies inside. */
static inline int RF_KNAME(area_sample)(const RfKernelLight *l, RfVec3 x, const double uv[2], RfLightSample *ls)
{
    if (l->kind == RF_LIGHT_SPHERE) {
        /* uniform in the cone of directions the sphere covers (solid-angle sampling) */
        RfVec3 to = rf_vec3_sub(l->position, x);
        double dc = rf_vec3_length(to);
        if (!(dc > l->radius))
            return 0; /* inside the light */
        double s2 = (l->radius / dc) * (l->radius / dc), cos_max = sqrt(1.0 - s2);
        double solid = 2.0 * RF_PI * (s2 / (1.0 + cos_max)); /* 2 pi (1 - cos_max), no cancellation */
        RfFrame f = rf_frame(rf_vec3_scale(to, 1.0 / dc));
        RfVec3 dir = rf_frame_to_world(&f, rf_warp_cone(uv[0], uv[1], cos_max));
        RfHit hit;
        RfSphere sph = {l->position, l->radius};
        if (!rf_intersect_sphere(rf_ray(x, dir), sph, RF_SPHERE_STABLE, 0.0, HUGE_VAL, &hit))
            return 0; /* a grazing direction that rounding put just outside */
        ls->l = dir;
        ls->distance = hit.t;
        ls->i = rf_rgb_scale(l->intensity, solid / l->samples);
        return 1;
    }
    RfVec3 y;
    if (l->kind == RF_LIGHT_RECT) {
        y = rf_vec3_add(l->position, rf_vec3_add(rf_vec3_scale(l->edge1, uv[0]), rf_vec3_scale(l->edge2, uv[1])));
    } else { /* disc: the concentric map keeps the strata compact */
        double dx, dy;
        rf_warp_disk(uv[0], uv[1], &dx, &dy);
        RfFrame f = rf_frame(l->direction);
        y = rf_vec3_add(l->position, rf_frame_to_world(&f, rf_vec3(l->radius * dx, l->radius * dy, 0.0)));
    }
    RfVec3 d = rf_vec3_sub(y, x);
    double d2 = rf_vec3_dot(d, d), dist = sqrt(d2);
    if (!(dist > 0.0))
        return 0;
    ls->l = rf_vec3_scale(d, 1.0 / dist);
    double cos_l = -rf_vec3_dot(l->direction, ls->l);
    if (l->two_sided)
        cos_l = fabs(cos_l);
    if (!(cos_l > 0.0))
        return 0; /* the light's back */
    ls->distance = dist;
    ls->i = rf_rgb_scale(l->intensity, cos_l * l->area / (l->samples * d2));
    return 1;
}

/* §3.10 glossy rays: the ideal direction perturbed within the lobe cos^gloss around it. 0 when
 * the perturbed direction leaves by the wrong side (then the ray carries nothing). */
static inline int RF_KNAME(glossy)(const RfKernelJob *job, RfVec3 *dir, double gloss, RfVec3 normal, int out_side,
                                   int slot, int depth, const RfPathSample *ps)
{
    double uv[2];
    rf_sample_2d(ps->sampler, ps->k, ps->n, ps->pixel, rf_kernel_dim(depth, slot), job->seed, uv);
    RfFrame f = rf_frame(*dir);
    *dir = rf_frame_to_world(&f, rf_warp_cos_power(uv[0], uv[1], gloss));
    double side = rf_vec3_dot(*dir, normal);
    return out_side ? side > 0.0 : side < 0.0;
}

/* color plus the weighted colour of a mirror (refracted = 0) or refracted ray leaving the hit
 * in dir, perturbed within the lobe cos^gloss first when gloss > 0 (§3.10). */
static RfRgb RF_KNAME(secondary)(const RfKernelJob *job, const RfSurfaceHit *h, RfVec3 dir, RfRgb w, double wmax,
                                 int refracted, double gloss, int depth, double weight, RfRenderStats *st,
                                 uint64_t *shadow_cache, const RfPathSample *ps, RfRgb color)
{
    if (gloss > 0.0 && !RF_KNAME(glossy)(job, &dir, gloss, h->normal, !refracted, refracted, depth, ps))
        return color;
    RfRay ray = rf_ray(rf_hit_offset_origin(h, dir, job->fixed_offset), dir);
    st->secondary_rays++;
    if (ps->log)
        rf_kernel_log(ps->log, " -> %s ray (depth %d)", refracted ? "refracted" : "mirror", depth + 1);
    return rf_rgb_add(color, rf_rgb_mul(w, RF_KNAME(trace)(job, &ray, 0.0, depth + 1, weight * wmax, st, shadow_cache, ps)));
}

/* refray trace: reports the colour a ray returns (and its local part); returns it */
static inline RfRgb RF_KNAME(traced)(const RfPathSample *ps, int depth, RfRgb local, RfRgb color)
{
    if (RF_TRACE_ON(ps)) {
        RfTraceEvent ev;
        memset(&ev, 0, sizeof ev);
        ev.kind = RF_TRACE_RESULT, ev.depth = depth, ev.sample = (int)ps->k, ev.samples = (int)ps->n;
        ev.local = local, ev.color = color;
        ps->log->trace(ps->log->trace_ctx, &ev);
    }
    return color;
}

/* A ray that meets nothing: the background. */
static inline RfRgb RF_KNAME(missed)(const RfKernelJob *job, int depth, const RfPathSample *ps)
{
    if (ps->log)
        rf_kernel_log(ps->log, " -> nothing (background)");
    if (RF_TRACE_ON(ps)) {
        RfTraceEvent ev;
        memset(&ev, 0, sizeof ev);
        ev.kind = RF_TRACE_MISS, ev.depth = depth, ev.sample = (int)ps->k, ev.samples = (int)ps->n;
        ev.color = job->background;
        ps->log->trace(ps->log->trace_ctx, &ev);
    }
    return job->background;
}

/* The colour a ray returns from its nearest hit h (depth 1 is the primary ray, weight the
 * product of the reflection/transmission weights on the way here). */
static RfRgb RF_KNAME(shade)(const RfKernelJob *job, const RfRay *ray, const RfSurfaceHit *h, int depth,
                             double weight, RfRenderStats *st, uint64_t *shadow_cache, const RfPathSample *ps)
{
    if (ps->log)
        rf_kernel_log_hit(ps->log, job->scene, h);
    if (RF_TRACE_ON(ps)) {
        RfTraceEvent ev;
        memset(&ev, 0, sizeof ev);
        ev.kind = RF_TRACE_HIT, ev.depth = depth, ev.sample = (int)ps->k, ev.samples = (int)ps->n, ev.hit = h;
        ps->log->trace(ps->log->trace_ctx, &ev);
    }
    const RfMaterial *m = &job->materials[h->material];
    RfVec3 v = rf_vec3_neg(rf_vec3_normalize(ray->dir));
    RfVec3 n = h->shading_normal;
    /* §3.6.2: emission + ka I_a + the sum over the lights of the diffuse and specular terms */
    RfRgb color = rf_rgb(0, 0, 0);
    if (RF_ON(RF_K_EMISSION) && RF_ON(RF_K_AMBIENT))
        color = rf_rgb_add(m->emission, rf_rgb_mul(m->ka, job->ambient));
    else if (RF_ON(RF_K_EMISSION))
        color = m->emission;
    else if (RF_ON(RF_K_AMBIENT))
        color = rf_rgb_mul(m->ka, job->ambient);
    for (int li = 0; li < job->light_count; li++) {
        const RfKernelLight *l = &job->lights[li];
        RfLightSample ls;
        RfRgb term;
        if (RF_ON(RF_K_AREA) && l->samples > 0) { /* an area light: its samples, drawn a run at a time */
            RfSampleKeys keys = rf_sample_keys(ps->sampler, ps->pixel, rf_kernel_dim(depth, 2 + li), job->seed);
            uint32_t ns = (uint32_t)l->samples;
            double uv[RF_SAMPLE_RUN][2];
            for (uint32_t j0 = 0; j0 < ns; j0 += RF_SAMPLE_RUN) {
                uint32_t run = ns - j0 < RF_SAMPLE_RUN ? ns - j0 : RF_SAMPLE_RUN;
                rf_sample_2d_keyed_run(&keys, ps->k * ns + j0, run, ps->n * ns, uv);
                for (uint32_t j = 0; j < run; j++)
                    if (RF_KNAME(area_sample)(l, h->point, uv[j], &ls) &&
                        RF_KNAME(light_term)(job, h, m, n, v, &ls, st, &shadow_cache[li], ps, li, (int)(j0 + j),
                                             depth, &term))
                        color = rf_rgb_add(color, term);
            }
            continue;
        }
        if (RF_ON(RF_K_DIRECTIONAL) && l->kind == RF_LIGHT_DIRECTIONAL) {
            ls = rf_light_directional(l->intensity, l->direction);
        } else if (RF_ON(RF_K_SPOT) && l->kind == RF_LIGHT_SPOT) {
            if (rf_light_spot(l->intensity, l->position, l->direction, l->spot_exponent, l->spot_cutoff_rad,
                              l->falloff, h->point, &ls) != RF_OK)
                continue;
        } else { /* §3.7 point light, as rf_light_point */
            RfVec3 to = rf_vec3_sub(l->position, h->point);
            double d = rf_vec3_length(to);
            if (!(d > 0.0) || !isfinite(d))
                continue;
            ls.l = rf_vec3_scale(to, 1.0 / d);
            ls.distance = d;
            ls.i = RF_ON(RF_K_FALLOFF) && l->falloff == RF_FALLOFF_INVERSE_SQUARE
                       ? rf_rgb_scale(l->intensity, 1.0 / (d * d))
                       : l->intensity;
        }
        if (RF_KNAME(light_term)(job, h, m, n, v, &ls, st, &shadow_cache[li], ps, li, -1, depth, &term))
            color = rf_rgb_add(color, term);
    }
    RfRgb local = color; /* for the trace */
    if (!RF_ON(RF_K_SECONDARY) || job->local_only || depth >= job->max_depth)
        return RF_KNAME(traced)(ps, depth, local, color);
    RfRgb kr = m->kr, kt = m->kt, zero = rf_rgb(0, 0, 0);
    int reflects = rf_kernel_rgb_max(kr) > 0.0, transmits = rf_kernel_rgb_max(kt) > 0.0;
    if (!reflects && !transmits)
        return RF_KNAME(traced)(ps, depth, local, color);
    /* §3.8.1: entering through the front (outside) goes from air (1) into the material */
    double eta_i = h->front ? 1.0 : m->ior, eta_t = h->front ? m->ior : 1.0;
    double vn = rf_vec3_dot(v, n);
    double cos_i = vn > 0.0 ? (vn < 1.0 ? vn : 1.0) : 0.0; /* fmin(1, fmax(0, vn)), NaN aside */
    RfVec3 tdir;
    int refracts = transmits && rf_refract(v, n, eta_i, eta_t, &tdir);
    double fr = 1.0, ft = 1.0;
    int fresnel = RF_ON(RF_K_FRESNEL) && (m->flags & RF_MAT_FRESNEL);
    if (fresnel) {
        RfFresnel f = rf_fresnel(eta_i, eta_t, cos_i, RF_FRESNEL_EXACT);
        fr = f.r;
        ft = f.t;
    }
    /* total internal reflection: the transmitted share goes into the mirror ray */
    RfRgb wr = rf_rgb_scale(kr, fr), wt = rf_rgb_scale(kt, ft);
    if (transmits && !refracts) {
        wr = fresnel ? rf_rgb_add(wr, wt) : rf_rgb_add(wr, kt);
        wt = zero;
    }
    double mr = rf_kernel_rgb_max(wr), mt = rf_kernel_rgb_max(wt);
    int glossy = RF_ON(RF_K_GLOSSY) && m->gloss > 0.0;
    RfTraceEvent ev; /* refray trace only: the §3.8.1 numbers of the secondary rays */
    if (RF_TRACE_ON(ps)) {
        memset(&ev, 0, sizeof ev);
        ev.kind = RF_TRACE_SECONDARY, ev.depth = depth, ev.sample = (int)ps->k, ev.samples = (int)ps->n;
        ev.tir = transmits && !refracts, ev.fresnel = fresnel;
        ev.eta_i = eta_i, ev.eta_t = eta_t, ev.cos_i = cos_i, ev.fr = fr, ev.ft = ft;
    }
    if (mr > 0.0 && weight * mr >= job->min_contribution) {
        RfVec3 rdir = rf_reflect_dir(rf_vec3_neg(v), n);
        if (RF_TRACE_ON(ps)) {
            ev.refracted = 0, ev.weight = wr, ev.ray = rf_ray(rf_hit_offset_origin(h, rdir, job->fixed_offset), rdir);
            ps->log->trace(ps->log->trace_ctx, &ev);
        }
        color = RF_KNAME(secondary)(job, h, rdir, wr, mr, 0, glossy ? m->gloss : 0.0, depth, weight, st, shadow_cache, ps,
                                    color);
    }
    if (refracts && mt > 0.0 && weight * mt >= job->min_contribution) {
        if (RF_TRACE_ON(ps)) {
            ev.refracted = 1, ev.weight = wt, ev.ray = rf_ray(rf_hit_offset_origin(h, tdir, job->fixed_offset), tdir);
            ps->log->trace(ps->log->trace_ctx, &ev);
        }
        color = RF_KNAME(secondary)(job, h, tdir, wt, mt, 1, glossy ? m->gloss : 0.0, depth, weight, st, shadow_cache, ps,
                                    color);
    }
    return RF_KNAME(traced)(ps, depth, local, color);
}

/* The colour seen along ray (hits in [t_min, inf)). */
static RfRgb RF_KNAME(trace)(const RfKernelJob *job, const RfRay *ray, double t_min, int depth, double weight,
                             RfRenderStats *st, uint64_t *shadow_cache, const RfPathSample *ps)
{
    RfSurfaceHit h;
    if ((RF_ON(RF_K_MOTION) ? rf_tracer_intersect_at(job->tracer, ray, ps->motion, t_min, HUGE_VAL, &h)
                            : rf_tracer_intersect(job->tracer, ray, t_min, HUGE_VAL, &h)) < 0)
        return RF_KNAME(missed)(job, depth, ps);
    return RF_KNAME(shade)(job, ray, &h, depth, weight, st, shadow_cache, ps);
}

/* refray trace: a camera sample's image position and primary ray */
static inline void RF_KNAME(trace_sample)(const RfPathSample *ps, double px, double py, const RfRay *ray)
{
    if (RF_TRACE_ON(ps)) {
        RfTraceEvent ev;
        memset(&ev, 0, sizeof ev);
        ev.kind = RF_TRACE_SAMPLE, ev.depth = 1, ev.sample = (int)ps->k, ev.samples = (int)ps->n;
        ev.px = px, ev.py = py, ev.ray = *ray;
        ps->log->trace(ps->log->trace_ctx, &ev);
    }
}

/* The camera ray of sample ps->k through image position (px, py) (pixel units, y down) and, with
 * a thin lens (§3.10), through the sample's lens point (ps->lens_uv, or drawn here). */
static inline RfRay RF_KNAME(lens_ray)(const RfKernelJob *job, double px, double py, const RfPathSample *ps)
{
    const RfCamera *cam = &job->camera;
    double lens[2] = {0.0, 0.0};
    if (RF_ON(RF_K_LENS) && cam->aperture_radius > 0.0) {
        double own[2];
        const double *uv = ps->lens_uv;
        if (!uv) {
            rf_sample_2d(ps->sampler, ps->k, ps->n, ps->pixel, RF_DIM_LENS, job->seed, own);
            uv = own;
        }
        rf_warp_disk(uv[0], uv[1], &lens[0], &lens[1]);
    }
    return rf_camera_ray(cam, px, py, lens[0], lens[1]);
}

/* Where a camera ray starts: the hither plane, nothing nearer than `hither` along the view
 * axis -w. */
static inline double RF_KNAME(hither_t)(const RfKernelJob *job, const RfRay *ray)
{
    return job->hither > 0.0 ? job->hither / -rf_vec3_dot(ray->dir, job->camera.basis.w) : 0.0;
}

/* A camera sample's colour as the film takes it: never let NaN, Inf or a negative radiance
 * reach it (note the first: the render fails unless it is a preview; count it; store black). */
static inline RfRgb RF_KNAME(film)(const RfKernelJob *job, const RfPathSample *ps, RfRenderStats *st, RfRgb c)
{
    if (!rf_kernel_rgb_valid(c)) {
        rf_kernel_note_invalid(st, job->width, ps->pixel, (int)ps->k, c);
        c = rf_rgb(0, 0, 0);
    }
    return c;
}

/* The primary ray's colour: the hither plane, the trace, the invalid-sample rule. */
static RfRgb RF_KNAME(camera_ray)(const RfKernelJob *job, const RfRay *ray, const RfPathSample *ps, RfRenderStats *st,
                                  uint64_t *shadow_cache)
{
    st->primary_rays++;
    RfRgb c = RF_KNAME(trace)(job, ray, RF_KNAME(hither_t)(job, ray), 1, 1.0, st, shadow_cache, ps);
    return RF_KNAME(film)(job, ps, st, c);
}

/* Camera rays in groups (stage 1 of the wavefront plan, docs/performance.md): whether this
 * kernel and render take them, rays at the scene's first keyframe (nothing moves). The general
 * kernel, the reference, traces one ray at a time. */
#define RF_KGROUPS(job) (RF_KPARTS != RF_K_ALL && !(RF_ON(RF_K_MOTION) && (job)->motion))

/* count (1-4) camera rays with their samples ps[l]: their nearest hits in one query
 * (rf_tracer_intersect4), then each shaded as camera_ray shades it, in their order; out[l] gets
 * camera_ray's colour bit for bit. */
static void RF_KNAME(camera_rays)(const RfKernelJob *job, const RfRay rays[4], int count, const RfPathSample ps[4],
                                  RfRenderStats *st, uint64_t *shadow_cache, RfRgb out[4])
{
    double t_min[4] = {0.0, 0.0, 0.0, 0.0}; /* idle lanes are not read */
    RfSurfaceHit h[4];
    for (int l = 0; l < count; l++)
        t_min[l] = RF_KNAME(hither_t)(job, &rays[l]);
    unsigned hit = rf_tracer_intersect4(job->tracer, rays, (1u << count) - 1, t_min, h);
    for (int l = 0; l < count; l++) {
        st->primary_rays++;
        RfRgb c = (hit >> l) & 1 ? RF_KNAME(shade)(job, &rays[l], &h[l], 1, 1.0, st, shadow_cache, &ps[l])
                                 : RF_KNAME(missed)(job, 1, &ps[l]);
        out[l] = RF_KNAME(film)(job, &ps[l], st, c);
    }
}

/* The camera ray through the centre of pixel (x, y): rf_camera_ray's plane point, from the
 * coordinates computed once per row and column. */
static inline RfRay RF_KNAME(centre_ray)(const RfKernelJob *job, int x, int y)
{
    const RfCamera *cam = &job->camera;
    RfVec3 c = rf_vec3(job->column_x[x], job->row_y[y], -cam->d);
    return rf_ray(cam->eye, rf_vec3_normalize(rf_camera_to_world(cam, c)));
}

/* Pixels x .. x + count - 1 (count <= 4) of row y at one sample each, through their centres, in
 * one group. */
static void RF_KNAME(centres)(const RfKernelJob *job, int x, int y, int count, int thread)
{
    RfRenderStats *st = &job->per_thread[thread];
    RfRay rays[4];
    RfPathSample ps[4];
    RfRgb c[4];
    for (int l = 0; l < count; l++) {
        RfPathSample p = {(uint64_t)y * (uint64_t)job->width + (uint64_t)(x + l), 0, 1, job->sampler,
                          job->shutter_open, job->motion ? job->motion[thread] : NULL, job->trace_log, NULL};
        ps[l] = p;
        rays[l] = RF_KNAME(centre_ray)(job, x + l, y);
    }
    RF_KNAME(camera_rays)(job, rays, count, ps, st, rf_kernel_shadow_cache(job, thread), c);
    for (int l = 0; l < count; l++)
        rf_kernel_store(job, st, x + l, y, c[l]);
}

/* One camera sample: the ray through image position (px, py) (pixel units, y down), through the
 * lens and at the time of sample k of n (§3.10), from the hither plane on. NaN and Inf are
 * counted and become black. */
static RfRgb RF_KNAME(camera_sample)(const RfKernelJob *job, double px, double py, RfPathSample *ps,
                                     RfRenderStats *st, uint64_t *shadow_cache)
{
    if (RF_ON(RF_K_MOTION) && ps->motion) {
        ps->time = job->shutter_open + (job->shutter_close - job->shutter_open) *
                                           rf_sample_1d(ps->sampler, ps->k, ps->n, ps->pixel, RF_DIM_TIME, job->seed);
        rf_motion_state_set(ps->motion, ps->time);
    }
    RfRay ray = RF_KNAME(lens_ray)(job, px, py, ps);
    RF_KNAME(trace_sample)(ps, px, py, &ray);
    return RF_KNAME(camera_ray)(job, &ray, ps, st, shadow_cache);
}

/* count (1-4) camera samples at image positions (px[l], py[l]) with their paths ps[l]: in one
 * group where the kernel and the render take groups (camera_rays), else one at a time; out[l]
 * is camera_sample's colour either way, and ps[l] is left as camera_sample leaves it. */
static void RF_KNAME(samples)(const RfKernelJob *job, const double *px, const double *py, int count,
                              RfPathSample *ps, RfRenderStats *st, uint64_t *shadow_cache, RfRgb *out)
{
    if (RF_KGROUPS(job)) {
        RfRay rays[4];
        for (int l = 0; l < count; l++)
            rays[l] = RF_KNAME(lens_ray)(job, px[l], py[l], &ps[l]);
        RF_KNAME(camera_rays)(job, rays, count, ps, st, shadow_cache, out);
        return;
    }
    for (int l = 0; l < count; l++)
        out[l] = RF_KNAME(camera_sample)(job, px[l], py[l], &ps[l], st, shadow_cache);
}

/* The value of a pixel from its samples (§3.9): the box filter's mean, or a filter's weighted
 * mean over samples drawn in [-radius, radius]^2 around the centre. One sample: the centre.
 * missed (more than one sample, a filter wider than the pixel): no camera ray of the tile can hit
 * anything (rf_kernel_tile_misses), so every sample is the background, counted but not traced;
 * the positions, weights and sums stay those of a traced tile, so the pixels get the same bits
 * (for the box filter and one sample rf_kernel_background does it without the positions). */
static void RF_KNAME(pixels)(const RfKernelJob *job, RfTile tile, int thread, int n, int missed)
{
    RfRenderStats *st = &job->per_thread[thread];
    uint64_t *shadow_cache = rf_kernel_shadow_cache(job, thread);
    const RfCamera *cam = &job->camera;
    const int groups = RF_KGROUPS(job) && !missed;
    const int pinhole = !(RF_ON(RF_K_LENS) && cam->aperture_radius > 0.0);
    for (int y = tile.y0; y < tile.y1; y++)
        for (int x = tile.x0; x < tile.x1; x++) {
            if (n == 1 && groups && pinhole) { /* the row's pixel centres, four at a time */
                int count = tile.x1 - x < 4 ? tile.x1 - x : 4;
                RF_KNAME(centres)(job, x, y, count, thread);
                x += count - 1;
                continue;
            }
            RfPathSample ps = {(uint64_t)y * (uint64_t)job->width + (uint64_t)x, 0, (uint32_t)n, job->sampler,
                               job->shutter_open, job->motion ? job->motion[thread] : NULL, job->trace_log, NULL};
            RfRgb sum = rf_rgb(0, 0, 0);
            if (n == 1) {
                if (RF_ON(RF_K_LENS | RF_K_MOTION) && (cam->aperture_radius > 0.0 || job->moving)) {
                    sum = RF_KNAME(camera_sample)(job, x + 0.5, y + 0.5, &ps, st, shadow_cache);
                } else {
                    RfRay ray = RF_KNAME(centre_ray)(job, x, y);
                    RF_KNAME(trace_sample)(&ps, x + 0.5, y + 0.5, &ray);
                    sum = RF_KNAME(camera_ray)(job, &ray, &ps, st, shadow_cache);
                }
            } else {
                RfRgb wsum_c = rf_rgb(0, 0, 0), sq = rf_rgb(0, 0, 0);
                double wsum = 0.0;
                /* the pixel's keys of the pixel position and the lens, once for its n samples,
                 * whose points are drawn a run at a time (Sobol: four in SIMD lanes) */
                int through_lens = RF_ON(RF_K_LENS) && cam->aperture_radius > 0.0;
                RfSampleKeys pos = rf_sample_keys(job->sampler, ps.pixel, RF_DIM_PIXEL, job->seed);
                RfSampleKeys lens = through_lens ? rf_sample_keys(job->sampler, ps.pixel, RF_DIM_LENS, job->seed) : pos;
                double pos_uv[RF_SAMPLE_RUN][2], lens_uv[RF_SAMPLE_RUN][2];
                /* four samples at a time (RF_SAMPLE_RUN is a multiple of 4): their positions, their
                 * colours (in one group of camera rays where the kernel takes them), their sums */
                for (int k0 = 0; k0 < n; k0 += 4) {
                    int j0 = k0 % RF_SAMPLE_RUN, count = n - k0 < 4 ? n - k0 : 4;
                    if (j0 == 0) {
                        uint32_t run = n - k0 < RF_SAMPLE_RUN ? (uint32_t)(n - k0) : RF_SAMPLE_RUN;
                        rf_sample_2d_keyed_run(&pos, (uint32_t)k0, run, (uint32_t)n, pos_uv);
                        if (through_lens)
                            rf_sample_2d_keyed_run(&lens, (uint32_t)k0, run, (uint32_t)n, lens_uv);
                    }
                    double px[4], py[4], w[4];
                    RfRgb c[4];
                    for (int l = 0; l < count; l++) {
                        const double *s = pos_uv[j0 + l];
                        px[l] = x + s[0], py[l] = y + s[1], w[l] = 1.0;
                        if (!job->filter_box) {
                            double r = job->filter.radius, ox = (2.0 * s[0] - 1.0) * r, oy = (2.0 * s[1] - 1.0) * r;
                            w[l] = rf_filter_eval(&job->filter, ox, oy);
                            px[l] = x + 0.5 + ox, py[l] = y + 0.5 + oy;
                        }
                    }
                    if (missed) {
                        for (int l = 0; l < count; l++) {
                            c[l] = job->background;
                            st->primary_rays++;
                        }
                    } else {
                        RfPathSample group[4];
                        for (int l = 0; l < count; l++) {
                            group[l] = ps;
                            group[l].k = (uint32_t)(k0 + l);
                            group[l].lens_uv = through_lens ? lens_uv[j0 + l] : NULL;
                        }
                        RF_KNAME(samples)(job, px, py, count, group, st, shadow_cache, c);
                    }
                    for (int l = 0; l < count; l++) {
                        sum = rf_rgb_add(sum, c[l]);
                        if (job->filter_box) {
                            if (job->variance) /* refray diff --stat: the samples' spread */
                                sq = rf_rgb_add(sq, rf_rgb_mul(c[l], c[l]));
                        } else {
                            wsum_c = rf_rgb_add(wsum_c, rf_rgb_scale(c[l], w[l]));
                            wsum += w[l];
                        }
                    }
                }
                /* a filter with negative lobes may leave a weight sum <= 0: then the plain mean */
                if (!job->filter_box && wsum > 0.0)
                    sum = rf_rgb_scale(wsum_c, (double)n / wsum);
                if (job->variance)
                    rf_kernel_store_variance(job, x, y, sum, sq, n);
            }
            rf_kernel_store(job, st, x, y, rf_rgb(sum.r / n, sum.g / n, sum.b / n));
            if (RF_TRACE_ON(&ps))
                rf_kernel_trace_pixel(job, &ps, x, y);
        }
}

/* One tile: when no camera ray of the tile can hit anything (a pinhole camera,
 * rf_kernel_tile_misses), its background without a ray traced; never in the general kernel, the
 * reference for the rest. (Quarters of a tile tested too cost more than they saved: +0.4 to
 * +2.6 % instructions on the SPD scenes, docs/performance.md.) */
static int RF_KNAME(tile)(void *ctx, RfTile tile, int thread)
{
    const RfKernelJob *job = ctx;
    int n = RF_ON(RF_K_JITTER) ? job->samples : 1;
    int plain = n == 1 || job->filter_box; /* the samples' positions do not enter the pixel's value */
    if (RF_KPARTS != RF_K_ALL && job->cull && rf_kernel_tile_misses(job, tile, plain ? 1.0 : job->filter.radius + 1.0)) {
        if (plain)
            rf_kernel_background(job, &job->per_thread[thread], tile, n);
        else /* a filter's weights: the sample loop, without the rays */
            RF_KNAME(pixels)(job, tile, thread, n, 1);
        job->per_thread[thread].background_tiles++;
    } else
        RF_KNAME(pixels)(job, tile, thread, n, 0);
    return 0;
}

/* §3.9 adaptive supersampling, pass 1: one sample at each pixel centre. */
static int RF_KNAME(adaptive_centres)(void *ctx, RfTile tile, int thread)
{
    const RfKernelJob *job = ctx;
    RfRenderStats *st = &job->per_thread[thread];
    uint64_t *shadow_cache = rf_kernel_shadow_cache(job, thread);
    for (int y = tile.y0; y < tile.y1; y++)
        for (int x0 = tile.x0; x0 < tile.x1; x0 += 4) { /* four pixels at a time */
            int count = tile.x1 - x0 < 4 ? tile.x1 - x0 : 4;
            double px[4], py[4];
            RfPathSample ps[4];
            RfRgb c[4];
            for (int l = 0; l < count; l++) {
                RfPathSample p = {(uint64_t)y * (uint64_t)job->width + (uint64_t)(x0 + l), 0, 1, RF_SAMPLER_RANDOM,
                                  job->shutter_open, job->motion ? job->motion[thread] : NULL, job->trace_log, NULL};
                ps[l] = p;
                px[l] = x0 + l + 0.5, py[l] = y + 0.5;
            }
            RF_KNAME(samples)(job, px, py, count, ps, st, shadow_cache, c);
            for (int l = 0; l < count; l++)
                job->centres[rf_kernel_centre(job, x0 + l, y)] = c[l];
        }
    return 0;
}

/* The mean of the four quadrant centres of the square (x0, y0, size), each quadrant split again
 * (to job->adaptive_depth levels) where its value differs from its parent's by more than the
 * threshold. */
static RfRgb RF_KNAME(adaptive_square)(const RfKernelJob *job, double x0, double y0, double size, int level,
                                       RfRgb parent, RfPathSample *ps, RfRenderStats *st, uint64_t *shadow_cache)
{
    RfRgb q[4], sum = rf_rgb(0, 0, 0);
    double h = 0.5 * size, px[4], py[4];
    RfPathSample quad[4];
    for (int i = 0; i < 4; i++) {
        quad[i] = *ps;
        quad[i].k = ps->k + 1 + (uint32_t)i;
        px[i] = x0 + (i & 1) * h + 0.5 * h, py[i] = y0 + (i >> 1) * h + 0.5 * h;
    }
    RF_KNAME(samples)(job, px, py, 4, quad, st, shadow_cache, q);
    *ps = quad[3];
    for (int i = 0; i < 4; i++) {
        if (level < job->adaptive_depth && rf_kernel_rgb_diff(q[i], parent) > job->adaptive_threshold)
            q[i] = RF_KNAME(adaptive_square)(job, x0 + (i & 1) * h, y0 + (i >> 1) * h, h, level + 1, q[i], ps, st,
                                             shadow_cache);
        sum = rf_rgb_add(sum, q[i]);
    }
    return rf_rgb_scale(sum, 0.25);
}

/* Pass 2: a pixel whose centre differs from a 4-neighbour's by more than the threshold (the
 * script: "wenn die Differenz der Farbe zum Nachbarpixel zu groß ist") is subdivided. */
static int RF_KNAME(adaptive_refine)(void *ctx, RfTile tile, int thread)
{
    const RfKernelJob *job = ctx;
    RfRenderStats *st = &job->per_thread[thread];
    uint64_t *shadow_cache = rf_kernel_shadow_cache(job, thread);
    for (int y = tile.y0; y < tile.y1; y++)
        for (int x = tile.x0; x < tile.x1; x++) {
            uint64_t pixel = (uint64_t)y * (uint64_t)job->width + (uint64_t)x;
            RfRgb c = job->centres[rf_kernel_centre(job, x, y)];
            double contrast = 0.0;
            if (x > 0)
                contrast = fmax(contrast, rf_kernel_rgb_diff(c, job->centres[rf_kernel_centre(job, x - 1, y)]));
            if (x + 1 < job->width)
                contrast = fmax(contrast, rf_kernel_rgb_diff(c, job->centres[rf_kernel_centre(job, x + 1, y)]));
            if (y > 0)
                contrast = fmax(contrast, rf_kernel_rgb_diff(c, job->centres[rf_kernel_centre(job, x, y - 1)]));
            if (y + 1 < job->height)
                contrast = fmax(contrast, rf_kernel_rgb_diff(c, job->centres[rf_kernel_centre(job, x, y + 1)]));
            if (job->adaptive_depth > 0 && contrast > job->adaptive_threshold) {
                RfPathSample ps = {pixel, 0, 1, RF_SAMPLER_RANDOM, job->shutter_open,
                                   job->motion ? job->motion[thread] : NULL, job->trace_log, NULL};
                c = RF_KNAME(adaptive_square)(job, x, y, 1.0, 1, c, &ps, st, shadow_cache);
                st->adaptive_pixels++;
            }
            rf_kernel_store(job, st, x, y, c);
            if (RF_TRACE_ON_JOB(job)) {
                RfPathSample ps = {pixel, 0, 1, RF_SAMPLER_RANDOM, job->shutter_open, NULL, job->trace_log, NULL};
                rf_kernel_trace_pixel(job, &ps, x, y);
            }
        }
    return 0;
}

/* Sample k of a pixel traced again as the tile traced it, its path written into log (the
 * adaptive passes' samples are explained by the pixel's centre sample). */
static RfRgb RF_KNAME(explain)(const RfKernelJob *job, uint64_t pixel, int k, RfPathLog *log)
{
    RfRenderStats st;
    uint64_t *cache = calloc((size_t)job->light_count + 1, sizeof *cache);
    int x = (int)(pixel % (uint64_t)job->width), y = (int)(pixel / (uint64_t)job->width);
    int n = RF_ON(RF_K_JITTER) && !job->centres ? job->samples : 1;
    RfPathSample ps = {pixel, (uint32_t)(k >= 0 ? k : 0), (uint32_t)n, job->centres ? RF_SAMPLER_RANDOM : job->sampler,
                       job->shutter_open, job->motion ? job->motion[0] : NULL, log, NULL};
    RfRgb c = rf_rgb(0, 0, 0);
    memset(&st, 0, sizeof st);
    if (!cache)
        return c;
    rf_kernel_log(log, "camera");
    if (n == 1) {
        c = RF_KNAME(camera_sample)(job, x + 0.5, y + 0.5, &ps, &st, cache);
    } else {
        double s[2];
        rf_sample_2d(job->sampler, ps.k, (uint32_t)n, pixel, RF_DIM_PIXEL, job->seed, s);
        if (job->filter_box) {
            c = RF_KNAME(camera_sample)(job, x + s[0], y + s[1], &ps, &st, cache);
        } else {
            double r = job->filter.radius;
            c = RF_KNAME(camera_sample)(job, x + 0.5 + (2.0 * s[0] - 1.0) * r, y + 0.5 + (2.0 * s[1] - 1.0) * r, &ps,
                                        &st, cache);
        }
    }
    free(cache);
    return c;
}

#undef RF_ON
