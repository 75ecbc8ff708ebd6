/* Ray/primitive intersection (§3.5). See refray/intersect.h for the contract. */
#include "refray/intersect.h"

#include <math.h>
#include <string.h>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "refray/geometry.h"

static int in_range(double t, double t_min, double t_max)
{
    return t >= t_min && t < t_max; /* false for NaN */
}

/* Roots of a t^2 + 2 bh t + c = 0 (half-b form) from the quarter discriminant dq = bh^2 - ac,
 * which the caller may compute more precisely than the formula. q = -(bh + sign(bh) sqrt(dq))
 * adds two numbers of the same sign, so no cancellation; the roots are q/a and c/q (Vieta).
 * Returns 0 (dq < 0 or no solution) or 1 with t[0] <= t[1]; a double root and the linear case
 * (a = 0) give t[0] = t[1]. *root_dq: sqrt(dq) when dq >= 0. */
static int solve_quadratic(double a, double bh, double c, double dq, double t[2], double *root_dq)
{
    if (!(dq >= 0.0))
        return 0;
    double sq = sqrt(dq);
    *root_dq = sq; /* for the caller's normal: one square root */
    double q = -(bh + copysign(sq, bh));
    if (q == 0.0) {          /* bh = 0 and dq = 0, so ac = 0 */
        if (a == 0.0)        /* 0 = c: no equation left (a ray inside the surface) or none */
            return 0;
        t[0] = t[1] = 0.0;   /* c = 0: double root at 0 */
        return 1;
    }
    if (a == 0.0) {          /* linear 2 bh t + c = 0; q = -2 bh */
        t[0] = t[1] = c / q;
        return 1;
    }
    if (dq == 0.0) {         /* tangent: one root, q/a = -bh/a */
        t[0] = t[1] = q / a;
        return 1;
    }
    double r1 = q / a, r2 = c / q;
    t[0] = rf_min_num(r1, r2);
    t[1] = rf_max_num(r1, r2);
    return 1;
}

/* <f,f> - r^2 with error-free products and sums (Ogita, Rump, Oishi 2005, Dot2): accurate to
 * about one rounding even when the origin lies near the sphere and the terms cancel. */
static inline void add_square(double h, double sgn, double *s, double *e)
{
    double p = sgn * (h * h);
    double pe = sgn * fma(h, h, -(h * h)); /* exact error of the square */
    double q = *s + p, z = q - *s;         /* TwoSum(s, p) */
    *e += ((*s - (q - z)) + (p - z)) + pe;
    *s = q;
}

static double dot_minus_square(RfVec3 f, double r)
{
    double s = 0.0, e = 0.0; /* four steps written out: the signs are constants then */
    add_square(f.x, 1.0, &s, &e);
    add_square(f.y, 1.0, &s, &e);
    add_square(f.z, 1.0, &s, &e);
    add_square(r, -1.0, &s, &e);
    return s + e;
}

/* The roots of a t^2 + 2 bh t + c = 0 with c = <f,f> - r^2 compensated (dot_minus_square) and
 * dq the caller's cancellation-free quarter discriminant. c is computed only when dq shows real
 * roots (solve_quadratic reads it for nothing else): most sphere and cone tests are misses. */
static inline int solve_compensated(double a, double bh, RfVec3 f, double r, double dq, double *c, double t[2],
                                    double *root_dq)
{
    if (!(dq >= 0.0))
        return 0;
    *c = dot_minus_square(f, r);
    return solve_quadratic(a, bh, *c, dq, t, root_dq);
}

/* The stable form's pieces: f = e - center, a = <d,d>, bh = <d,f>, v = f - (bh/a) d (the
 * centre's offset from the ray's closest point, v perpendicular to d) and the quarter
 * discriminant D/4 = a (r - |v|)(r + |v|), which does not cancel the way b^2 - 4ac does for a
 * far sphere (Ray Tracing Gems ch. 7, pbrt-v4). */
typedef struct { RfVec3 f, v; double a, bh, dq; } SphereParts;

static SphereParts sphere_parts(RfRay ray, RfSphere s)
{
    SphereParts p;
    p.f = rf_vec3_sub(ray.origin, s.center);
    p.a = rf_vec3_dot(ray.dir, ray.dir);
    p.bh = rf_vec3_dot(ray.dir, p.f);
    p.v = rf_vec3_sub(p.f, rf_vec3_scale(ray.dir, p.bh / p.a));
    double lv = rf_vec3_length(p.v);
    p.dq = p.a * ((s.radius - lv) * (s.radius + lv));
    return p;
}

