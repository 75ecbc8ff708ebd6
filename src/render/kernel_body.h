/* One render kernel: the Whitted-style shading of §3.6-3.8 and the tile loop, compiled with
 * RF_KPARTS (a set of RF_K_*) fixed, so that the compiler drops every part the set leaves out.
 * kernels.c includes this file once per kernel, with RF_KPARTS and RF_KNAME defined. Not a
 * header of its own: no include guard.
 *
 * Each part left out is one that could only have added nothing: a light kind that no light has,
 * a term whose coefficients are all zero, the recursion of a scene that neither reflects nor
 * transmits. Only the sign of a zero can differ on the way (x + 0 for x = -0), and the pixel sum,
 * which starts at +0, erases it, so every kernel writes the general kernel's image bit for bit
 * (tests/test_kernels.c renders every shipped scene both ways). */

#define RF_ON(part) ((RF_KPARTS & (part)) != 0)

/* The colour seen along ray (hits in [t_min, inf)); depth 1 is the primary ray, weight the
 * product of the reflection/transmission weights on the way here. */
static RfRgb RF_KNAME(trace)(const RfKernelJob *job, RfRay ray, double t_min, int depth, double weight,
                             RfRenderStats *st, uint64_t *shadow_cache)
{
    RfSurfaceHit h;
    if (rf_tracer_intersect(job->tracer, ray, t_min, HUGE_VAL, &h) < 0)
        return job->background;
    const RfMaterial *m = &job->materials[h.material];
    RfVec3 v = rf_vec3_neg(rf_vec3_normalize(ray.dir));
    RfVec3 n = h.shading_normal;
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
        if (RF_ON(RF_K_DIRECTIONAL) && l->kind == RF_LIGHT_DIRECTIONAL) {
            ls = rf_light_directional(l->intensity, l->direction);
        } else if (RF_ON(RF_K_SPOT) && l->kind == RF_LIGHT_SPOT) {
            if (rf_light_spot(l->intensity, l->position, l->direction, l->spot_exponent, l->spot_cutoff_rad,
                              l->falloff, h.point, &ls) != RF_OK)
                continue;
        } else { /* §3.7 point light, as rf_light_point */
            RfVec3 to = rf_vec3_sub(l->position, h.point);
            double d = rf_vec3_length(to);
            if (!(d > 0.0) || !isfinite(d))
                continue;
            ls.l = rf_vec3_scale(to, 1.0 / d);
            ls.distance = d;
            ls.i = RF_ON(RF_K_FALLOFF) && l->falloff == RF_FALLOFF_INVERSE_SQUARE
                       ? rf_rgb_scale(l->intensity, 1.0 / (d * d))
                       : l->intensity;
        }
        if (rf_kernel_rgb_max(ls.i) <= 0.0)
            continue;
        if (rf_vec3_dot(h.normal, ls.l) <= 0.0) /* the light is behind the surface */
            continue;
        if (RF_ON(RF_K_SHADOW) && !job->local_only) {
            /* §3.8 shadow ray to the light: any surface in between blocks it (opaque shadows) */
            RfRay sr = rf_ray(rf_ray_offset_origin(h.point, h.normal, ls.l, job->fixed_offset), ls.l);
            double dist = isinf(ls.distance) ? HUGE_VAL
                                             : rf_vec3_length(rf_vec3_sub(rf_vec3_add(h.point,
                                                   rf_vec3_scale(ls.l, ls.distance)), sr.origin));
            st->shadow_rays++;
            if (rf_tracer_occluded_cached(job->tracer, sr, 0.0, dist, &shadow_cache[li]))
                continue;
        }
        /* §3.6.2 Phong, as rf_phong: only positive scalar products contribute */
        double nl = rf_vec3_dot(n, ls.l);
        double diff = nl > 0.0 ? nl : 0.0;
        RfRgb diffuse = rf_rgb_scale(rf_rgb_mul(m->kd, ls.i), diff);
        if (RF_ON(RF_K_SPECULAR)) {
            /* without a highlight (ks = 0) the power would only multiply a zero */
            double rv = job->highlight[h.material] ? rf_vec3_dot(rf_reflect(n, ls.l), v) : 0.0;
            double spec = nl > 0.0 && rv > 0.0 ? pow(rv, m->shininess) : 0.0;
            RfRgb specular = rf_rgb_scale(rf_rgb_mul(m->ks, ls.i), spec);
            color = rf_rgb_add(color, rf_rgb_add(diffuse, specular));
        } else {
            color = rf_rgb_add(color, diffuse);
        }
    }
    if (!RF_ON(RF_K_SECONDARY) || job->local_only || depth >= job->max_depth)
        return color;
    RfRgb kr = m->kr, kt = m->kt, zero = rf_rgb(0, 0, 0);
    int reflects = rf_kernel_rgb_max(kr) > 0.0, transmits = rf_kernel_rgb_max(kt) > 0.0;
    if (!reflects && !transmits)
        return color;
    /* §3.8.1: entering through the front (outside) goes from air (1) into the material */
    double eta_i = h.front ? 1.0 : m->ior, eta_t = h.front ? m->ior : 1.0;
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
    if (mr > 0.0 && weight * mr >= job->min_contribution) {
        RfVec3 rdir = rf_reflect_dir(rf_vec3_neg(v), n);
        RfRay rr = rf_ray(rf_ray_offset_origin(h.point, h.normal, rdir, job->fixed_offset), rdir);
        st->secondary_rays++;
        color = rf_rgb_add(color, rf_rgb_mul(wr, RF_KNAME(trace)(job, rr, 0.0, depth + 1, weight * mr, st, shadow_cache)));
    }
    if (refracts && mt > 0.0 && weight * mt >= job->min_contribution) {
        RfRay tr = rf_ray(rf_ray_offset_origin(h.point, h.normal, tdir, job->fixed_offset), tdir);
        st->secondary_rays++;
        color = rf_rgb_add(color, rf_rgb_mul(wt, RF_KNAME(trace)(job, tr, 0.0, depth + 1, weight * mt, st, shadow_cache)));
    }
    return color;
}