/* The stable method's roots t[0] <= t[1] from its parts (computed here into *p); *c is set only
 * when p->dq >= 0. */
static inline int sphere_stable(RfRay ray, RfSphere s, SphereParts *p, double *c, double t[2], double *root_dq)
{
    *p = sphere_parts(ray, s);
    return solve_compensated(p->a, p->bh, p->f, s.radius, p->dq, c, t, root_dq);
}

/* §3.5.1 */
RfSphereQuadratic rf_sphere_quadratic(RfRay ray, RfSphere s, RfSphereMethod method)
{
    RfSphereQuadratic q;
    RfVec3 f = rf_vec3_sub(ray.origin, s.center), d = ray.dir;
    double t[2];
    q.a = rf_vec3_dot(d, d);
    q.b = 2.0 * rf_vec3_dot(d, f);
    q.t1 = q.t2 = NAN;
    q.roots = 0;
    if (method == RF_SPHERE_SCRIPT) {
        /* the script's midnight formula, its cases as written */
        q.c = rf_vec3_dot(f, f) - s.radius * s.radius;
        q.disc = q.b * q.b - 4.0 * q.a * q.c;
        if (q.disc == 0.0) {
            q.t1 = q.t2 = -q.b / (2.0 * q.a);
            q.roots = 1;
        } else if (q.disc > 0.0) {
            double sq = sqrt(q.disc);
            q.t1 = (-q.b - sq) / (2.0 * q.a); /* a > 0, so t1 < t2 */
            q.t2 = (-q.b + sq) / (2.0 * q.a);
            q.roots = 2;
        }
        return q;
    }
    SphereParts p;
    double sq;
    int real = sphere_stable(ray, s, &p, &q.c, t, &sq);
    if (!(p.dq >= 0.0))
        q.c = dot_minus_square(f, s.radius);
    q.disc = 4.0 * p.dq;
    if (real) {
        q.t1 = t[0];
        q.t2 = t[1];
        q.roots = p.dq == 0.0 ? 1 : 2;
    }
    return q;
}

int rf_sphere_roots(const RfRay *ray, const RfSphere *s, RfSphereRoots *out)
{
    SphereParts p;
    double c;
    if (!sphere_stable(*ray, *s, &p, &c, out->t, &out->sq))
        return 0;
    out->v = p.v;
    out->a = p.a;
    return 1;
}

#if defined(__AVX2__) && defined(__FMA__)
/* add_square in four lanes */
static inline void add_square4(__m256d h, double sgn, __m256d *s, __m256d *e)
{
    __m256d g = _mm256_set1_pd(sgn), hh = _mm256_mul_pd(h, h);
    __m256d p = _mm256_mul_pd(g, hh);
    __m256d pe = _mm256_mul_pd(g, _mm256_fmsub_pd(h, h, hh));
    __m256d q = _mm256_add_pd(*s, p), z = _mm256_sub_pd(q, *s);
    __m256d err = _mm256_add_pd(_mm256_sub_pd(*s, _mm256_sub_pd(q, z)), _mm256_sub_pd(p, z));
    *e = _mm256_add_pd(*e, _mm256_add_pd(err, pe));
    *s = q;
}

/* a x + b y + c z, added left to right as rf_vec3_dot does */
static inline __m256d dot4(__m256d ax, __m256d ay, __m256d az, __m256d bx, __m256d by, __m256d bz)
{
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(ax, bx), _mm256_mul_pd(ay, by)), _mm256_mul_pd(az, bz));
}

unsigned rf_sphere_roots4(const RfRay4 *r4, const RfSphere *s, RfSphereRoots out[4])
{
    /* sphere_parts */
    __m256d dx = _mm256_loadu_pd(r4->dx), dy = _mm256_loadu_pd(r4->dy), dz = _mm256_loadu_pd(r4->dz);
    __m256d fx = _mm256_sub_pd(_mm256_loadu_pd(r4->ox), _mm256_set1_pd(s->center.x));
    __m256d fy = _mm256_sub_pd(_mm256_loadu_pd(r4->oy), _mm256_set1_pd(s->center.y));
    __m256d fz = _mm256_sub_pd(_mm256_loadu_pd(r4->oz), _mm256_set1_pd(s->center.z));
    __m256d a = dot4(dx, dy, dz, dx, dy, dz), bh = dot4(dx, dy, dz, fx, fy, fz);
    __m256d k = _mm256_div_pd(bh, a);
    __m256d vx = _mm256_sub_pd(fx, _mm256_mul_pd(dx, k)), vy = _mm256_sub_pd(fy, _mm256_mul_pd(dy, k)),
            vz = _mm256_sub_pd(fz, _mm256_mul_pd(dz, k));
    __m256d lv = _mm256_sqrt_pd(dot4(vx, vy, vz, vx, vy, vz));
    __m256d r = _mm256_set1_pd(s->radius), zero = _mm256_setzero_pd();
    __m256d dq = _mm256_mul_pd(a, _mm256_mul_pd(_mm256_sub_pd(r, lv), _mm256_add_pd(r, lv)));
    unsigned real = (unsigned)_mm256_movemask_pd(_mm256_cmp_pd(dq, zero, _CMP_GE_OQ));
    if (!real)
        return 0;
    /* solve_compensated: c, then solve_quadratic's general case */
    __m256d se = zero, ee = zero;
    add_square4(fx, 1.0, &se, &ee);
    add_square4(fy, 1.0, &se, &ee);
    add_square4(fz, 1.0, &se, &ee);
    add_square4(r, -1.0, &se, &ee);
    __m256d c = _mm256_add_pd(se, ee);
    __m256d sq = _mm256_sqrt_pd(dq), sign = _mm256_set1_pd(-0.0);
    __m256d q = _mm256_xor_pd(_mm256_add_pd(bh, _mm256_or_pd(_mm256_andnot_pd(sign, sq), _mm256_and_pd(sign, bh))),
                              sign); /* -(bh + copysign(sq, bh)) */
    __m256d r1 = _mm256_div_pd(q, a), r2 = _mm256_div_pd(c, q);
    __m256d lo = _mm256_blendv_pd(r2, r1, _mm256_cmp_pd(r1, r2, _CMP_LT_OQ)); /* rf_min_num without NaN */
    __m256d hi = _mm256_blendv_pd(r2, r1, _mm256_cmp_pd(r1, r2, _CMP_GT_OQ));
    __m256d rare = _mm256_or_pd(_mm256_or_pd(_mm256_cmp_pd(q, zero, _CMP_EQ_OQ), _mm256_cmp_pd(a, zero, _CMP_EQ_OQ)),
                                _mm256_or_pd(_mm256_cmp_pd(dq, zero, _CMP_EQ_OQ), _mm256_cmp_pd(r1, r2, _CMP_UNORD_Q)));
    double t0[4], t1[4], sqs[4], as[4], v[3][4];
    _mm256_storeu_pd(t0, lo);
    _mm256_storeu_pd(t1, hi);
    _mm256_storeu_pd(sqs, sq);
    _mm256_storeu_pd(as, a);
    _mm256_storeu_pd(v[0], vx);
    _mm256_storeu_pd(v[1], vy);
    _mm256_storeu_pd(v[2], vz);
    unsigned odd = (unsigned)_mm256_movemask_pd(rare) & real;
    for (unsigned m = real & ~odd; m; m &= m - 1) {
        int l = __builtin_ctz(m);
        out[l].t[0] = t0[l], out[l].t[1] = t1[l], out[l].sq = sqs[l], out[l].a = as[l];
        out[l].v = rf_vec3(v[0][l], v[1][l], v[2][l]);
    }
    for (unsigned m = odd; m; m &= m - 1) {
        int l = __builtin_ctz(m);
        RfRay ray = rf_ray4_get(r4, l);
        if (!rf_sphere_roots(&ray, s, &out[l]))
            real &= ~(1u << l);
    }
    return real;
}
#else
unsigned rf_sphere_roots4(const RfRay4 *r4, const RfSphere *s, RfSphereRoots out[4])
{
    unsigned real = 0;
    for (int l = 0; l < 4; l++) {
        RfRay ray = rf_ray4_get(r4, l);
        real |= (unsigned)rf_sphere_roots(&ray, s, &out[l]) << l;
    }
    return real;
}
#endif