/* One tile: for each pixel its samples (the centre, or jittered positions, rf_kernel_sample),
 * the primary ray through each (from the hither plane on), the box-filtered mean. */
static int RF_KNAME(tile)(void *ctx, RfTile tile, int thread)
{
    const RfKernelJob *job = ctx;
    RfRenderStats *st = &job->per_thread[thread];
    uint64_t *shadow_cache = job->shadow_cache + (size_t)thread * (size_t)job->light_count;
    const RfCamera *cam = &job->camera;
    for (int y = tile.y0; y < tile.y1; y++)
        for (int x = tile.x0; x < tile.x1; x++) {
            uint64_t pixel = (uint64_t)y * (uint64_t)job->width + (uint64_t)x;
            RfRgb sum = rf_rgb(0, 0, 0);
            for (int k = 0; k < (RF_ON(RF_K_JITTER) ? job->samples : 1); k++) {
                RfRay ray;
                if (RF_ON(RF_K_JITTER) && job->samples > 1) {
                    double sx, sy;
                    rf_kernel_sample(job->samples, k, pixel, job->seed, &sx, &sy);
                    ray = rf_camera_ray(cam, x + sx, y + sy, 0.0, 0.0);
                } else { /* the pixel centre: rf_camera_ray's plane point, computed per row and column */
                    RfVec3 c = rf_vec3(job->column_x[x], job->row_y[y], -cam->d);
                    ray = rf_ray(cam->eye, rf_vec3_normalize(rf_camera_to_world(cam, c)));
                }
                /* the hither plane: nothing nearer than `hither` along the view axis -w */
                double t_min = job->hither > 0.0 ? job->hither / -rf_vec3_dot(ray.dir, cam->basis.w) : 0.0;
                st->primary_rays++;
                RfRgb c = RF_KNAME(trace)(job, ray, t_min, 1, 1.0, st, shadow_cache);
                if (!isfinite(c.r) || !isfinite(c.g) || !isfinite(c.b)) {
                    /* never let NaN/Inf reach the film: count it (reported), store black */
                    st->invalid_samples++;
                    c = rf_rgb(0, 0, 0);
                }
                sum = rf_rgb_add(sum, c);
            }
            float *px = job->img->data + (size_t)pixel * 3;
            px[0] = (float)(sum.r / job->samples);
            px[1] = (float)(sum.g / job->samples);
            px[2] = (float)(sum.b / job->samples);
        }
    return 0;
}

#undef RF_ON