int rf_intersect_sphere(RfRay ray, RfSphere s, RfSphereMethod method, double t_min, double t_max,
                        RfHit *hit)
{
    double t[2];
    int root;
    hit->l[0] = hit->l[1] = hit->l[2] = 0.0;
    if (method == RF_SPHERE_SCRIPT) {
        RfSphereQuadratic q = rf_sphere_quadratic(ray, s, method);
        t[0] = q.t1;
        t[1] = q.t2;
        if (q.roots == 0 || !(root = rf_sphere_pick_root(t, t_min, t_max)))
            return 0;
        hit->t = t[root - 1];
        hit->normal = rf_vec3_scale(rf_vec3_sub(rf_ray_at(ray, hit->t), s.center), 1.0 / s.radius);
        return 1;
    }
    /* t1 is the near side (origin outside); t2 when t1 is behind or before t_min (origin
     * inside: the far side) */
    RfSphereRoots r;
    if (!rf_sphere_roots(&ray, &s, &r) || !(root = rf_sphere_pick_root(r.t, t_min, t_max)))
        return 0;
    hit->t = r.t[root - 1];
    hit->normal = rf_sphere_root_normal(&r, &ray, &s, root == 2);
    return 1;
}

/* §3.5.2 (erratum: the script uses d for the direction and the plane offset; kept apart) */
int rf_plane_line_t(RfRay ray, RfPlane p, double *t)
{
    double den = rf_vec3_dot(ray.dir, p.normal);
    if (den == 0.0)
        return 0;
    *t = (p.offset - rf_vec3_dot(ray.origin, p.normal)) / den;
    return 1;
}

int rf_intersect_plane(RfRay ray, RfPlane p, double t_min, double t_max, RfHit *hit)
{
    double t;
    if (!rf_plane_line_t(ray, p, &t) || !in_range(t, t_min, t_max))
        return 0; /* parallel, behind the origin (t < 0 <= t_min) or beyond t_max */
    hit->t = t;
    hit->l[0] = hit->l[1] = hit->l[2] = 0.0;
    hit->normal = rf_vec3_normalize(p.normal);
    return 1;
}

/* by pointer: the triangle is read where it lies (a copy made just before would be read back
 * across its stores) */
static RfVec3 triangle_unit_normal(const RfTriangle *tri)
{
    return rf_vec3_normalize(rf_vec3_cross(rf_vec3_sub(tri->p2, tri->p1), rf_vec3_sub(tri->p3, tri->p1)));
}

static void set_triangle_hit(RfHit *hit, RfTriangle tri, double t, double l1, double l2, double l3)
{
    hit->t = t;
    hit->l[0] = l1;
    hit->l[1] = l2;
    hit->l[2] = l3;
    hit->normal = triangle_unit_normal(&tri);
}

void rf_watertight_hit(const RfTriangle *tri, double t, const double e[4], const RfVec3 *normal, RfHit *hit)
{
    hit->t = t;
#if defined(__AVX__)
    /* the three divisions as one: the same IEEE quotient in each lane */
    double l[4];
    _mm256_storeu_pd(l, _mm256_div_pd(_mm256_set_pd(1.0, e[2], e[1], e[0]), _mm256_set1_pd(e[3])));
    hit->l[0] = l[0], hit->l[1] = l[1], hit->l[2] = l[2];
#else
    for (int i = 0; i < 3; i++)
        hit->l[i] = e[i] / e[3];
#endif
    hit->normal = normal ? *normal : triangle_unit_normal(tri);
}

/* §3.5.3 as in the script: the plane <x,n> = <p1,n> with n = (p2-p1) x (p3-p1), then the
 * barycentric coordinates of the plane point (rf_barycentric, §2.4), inside iff all >= 0.
 * Parallel rays and degenerate triangles miss; an edge or vertex point is inside (a zero
 * coordinate), but rounding in the plane point may put it on either side. */
static int triangle_script(RfRay ray, RfTriangle tri, double t_min, double t_max, RfHit *hit)
{
    RfVec3 n = rf_vec3_cross(rf_vec3_sub(tri.p2, tri.p1), rf_vec3_sub(tri.p3, tri.p1));
    RfPlane plane = {n, rf_vec3_dot(tri.p1, n)};
    double t, l[3];
    if (!rf_plane_line_t(ray, plane, &t) || !in_range(t, t_min, t_max))
        return 0;
    if (rf_barycentric(tri.p1, tri.p2, tri.p3, rf_ray_at(ray, t), l) != RF_OK)
        return 0;
    if (!(l[0] >= 0.0 && l[1] >= 0.0 && l[2] >= 0.0))
        return 0;
    set_triangle_hit(hit, tri, t, l[0], l[1], l[2]);
    return 1;
}

/* Moller-Trumbore: solve e + t d = p1 + u (p2-p1) + v (p3-p1) by Cramer's rule. det = 0
 * exactly (parallel ray or degenerate triangle) misses; no epsilon, which would scale with the
 * triangle's size. Comparisons are written so that NaN fails them. Edges and vertices are
 * inside, but u, v are rounded independently for the two triangles of an edge, so a ray
 * through a shared edge can miss both. */
static int triangle_moller(RfRay ray, RfTriangle tri, double t_min, double t_max, RfHit *hit)
{
    RfVec3 e1 = rf_vec3_sub(tri.p2, tri.p1), e2 = rf_vec3_sub(tri.p3, tri.p1);
    RfVec3 pv = rf_vec3_cross(ray.dir, e2);
    double det = rf_vec3_dot(e1, pv);
    if (det == 0.0)
        return 0;
    double inv = 1.0 / det;
    RfVec3 tv = rf_vec3_sub(ray.origin, tri.p1);
    double u = rf_vec3_dot(tv, pv) * inv;
    if (!(u >= 0.0 && u <= 1.0))
        return 0;
    RfVec3 qv = rf_vec3_cross(tv, e1);
    double v = rf_vec3_dot(ray.dir, qv) * inv;
    if (!(v >= 0.0 && u + v <= 1.0))
        return 0;
    double t = rf_vec3_dot(e2, qv) * inv;
    if (!in_range(t, t_min, t_max))
        return 0;
    set_triangle_hit(hit, tri, t, 1.0 - u - v, u, v);
    return 1;
}

static double comp(RfVec3 a, int k) { return k == 0 ? a.x : k == 1 ? a.y : a.z; }

/* Woop, Benthin, Wald 2013: the axis kz with the largest |d| becomes z (kx, ky swapped when
 * d_kz < 0 to keep the winding), the shear (sx, sy, sz) maps d to (0, 0, 1). */
void rf_watertight_ray(const RfRay *rp, RfWatertightRay *w)
{
    const RfRay ray = rf_ray_read(rp);
    double ax = fabs(ray.dir.x), ay = fabs(ray.dir.y), az = fabs(ray.dir.z);
    w->ray = ray;
    w->kz = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    w->kx = (w->kz + 1) % 3;
    w->ky = (w->kx + 1) % 3;
    if (comp(ray.dir, w->kz) < 0.0) {
        int k = w->kx;
        w->kx = w->ky;
        w->ky = k;
    }
    double dz = comp(ray.dir, w->kz);
#if defined(__AVX__)
    /* the three divisions as one: the same IEEE quotient in each lane */
    double q[4];
    _mm256_storeu_pd(q, _mm256_div_pd(_mm256_set_pd(1.0, 1.0, comp(ray.dir, w->ky), comp(ray.dir, w->kx)),
                                      _mm256_set1_pd(dz)));
    w->sx = q[0];
    w->sy = q[1];
    w->sz = q[2];
#else
    w->sx = comp(ray.dir, w->kx) / dz;
    w->sy = comp(ray.dir, w->ky) / dz;
    w->sz = 1.0 / dz;
#endif
    /* the vector kernel's lanes (kx, ky, kz, kz) as 32-bit halves, by kz and whether kx, ky swapped */
    static const int lanes[3][2][8] = {{{2, 3, 4, 5, 0, 1, 0, 1}, {4, 5, 2, 3, 0, 1, 0, 1}},
                                       {{4, 5, 0, 1, 2, 3, 2, 3}, {0, 1, 4, 5, 2, 3, 2, 3}},
                                       {{0, 1, 2, 3, 4, 5, 4, 5}, {2, 3, 0, 1, 4, 5, 4, 5}}};
    memcpy(w->lanes, lanes[w->kz][w->kx != (w->kz + 1) % 3], sizeof w->lanes);
    w->scalar = 0;
}

/* The 2D edge function e(P,Q) = Px Qy - Py Qx with its sign exact for the given doubles:
 * rounding is monotone, so RN(Px Qy) != RN(Py Qx) already orders the exact products; when they
 * round to the same double the exact difference is the difference of the two rounding errors,
 * which fma gives exactly (barring underflow below 2^-969). Swapping P and Q negates the result
 * exactly, so the two triangles of a shared edge see opposite signs and no ray slips between
 * them (the property WBW get by re-evaluating in double; a double tracer has nothing wider). */
static double edge_function(double px, double py, double qx, double qy)
{
    double a = px * qy, b = py * qx;
    if (a != b)
        return a - b;
    return fma(px, qy, -a) - fma(py, qx, -b);
}

/* The edge functions U, V, W of the sheared triangle, det = U + V + W and t = T / det. Two-sided:
 * the line meets the triangle when U, V, W are all >= 0 or all <= 0; a ray exactly through an
 * edge or vertex (a zero edge function) meets every triangle there; det = 0 (the ray in the
 * triangle's plane, or a degenerate triangle) meets none. */
static inline int watertight(const RfWatertightRay *w, const RfTriangle *tri, double e[3],
                             double *det, double *t)
{
    RfVec3 a = rf_vec3_sub(tri->p1, w->ray.origin), b = rf_vec3_sub(tri->p2, w->ray.origin),
           c = rf_vec3_sub(tri->p3, w->ray.origin);
    double az = comp(a, w->kz), bz = comp(b, w->kz), cz = comp(c, w->kz);
    double ax = comp(a, w->kx) - w->sx * az, ay = comp(a, w->ky) - w->sy * az;
    double bx = comp(b, w->kx) - w->sx * bz, by = comp(b, w->ky) - w->sy * bz;
    double cx = comp(c, w->kx) - w->sx * cz, cy = comp(c, w->ky) - w->sy * cz;
    e[0] = edge_function(cx, cy, bx, by); /* edge p2 -> p3, weight of p1 */
    e[1] = edge_function(ax, ay, cx, cy); /* edge p3 -> p1, weight of p2 */
    e[2] = edge_function(bx, by, ax, ay); /* edge p1 -> p2, weight of p3 */
    if ((e[0] < 0.0 || e[1] < 0.0 || e[2] < 0.0) && (e[0] > 0.0 || e[1] > 0.0 || e[2] > 0.0))
        return 0;
    *det = e[0] + e[1] + e[2];
    if (*det == 0.0)
        return 0;
    double tt = e[0] * (w->sz * az) + e[1] * (w->sz * bz) + e[2] * (w->sz * cz);
    *t = tt / *det;
    return 1;
}

#if defined(__AVX2__) && defined(__FMA__)
#define RF_WATERTIGHT_AVX 1
#endif

#if RF_WATERTIGHT_AVX
/* watertight() with the three vertices in SIMD lanes: every lane makes the scalar kernel's
 * operations in its order (the vertex minus the origin, the shear, the two products of an edge
 * function, their difference or the difference of their fma-recovered errors, the products of
 * t's numerator), so the answers are the same bits; det and the numerator are summed in the
 * scalar order. */
static inline int watertight_avx(const RfWatertightRay *w, const RfTriangle *tri, double e[3], double *det,
                                 double *t)
{
    const __m256d o = _mm256_set_pd(0.0, w->ray.origin.z, w->ray.origin.y, w->ray.origin.x);
    const __m256i lanes = _mm256_loadu_si256((const __m256i *)w->lanes);
    const __m256d shear = _mm256_set_pd(0.0, 0.0, w->sy, w->sx);
    /* p1 and p2 read a fourth double of the triangle (lane 3, never used); p3 is masked */
    __m256d pa = _mm256_sub_pd(_mm256_loadu_pd(&tri->p1.x), o);
    __m256d pb = _mm256_sub_pd(_mm256_loadu_pd(&tri->p2.x), o);
    __m256d pc = _mm256_sub_pd(_mm256_maskload_pd(&tri->p3.x, _mm256_set_epi64x(0, -1, -1, -1)), o);
    /* (v_kx, v_ky, v_kz, v_kz) */
    pa = _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(pa), lanes));
    pb = _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(pb), lanes));
    pc = _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(pc), lanes));
    /* (v_kx - sx v_kz, v_ky - sy v_kz, -, -) */
    __m256d sa = _mm256_sub_pd(pa, _mm256_mul_pd(shear, _mm256_permute4x64_pd(pa, 0xAA)));
    __m256d sb = _mm256_sub_pd(pb, _mm256_mul_pd(shear, _mm256_permute4x64_pd(pb, 0xAA)));
    __m256d sc = _mm256_sub_pd(pc, _mm256_mul_pd(shear, _mm256_permute4x64_pd(pc, 0xAA)));
    /* X = (ax, bx, cx, cx), Y = (ay, by, cy, cy), Z = (az, bz, cz, cz) */
    __m256d X = _mm256_permute2f128_pd(_mm256_unpacklo_pd(sa, sb), _mm256_unpacklo_pd(sc, sc), 0x20);
    __m256d Y = _mm256_permute2f128_pd(_mm256_unpackhi_pd(sa, sb), _mm256_unpackhi_pd(sc, sc), 0x20);
    __m256d Z = _mm256_permute2f128_pd(_mm256_unpacklo_pd(pa, pb), _mm256_unpacklo_pd(pc, pc), 0x31);
    /* edge i = P_x Q_y - P_y Q_x with P = (c, a, b), Q = (b, c, a): edge_function(P, Q) */
    __m256d px = _mm256_permute4x64_pd(X, 0xD2), py = _mm256_permute4x64_pd(Y, 0xD2);
    __m256d qx = _mm256_permute4x64_pd(X, 0xC9), qy = _mm256_permute4x64_pd(Y, 0xC9);
    __m256d a = _mm256_mul_pd(px, qy), b = _mm256_mul_pd(py, qx);
    __m256d exact = _mm256_sub_pd(_mm256_fmsub_pd(px, qy, a), _mm256_fmsub_pd(py, qx, b));
    __m256d E = _mm256_blendv_pd(exact, _mm256_sub_pd(a, b), _mm256_cmp_pd(a, b, _CMP_NEQ_UQ));
    const __m256d zero = _mm256_setzero_pd();
    int neg = _mm256_movemask_pd(_mm256_cmp_pd(E, zero, _CMP_LT_OQ)) & 7;
    int pos = _mm256_movemask_pd(_mm256_cmp_pd(E, zero, _CMP_GT_OQ)) & 7;
    double ev[4], zv[4];
    _mm256_storeu_pd(ev, E);
    e[0] = ev[0], e[1] = ev[1], e[2] = ev[2];
    if (neg && pos)
        return 0;
    *det = e[0] + e[1] + e[2];
    if (*det == 0.0)
        return 0;
    _mm256_storeu_pd(zv, _mm256_mul_pd(E, _mm256_mul_pd(_mm256_set1_pd(w->sz), Z)));
    double tt = zv[0] + zv[1] + zv[2];
    *t = tt / *det;
    return 1;
}
#endif

/* The kernel the ray asks for: the vector one where the machine has it. */
static inline int watertight_any(const RfWatertightRay *w, const RfTriangle *tri, double e[3], double *det,
                                 double *t)
{
#if RF_WATERTIGHT_AVX
    if (!w->scalar)
        return watertight_avx(w, tri, e, det, t);
#endif
    return watertight(w, tri, e, det, t);
}

int rf_watertight_t(const RfWatertightRay *w, const RfTriangle *tri, double *t)
{
    double e[3], det;
    return watertight_any(w, tri, e, &det, t);
}

int rf_watertight_edges(const RfWatertightRay *w, const RfTriangle *tri, double *t, double e[4])
{
    return watertight_any(w, tri, e, &e[3], t);
}

RfVec3 rf_triangle_unit_normal(const RfTriangle *tri) { return triangle_unit_normal(tri); }

/* l1, l2, l3 = U, V, W / det. */
int rf_intersect_triangle_watertight(const RfWatertightRay *w, RfTriangle tri, double t_min,
                                     double t_max, RfHit *hit)
{
    double e[4], t;
    if (!watertight_any(w, &tri, e, &e[3], &t) || !in_range(t, t_min, t_max))
        return 0;
    rf_watertight_hit(&tri, t, e, NULL, hit);
    return 1;
}

int rf_intersect_triangle(RfRay ray, RfTriangle tri, RfTriangleMethod method, double t_min,
                          double t_max, RfHit *hit)
{
    RfWatertightRay w;
    switch (method) {
    case RF_TRIANGLE_SCRIPT:
        return triangle_script(ray, tri, t_min, t_max, hit);
    case RF_TRIANGLE_MOLLER:
        return triangle_moller(ray, tri, t_min, t_max, hit);
    case RF_TRIANGLE_WATERTIGHT:
        rf_watertight_ray(&ray, &w);
        return rf_intersect_triangle_watertight(&w, tri, t_min, t_max, hit);
    }
    return 0;
}

/* NFF cone/cylinder. With k the unit axis, H = |apex - base|, slope m = (r_apex - r_base)/H and
 * q = p - base, a surface point has |q - <q,k> k| = r_base + m <q,k>. For p = e + t d, with
 * the parts of d and e - base perpendicular to k (d_p, o_p) and along it (dz, oz):
 *   |o_p + t d_p|^2 = (r_base + m (oz + t dz))^2
 * a t^2 + 2 bh t + c = 0 with a = |d_p|^2 - m^2 dz^2, bh = <o_p,d_p> - m dz (r_base + m oz),
 * c = |o_p|^2 - (r_base + m oz)^2. The squared equation also holds on the mirrored nappe past
 * the tip, which the axial range [0, H] excludes (radii >= 0 there). */
RfConeFrame rf_cone_frame(RfCone cone)
{
    RfConeFrame f;
    RfVec3 axis = rf_vec3_sub(cone.apex, cone.base);
    f.h = rf_vec3_length(axis);
    f.degenerate = !(f.h > 0.0) || (cone.base_radius == 0.0 && cone.apex_radius == 0.0);
    f.k = rf_vec3_scale(axis, 1.0 / f.h);
    f.m = (cone.apex_radius - cone.base_radius) / f.h;
    return f;
}

int rf_intersect_cone(RfRay ray, RfCone cone, double t_min, double t_max, RfHit *hit)
{
    RfConeFrame f = rf_cone_frame(cone);
    return rf_intersect_cone_framed(&ray, &cone, &f, t_min, t_max, 1, hit);
}

int rf_intersect_cone_framed(const RfRay *rp, const RfCone *cp, const RfConeFrame *frame, double t_min,
                             double t_max, int want_normal, RfHit *hit)
{
    if (frame->degenerate)
        return 0;
    const RfRay ray = rf_ray_read(rp);
    const RfCone cone = *cp;
    const RfVec3 k = frame->k;
    const double h = frame->h, m = frame->m;
    RfVec3 o = rf_vec3_sub(ray.origin, cone.base);
    double dz = rf_vec3_dot(ray.dir, k), oz = rf_vec3_dot(o, k);
    RfVec3 dp = rf_vec3_sub(ray.dir, rf_vec3_scale(k, dz)), op = rf_vec3_sub(o, rf_vec3_scale(k, oz));
    double r0 = cone.base_radius + m * oz; /* radius at the origin's axial position */
    double a = rf_vec3_dot(dp, dp) - m * m * dz * dz;
    double bh = rf_vec3_dot(op, dp) - m * dz * r0;
    /* The quarter discriminant without the cancellation of bh^2 - a c (which loses |op|^2 u of
     * it for a ray far from the cone): by Lagrange's identity (op.dp)^2 - |op|^2 |dp|^2 =
     * -|op x dp|^2, so bh^2 - a c = |r0 dp - m dz op|^2 - |op x dp|^2, taken as a product of a
     * difference and a sum as the sphere's (r - |v|)(r + |v|) */
    double lw = rf_vec3_length(rf_vec3_sub(rf_vec3_scale(dp, r0), rf_vec3_scale(op, m * dz)));
    double lx = rf_vec3_length(rf_vec3_cross(op, dp));
    double t[2], c, sq; /* c = |op|^2 - r0^2, compensated as the sphere's */
    if (!solve_compensated(a, bh, op, r0, (lw - lx) * (lw + lx), &c, t, &sq))
        return 0;
    for (int i = 0; i < 2; i++) {
        if (!in_range(t[i], t_min, t_max))
            continue;
        RfVec3 q = rf_vec3_sub(rf_ray_at(ray, t[i]), cone.base);
        double z = rf_vec3_dot(q, k);
        if (!(z >= 0.0 && z <= h))
            continue;
        hit->t = t[i];
        hit->l[0] = hit->l[1] = hit->l[2] = 0.0;
        if (!want_normal) {
            hit->normal = rf_vec3(0.0, 0.0, 0.0);
            return 1;
        }
        RfVec3 radial = rf_vec3_sub(q, rf_vec3_scale(k, z));
        double rl = rf_vec3_length(radial);
        /* gradient of |q_p| - (r_base + m z): the radial unit vector minus m k */
        RfVec3 n = rl > 0.0 ? rf_vec3_sub(rf_vec3_scale(radial, 1.0 / rl), rf_vec3_scale(k, m))
                            : rf_vec3_scale(k, m > 0.0 ? -1.0 : 1.0);
        hit->normal = rf_vec3_normalize(n);
        return 1;
    }
    return 0;
}
