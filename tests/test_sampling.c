/* Sample patterns, warps and filters (sampling.h). Every sampler and warp is χ²-tested against
 * its density, as nori's warptest/chi2test do: a histogram over bins of the parameter domain,
 * expected counts from the density integrated over each bin (adaptive Simpson), bins expecting
 * fewer than 5 pooled, the p-value from the χ² distribution, rejection at α = 0.01 with a Šidák
 * correction over the family; a planted wrong density shows that the routine rejects. Then the
 * structure each pattern promises (one point per stratum, per elementary interval, grid
 * centres), the renderer's historical pixel pattern bit for bit, convergence, the frame and
 * the filters' values. Fixed seeds throughout: the run is deterministic. */
#include <stdint.h>
#include <stdlib.h>

#include "refray/rng.h"
#include "refray/sampling.h"
#include "rf_test.h"

/* ---- χ² machinery ------------------------------------------------------------------------ */

#define CHI2_ALPHA 0.01
/* The χ² tests of this file that must accept (the planted bug is not counted): 8 sampler
 * distributions, 5 shuffle/scramble marginals, 7 warps. */
#define CHI2_FAMILY 20

/* Šidák: the per-test level at which the family's chance of any false rejection is α. */
static double sidak_alpha(void)
{
    return 1.0 - pow(1.0 - CHI2_ALPHA, 1.0 / CHI2_FAMILY);
}

/* The regularized upper incomplete gamma function Q(a, x) = Γ(a, x) / Γ(a): by its power series
 * for P = 1 - Q when x < a + 1, otherwise by its continued fraction evaluated with the modified
 * Lentz method (Abramowitz & Stegun 6.5.29 and 6.5.31). The χ² p-value is Q(dof/2, χ²/2). */
static double gamma_q(double a, double x)
{
    if (x <= 0.0)
        return 1.0;
    double lead = exp(-x + a * log(x) - lgamma(a));
    if (x < a + 1.0) {
        /* P(a, x) = e^-x x^a / Γ(a) * Σ_n x^n / (a (a+1) ... (a+n)) */
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 100000 && term > sum * 1e-17; n++) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - lead * sum;
    }
    /* Q(a, x) = e^-x x^a / Γ(a) * 1/(x+1-a - 1(1-a)/(x+3-a - 2(2-a)/(x+5-a - ...))) */
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; i++) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < tiny)
            d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny)
            c = tiny;
        d = 1.0 / d;
        h *= d * c;
        if (fabs(d * c - 1.0) < 1e-16)
            break;
    }
    return lead * h;
}

typedef struct {
    double stat; /* Σ (O - E)^2 / E over the pooled bins */
    int dof;     /* pooled bins - 1 */
    double p;    /* Q(dof/2, stat/2); 0 when a sample fell where the density is 0 */
} Chi2;

/* The χ² statistic of observed against expected counts. Bins expecting fewer than 5 are pooled
 * into one; a pool still under 5 joins the smallest other bin. */
static Chi2 chi2_eval(const double *obs, const double *expd, int nbins)
{
    Chi2 r = {0.0, 0, 1.0};
    double po = 0.0, pe = 0.0, small_o = 0.0, small_e = INFINITY;
    int kept = 0;
    for (int i = 0; i < nbins; i++) {
        if (obs[i] > 0.0 && expd[i] < 1e-6) {
            r.stat = INFINITY;
            r.p = 0.0;
            return r;
        }
        if (expd[i] < 5.0) {
            po += obs[i];
            pe += expd[i];
            continue;
        }
        kept++;
        r.stat += (obs[i] - expd[i]) * (obs[i] - expd[i]) / expd[i];
        if (expd[i] < small_e) {
            small_e = expd[i];
            small_o = obs[i];
        }
    }
    if (pe > 0.0 || po > 0.0) {
        if (pe < 5.0 && kept > 0) {
            r.stat -= (small_o - small_e) * (small_o - small_e) / small_e;
            po += small_o;
            pe += small_e;
            kept--;
        }
        r.stat += (po - pe) * (po - pe) / pe;
        kept++;
    }
    r.dof = kept - 1;
    r.p = r.dof > 0 ? gamma_q(0.5 * r.dof, 0.5 * r.stat) : 1.0;
    return r;
}

/* A density over a 2D parameter domain (a, b), with respect to da db. */
typedef double (*Density)(double a, double b, const void *ctx);

typedef struct {
    const char *name;
    int na, nb;            /* bins along a and b */
    double a0, a1, b0, b1; /* the binned domain; samples outside go to one extra bin */
    Density density;
    const void *ctx;
} Chi2Setup;

typedef double (*Fn1)(double x, const void *ctx);

static double simpson_step(Fn1 f, const void *ctx, double a, double b, double fa, double fm, double fb,
                           double whole, double eps, int depth)
{
    double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    double flm = f(lm, ctx), frm = f(rm, ctx);
    double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    double delta = left + right - whole;
    /* at least two halvings, so that a lucky first estimate cannot end the recursion */
    if (depth <= 0 || (depth < 18 && fabs(delta) <= 15.0 * eps))
        return left + right + delta / 15.0;
    return simpson_step(f, ctx, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
           simpson_step(f, ctx, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}

/* Adaptive Simpson quadrature of f over [a, b] to an absolute error of about eps. */
static double simpson(Fn1 f, const void *ctx, double a, double b, double eps)
{
    double fa = f(a, ctx), fb = f(b, ctx), fm = f(0.5 * (a + b), ctx);
    return simpson_step(f, ctx, a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), eps, 20);
}

typedef struct {
    const Chi2Setup *s;
    double a, b0, b1;
} BinCtx;

static double inner_fn(double b, const void *ctx)
{
    const BinCtx *c = ctx;
    return c->s->density(c->a, b, c->s->ctx);
}

static double outer_fn(double a, const void *ctx)
{
    BinCtx c = *(const BinCtx *)ctx;
    c.a = a;
    return simpson(inner_fn, &c, c.b0, c.b1, 1e-13);
}

static int bin_of(double x, double lo, double hi, int n)
{
    if (!(x >= lo && x <= hi))
        return -1;
    int i = (int)floor((x - lo) / (hi - lo) * n);
    return i < n ? i : n - 1;
}

/* Histograms count samples (pa[i], pb[i]) and tests them against the setup's density. */
static Chi2 chi2_run(const Chi2Setup *s, const double *pa, const double *pb, int count)
{
    int nbins = s->na * s->nb + 1, out = nbins - 1;
    double *obs = calloc((size_t)nbins, sizeof *obs), *expd = calloc((size_t)nbins, sizeof *expd);
    for (int i = 0; i < count; i++) {
        int ia = bin_of(pa[i], s->a0, s->a1, s->na), ib = bin_of(pb[i], s->b0, s->b1, s->nb);
        obs[ia < 0 || ib < 0 ? out : ia * s->nb + ib] += 1.0;
    }
    double total = 0.0;
    for (int ia = 0; ia < s->na; ia++)
        for (int ib = 0; ib < s->nb; ib++) {
            BinCtx c;
            c.s = s;
            c.a = 0.0;
            c.b0 = s->b0 + (s->b1 - s->b0) * ib / s->nb;
            c.b1 = s->b0 + (s->b1 - s->b0) * (ib + 1) / s->nb;
            double lo = s->a0 + (s->a1 - s->a0) * ia / s->na, hi = s->a0 + (s->a1 - s->a0) * (ia + 1) / s->na;
            double e = count * simpson(outer_fn, &c, lo, hi, 1e-10);
            expd[ia * s->nb + ib] = e;
            total += e;
        }
    expd[out] = fmax(0.0, count - total);
    Chi2 r = chi2_eval(obs, expd, nbins);
    if (getenv("RF_CHI2_VERBOSE"))
        fprintf(stderr, "chi2 %-34s stat %9.2f dof %4d p %.4g\n", s->name, r.stat, r.dof, r.p);
    free(obs);
    free(expd);
    return r;
}

static void check_accept(const Chi2Setup *s, Chi2 r)
{
    rf_test_checks++;
    if (!(r.p > sidak_alpha()))
        rf_test_fail(__FILE__, __LINE__, "%s: rejected, chi2 = %.3f, dof %d, p = %.3g <= %.3g", s->name, r.stat,
                     r.dof, r.p, sidak_alpha());
}

static double density_one(double a, double b, const void *ctx)
{
    (void)a, (void)b, (void)ctx;
    return 1.0;
}

/* ---- the χ² routine itself --------------------------------------------------------------- */

static void t_chi2_pvalue(void)
{
    /* closed forms: dof 2 gives Q(1, x/2) = e^(-x/2); dof 1 gives erfc(sqrt(x/2)) */
    RF_CHECK_NEAR(gamma_q(1.0, 0.5 * 3.0), exp(-1.5), 1e-13, 0);
    RF_CHECK_NEAR(gamma_q(1.0, 0.5 * 40.0), exp(-20.0), 1e-12, 0);
    RF_CHECK_NEAR(gamma_q(0.5, 0.5 * 0.3), erfc(sqrt(0.15)), 1e-13, 0);
    RF_CHECK_NEAR(gamma_q(0.5, 0.5 * 9.0), erfc(sqrt(4.5)), 1e-12, 0);
    /* tables: the 0.99 quantile of χ² with 10 dof is 23.2093, with 100 dof 135.807 */
    RF_CHECK_NEAR(gamma_q(5.0, 0.5 * 23.2093), 0.01, 1e-4, 0);
    RF_CHECK_NEAR(gamma_q(50.0, 0.5 * 135.807), 0.01, 1e-4, 0);
    /* pooling: 4 bins expecting 2.5 each become one bin of 10 */
    double obs[6] = {10, 10, 1, 3, 2, 4}, expd[6] = {10, 10, 2.5, 2.5, 2.5, 2.5};
    Chi2 r = chi2_eval(obs, expd, 6);
    RF_CHECK_EQ_INT(r.dof, 2);
    RF_CHECK_NEAR(r.stat, 0.0, 0, 1e-15);
    /* a pool still under 5 (O 3, E 2) joins the smallest bin (O 10, E 10): (13 - 12)^2 / 12 */
    double obs3[3] = {10, 20, 3}, expd3[3] = {10, 20, 2};
    r = chi2_eval(obs3, expd3, 3);
    RF_CHECK_EQ_INT(r.dof, 1);
    RF_CHECK_NEAR(r.stat, 1.0 / 12.0, 1e-15, 0);
    /* a sample where the density is zero is an outright rejection */
    double obs2[2] = {10, 1}, expd2[2] = {11, 0};
    RF_CHECK(chi2_eval(obs2, expd2, 2).p == 0.0);
    /* Šidák over 20 tests at 0.01: 1 - 0.99^(1/20) */
    RF_CHECK_NEAR(sidak_alpha(), 5.0239e-4, 1e-4, 0);
}

/* ---- samplers as distributions on [0,1)^2 ------------------------------------------------- */

enum { SAMP_PIXELS = 1000, SAMP_N = 16 };

static void t_chi2_samplers(void)
{
    static double xs[SAMP_PIXELS * SAMP_N], ys[SAMP_PIXELS * SAMP_N];
    static const uint32_t dims[2] = {0, 5};
    for (int s = 0; s < RF_SAMPLER_COUNT; s++)
        for (int di = 0; di < 2; di++) {
            int m = 0;
            for (uint64_t px = 0; px < SAMP_PIXELS; px++)
                for (uint32_t k = 0; k < SAMP_N; k++) {
                    double p[2];
                    rf_sample_2d((RfSampler)s, k, SAMP_N, px * 7919 + 11, dims[di], 42, p);
                    xs[m] = p[0];
                    ys[m++] = p[1];
                }
            char name[64];
            snprintf(name, sizeof name, "sampler %s dim %u", rf_sampler_name((RfSampler)s), dims[di]);
            /* stratified and Sobol points are more even than independent ones, so their χ² comes
             * out small (p near 1): the test catches a lack of uniformity, not an excess.
             * The uniform pattern is the same 4 x 4 grid centres in every pixel: it can only match
             * bins that are unions of its cells, where it is exact (χ² = 0) */
            int nb = s == RF_SAMPLER_UNIFORM ? 4 : 10;
            Chi2Setup st = {name, nb, nb, 0, 1, 0, 1, density_one, NULL};
            check_accept(&st, chi2_run(&st, xs, ys, m));
        }
}

/* The marginal of one sample index over many pixels must be uniform, which only a uniformly
 * random shuffle (stratified) or scramble (sobol) gives. */
static void t_chi2_shuffles(void)
{
    enum { P = 8000 };
    static double xs[P], ys[P];
    /* (a) the 1D stratum of sample 0 of 16 */
    for (int i = 0; i < 4000; i++) {
        xs[i] = rf_sample_1d(RF_SAMPLER_STRATIFIED, 0, 16, (uint64_t)i, 3, 9);
        ys[i] = 0.5;
    }
    Chi2Setup a = {"stratified 1d sample 0 of 16", 16, 1, 0, 1, 0, 1, density_one, NULL};
    check_accept(&a, chi2_run(&a, xs, ys, 4000));
    /* (b) the 2D point of sample 0 of 16 (cell and jitter) */
    for (int i = 0; i < 4000; i++) {
        double p[2];
        rf_sample_2d(RF_SAMPLER_STRATIFIED, 0, 16, (uint64_t)i, 3, 9, p);
        xs[i] = p[0];
        ys[i] = p[1];
    }
    Chi2Setup b = {"stratified 2d sample 0 of 16", 8, 8, 0, 1, 0, 1, density_one, NULL};
    check_accept(&b, chi2_run(&b, xs, ys, 4000));
    /* (c) the Latin-hypercube row and column of sample 0 of 12, jointly */
    for (int i = 0; i < P; i++) {
        double p[2];
        rf_sample_2d(RF_SAMPLER_STRATIFIED, 0, 12, (uint64_t)i, 3, 9, p);
        xs[i] = p[0];
        ys[i] = p[1];
    }
    Chi2Setup c = {"lhs 2d sample 0 of 12", 12, 12, 0, 1, 0, 1, density_one, NULL};
    check_accept(&c, chi2_run(&c, xs, ys, P));
    /* (d) the Owen-scrambled Sobol sample 0 of 16 */
    for (int i = 0; i < 4000; i++) {
        double p[2];
        rf_sample_2d(RF_SAMPLER_SOBOL, 0, 16, (uint64_t)i, 3, 9, p);
        xs[i] = p[0];
        ys[i] = p[1];
    }
    Chi2Setup d = {"sobol 2d sample 0 of 16", 8, 8, 0, 1, 0, 1, density_one, NULL};
    check_accept(&d, chi2_run(&d, xs, ys, 4000));
    /* (e) two dimensions of one sample are independent: the strata of dimensions 1 and 2 */
    for (int i = 0; i < P; i++) {
        xs[i] = rf_sample_1d(RF_SAMPLER_STRATIFIED, 0, 16, (uint64_t)i, 1, 9);
        ys[i] = rf_sample_1d(RF_SAMPLER_STRATIFIED, 0, 16, (uint64_t)i, 2, 9);
    }
    Chi2Setup e = {"stratified dims 1 x 2 sample 0", 16, 16, 0, 1, 0, 1, density_one, NULL};
    check_accept(&e, chi2_run(&e, xs, ys, P));
}

/* ---- warps ---------------------------------------------------------------------------------- */

enum { WARP_N = 40000 };

static double azimuth(double x, double y)
{
    double phi = atan2(y, x);
    return phi < 0.0 ? phi + 2.0 * RF_PI : phi;
}

/* Uniform points for the warps; each test its own stream, so that the tests are independent
 * (which Šidák's correction assumes). */
static void random_square(uint64_t stream, int i, double p[2])
{
    rf_sample_2d(RF_SAMPLER_RANDOM, (uint32_t)i, WARP_N, stream, 4, 2024, p);
}

/* The disk's 1/pi in polar coordinates (r, phi): times the Jacobian r. */
static double density_disk(double r, double phi, const void *ctx)
{
    (void)phi, (void)ctx;
    return r / RF_PI;
}

/* Directions in (z = cos theta, phi): the solid angle is dz dphi, so a density by solid angle
 * is the density in these parameters as it is. */
static double density_sphere(double z, double phi, const void *ctx)
{
    (void)z, (void)phi, (void)ctx;
    return 1.0 / (4.0 * RF_PI);
}

static double density_cone(double z, double phi, const void *ctx)
{
    (void)z, (void)phi;
    return rf_warp_cone_pdf(*(const double *)ctx);
}

static RfVec3 dir_of(double z, double phi)
{
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    return rf_vec3(r * cos(phi), r * sin(phi), z);
}

static double density_lobe(double z, double phi, const void *ctx)
{
    return rf_warp_cos_power_pdf(dir_of(z, phi), *(const double *)ctx);
}

static double xs_w[WARP_N], ys_w[WARP_N];

static Chi2 run_lobe(const char *name, uint64_t stream, double n_sample, const double *n_pdf)
{
    /* bins over z in [z_lo, 1] where z_lo leaves 0.2 % of the lobe below it (z^(n+1) = 0.002),
     * so that the bins resolve the lobe; the rest is the extra bin */
    double z_lo = n_sample <= 1.0 ? 0.0 : pow(0.002, 1.0 / (n_sample + 1.0));
    for (int i = 0; i < WARP_N; i++) {
        double p[2];
        random_square(stream, i, p);
        RfVec3 d = rf_warp_cos_power(p[0], p[1], n_sample);
        xs_w[i] = d.z;
        ys_w[i] = azimuth(d.x, d.y);
    }
    Chi2Setup s = {name, 16, 16, z_lo, 1, 0, 2.0 * RF_PI, density_lobe, n_pdf};
    Chi2 r = chi2_run(&s, xs_w, ys_w, WARP_N);
    if (n_sample == *n_pdf)
        check_accept(&s, r);
    return r;
}

static void t_chi2_warps(void)
{
    /* the concentric disk, binned in (r, phi) */
    for (int i = 0; i < WARP_N; i++) {
        double p[2], x, y;
        random_square(1, i, p);
        rf_warp_disk(p[0], p[1], &x, &y);
        xs_w[i] = sqrt(x * x + y * y);
        ys_w[i] = azimuth(x, y);
    }
    Chi2Setup disk = {"warp disk", 16, 16, 0, 1, 0, 2.0 * RF_PI, density_disk, NULL};
    check_accept(&disk, chi2_run(&disk, xs_w, ys_w, WARP_N));

    for (int i = 0; i < WARP_N; i++) {
        double p[2];
        random_square(2, i, p);
        RfVec3 d = rf_warp_sphere(p[0], p[1]);
        xs_w[i] = d.z;
        ys_w[i] = azimuth(d.x, d.y);
    }
    Chi2Setup sph = {"warp sphere", 16, 16, -1, 1, 0, 2.0 * RF_PI, density_sphere, NULL};
    check_accept(&sph, chi2_run(&sph, xs_w, ys_w, WARP_N));

    static const double cos_max[2] = {0.9, -0.5}; /* apertures 25.8 and 120 degrees */
    for (int c = 0; c < 2; c++) {
        for (int i = 0; i < WARP_N; i++) {
            double p[2];
            random_square(3 + (uint64_t)c, i, p);
            RfVec3 d = rf_warp_cone(p[0], p[1], cos_max[c]);
            xs_w[i] = d.z;
            ys_w[i] = azimuth(d.x, d.y);
        }
        char name[64];
        snprintf(name, sizeof name, "warp cone cos_max %g", cos_max[c]);
        Chi2Setup cone = {name, 16, 16, cos_max[c], 1, 0, 2.0 * RF_PI, density_cone, &cos_max[c]};
        check_accept(&cone, chi2_run(&cone, xs_w, ys_w, WARP_N));
    }

    static const double ns[3] = {1, 10, 100};
    for (int j = 0; j < 3; j++) {
        char name[64];
        snprintf(name, sizeof name, "warp cos power n = %g", ns[j]);
        run_lobe(name, 5 + (uint64_t)j, ns[j], &ns[j]);
    }
}

/* The planted bug: samples of the n = 10 lobe checked against the density of n = 11 (the
 * exponent off by one) must be rejected, or the χ² tests above prove nothing. */
static void t_chi2_rejects_wrong_pdf(void)
{
    static const double wrong = 11.0;
    Chi2 r = run_lobe("planted bug: n = 10 vs pdf n = 11", 8, 10.0, &wrong);
    RF_CHECK(r.p < sidak_alpha());
    RF_CHECK(r.p < 1e-12);
}

/* ---- structure of the patterns ------------------------------------------------------------- */

static void t_stratified_cells(void)
{
    static const uint32_t squares[] = {1, 4, 9, 16, 25, 64};
    static const uint32_t others[] = {2, 3, 5, 6, 7, 8, 10, 12, 50};
    for (uint64_t px = 0; px < 40; px++)
        for (uint32_t dim = 0; dim < 4; dim++) {
            for (size_t q = 0; q < sizeof squares / sizeof squares[0]; q++) {
                uint32_t n = squares[q], side = (uint32_t)sqrt((double)n);
                int seen[64] = {0};
                for (uint32_t k = 0; k < n; k++) {
                    double p[2];
                    rf_sample_2d(RF_SAMPLER_STRATIFIED, k, n, px, dim, 5, p);
                    seen[(int)floor(p[0] * side) + side * (int)floor(p[1] * side)]++;
                }
                for (uint32_t c = 0; c < n; c++)
                    RF_CHECK_EQ_INT(seen[c], 1);
            }
            for (size_t q = 0; q < sizeof others / sizeof others[0]; q++) {
                uint32_t n = others[q];
                int col[64] = {0}, row[64] = {0}, str[64] = {0};
                for (uint32_t k = 0; k < n; k++) {
                    double p[2];
                    rf_sample_2d(RF_SAMPLER_STRATIFIED, k, n, px, dim, 5, p);
                    col[(int)floor(p[0] * n)]++;
                    row[(int)floor(p[1] * n)]++;
                    str[(int)floor(rf_sample_1d(RF_SAMPLER_STRATIFIED, k, n, px, dim, 5) * n)]++;
                }
                for (uint32_t c = 0; c < n; c++) {
                    RF_CHECK_EQ_INT(col[c], 1);
                    RF_CHECK_EQ_INT(row[c], 1);
                    RF_CHECK_EQ_INT(str[c], 1);
                }
            }
        }
}

/* Every elementary interval [a 2^-i, (a+1) 2^-i) x [b 2^-(m-i), (b+1) 2^-(m-i)) of area 2^-m holds
 * exactly one of 2^m points: the first 2^m samples, and also samples [2^m, 2^(m+1)) (the shuffled
 * index keeps the (0,2)-sequence property). The 1D samples: one per interval of length 2^-m. */
static void t_sobol_elementary_intervals(void)
{
    static int cnt[512];
    for (uint64_t px = 0; px < 12; px++)
        for (uint32_t dim = 0; dim < 3; dim++)
            for (int m = 0; m <= 8; m++) {
                uint32_t n = 1u << m;
                for (uint32_t start = 0; start <= n; start += n) {
                    double pts[256][2], xs1[256];
                    for (uint32_t k = 0; k < n; k++) {
                        rf_sample_2d(RF_SAMPLER_SOBOL, start + k, n, px, dim, 31, pts[k]);
                        xs1[k] = rf_sample_1d(RF_SAMPLER_SOBOL, start + k, n, px, dim, 31);
                        RF_CHECK(xs1[k] == pts[k][0]);
                    }
                    for (int i = 0; i <= m; i++) {
                        memset(cnt, 0, sizeof cnt);
                        double sx = ldexp(1.0, i), sy = ldexp(1.0, m - i);
                        for (uint32_t k = 0; k < n; k++)
                            cnt[(int)(pts[k][0] * sx) * (1 << (m - i)) + (int)(pts[k][1] * sy)]++;
                        int bad = 0;
                        for (uint32_t c = 0; c < n; c++)
                            bad += cnt[c] != 1;
                        RF_CHECK_EQ_INT(bad, 0);
                    }
                }
            }
    /* progressive: a sample does not depend on n */
    double a[2], b[2];
    rf_sample_2d(RF_SAMPLER_SOBOL, 7, 10, 3, 1, 4, a);
    rf_sample_2d(RF_SAMPLER_SOBOL, 7, 64, 3, 1, 4, b);
    RF_CHECK(a[0] == b[0] && a[1] == b[1]);
}

/* Sobol samples as the first implementation computed them (the second component by a loop over
 * the set bits of the index; now the superset-sum transform, checked against that loop over all
 * 2^32 indices once): the same values to the last bit, so the sobol renders are unchanged. */
static void t_sobol_recorded_values(void)
{
    static const struct {
        uint64_t pixel;
        uint32_t k, dim;
        double x, y;
    } rec[] = {
    {0ull, 0, 0, 0x1.ba72216p-1, 0x1.8758e91p-1},
    {0ull, 0, 5, 0x1.131db472p-1, 0x1.94b16632p-1},
    {0ull, 13, 0, 0x1.9e9ab334p-1, 0x1.3d9e34cp-2},
    {0ull, 13, 5, 0x1.2d07311p-3, 0x1.763fcf12p-1},
    {0ull, 26, 0, 0x1.5f8498p-8, 0x1.6687c43ap-1},
    {0ull, 26, 5, 0x1.b9270092p-1, 0x1.9f0c3274p-2},
    {0ull, 39, 0, 0x1.72186c8p-6, 0x1.f8278c38p-3},
    {0ull, 39, 5, 0x1.5191298ap-1, 0x1.a45826dap-1},
    {0ull, 52, 0, 0x1.63e585b6p-1, 0x1.9d00d98ap-1},
    {0ull, 52, 5, 0x1.d28974f8p-1, 0x1.c57a6ef8p-2},
    {12345ull, 0, 0, 0x1.e879db4ap-1, 0x1.6000e5e8p-3},
    {12345ull, 0, 5, 0x1.f52ef6ep-5, 0x1.ff5265ap-3},
    {12345ull, 13, 0, 0x1.3618658cp-2, 0x1.1a49815p-1},
    {12345ull, 13, 5, 0x1.0a7bcd88p-1, 0x1.4b960e22p-1},
    {12345ull, 26, 0, 0x1.99afd078p-2, 0x1.0a86aa2p-3},
    {12345ull, 26, 5, 0x1.58b8dc3p-1, 0x1.ba949a38p-2},
    {12345ull, 39, 0, 0x1.4a65f382p-1, 0x1.dd713464p-2},
    {12345ull, 39, 5, 0x1.1518a8p-6, 0x1.21ad731p-2},
    {12345ull, 52, 0, 0x1.6a5d3cecp-2, 0x1.5505e4b4p-2},
    {12345ull, 52, 5, 0x1.11f684ap-5, 0x1.cb814e9cp-1},
    {4294967295ull, 0, 0, 0x1.b4aba468p-2, 0x1.86aa43d8p-3},
    {4294967295ull, 0, 5, 0x1.5daecaap-2, 0x1.f773385ap-1},
    {4294967295ull, 13, 0, 0x1.5e7b766p-4, 0x1.5e320f56p-1},
    {4294967295ull, 13, 5, 0x1.6f22e2p-8, 0x1.2dc7b464p-2},
    {4294967295ull, 26, 0, 0x1.f03202a4p-1, 0x1.3966f8ap-4},
    {4294967295ull, 26, 5, 0x1.13158fbep-1, 0x1.649e0426p-1},
    {4294967295ull, 39, 0, 0x1.1bee1d06p-1, 0x1.ce8da48p-4},
    {4294967295ull, 39, 5, 0x1.044a003p-1, 0x1.c3040faap-1},
    {4294967295ull, 52, 0, 0x1.fcbc21cp-3, 0x1.d28f31cp-3},
    {4294967295ull, 52, 5, 0x1.58155e3p-1, 0x1.b619b6dap-1},
    };
    for (size_t i = 0; i < sizeof rec / sizeof rec[0]; i++) {
        double o[2];
        rf_sample_2d(RF_SAMPLER_SOBOL, rec[i].k, 64, rec[i].pixel, rec[i].dim, 7, o);
        if (o[0] != rec[i].x || o[1] != rec[i].y)
            rf_test_fail(__FILE__, __LINE__, "sample %u of pixel %llu, dimension %u: (%a, %a), recorded (%a, %a)",
                         rec[i].k, (unsigned long long)rec[i].pixel, rec[i].dim, o[0], o[1], rec[i].x, rec[i].y);
        rf_test_checks++;
    }
}

/* A run of samples (rf_sample_2d_keyed_run: Sobol four at a time in SIMD lanes) gives each
 * sample's rf_sample_2d value, for every pattern, run length and start. */
static void t_sample_runs(void)
{
    for (int s = 0; s < RF_SAMPLER_COUNT; s++)
        for (uint32_t dim = 0; dim < 3; dim++)
            for (uint32_t count = 1; count <= 13; count += 3)
                for (uint32_t k0 = 0; k0 < 40; k0 += 9) {
                    double run[16][2];
                    RfSampleKeys keys = rf_sample_keys((RfSampler)s, 1234567 + k0, dim, 99);
                    rf_sample_2d_keyed_run(&keys, k0, count, 64, run);
                    for (uint32_t j = 0; j < count; j++) {
                        double one[2];
                        rf_sample_2d((RfSampler)s, k0 + j, 64, 1234567 + k0, dim, 99, one);
                        if (one[0] != run[j][0] || one[1] != run[j][1])
                            rf_test_fail(__FILE__, __LINE__, "%s sample %u: run (%a, %a), alone (%a, %a)",
                                         rf_sampler_name((RfSampler)s), k0 + j, run[j][0], run[j][1], one[0], one[1]);
                        rf_test_checks++;
                    }
                }
}

/* Two dimensions of one Sobol sample must not be paired by their index: without the index
 * shuffle, the 4-strata of both 1D coordinates are functions of the same two bits of k, so the
 * 16 pairs of a pixel fill exactly 4 of the 4 x 4 cells of the (dimension 1, dimension 2) square.
 * A uniformly random pairing fills 16 (1 - C(12,4)/C(16,4)) = 11.65 on average; observed 10.84. */
static void t_sobol_dimensions_decorrelated(void)
{
    int occupied = 0;
    for (uint64_t px = 0; px < 200; px++) {
        int cnt[16] = {0};
        for (uint32_t k = 0; k < 16; k++) {
            double a = rf_sample_1d(RF_SAMPLER_SOBOL, k, 16, px, 1, 3), b = rf_sample_1d(RF_SAMPLER_SOBOL, k, 16, px, 2, 3);
            cnt[(int)(a * 4) * 4 + (int)(b * 4)]++;
        }
        for (int c = 0; c < 16; c++)
            occupied += cnt[c] > 0;
    }
    RF_CHECK(occupied > 9 * 200);
    /* and the 2D samples of two dimensions differ */
    double p[2], q[2];
    rf_sample_2d(RF_SAMPLER_SOBOL, 0, 16, 3, 1, 3, p);
    rf_sample_2d(RF_SAMPLER_SOBOL, 0, 16, 3, 2, 3, q);
    RF_CHECK(p[0] != q[0] && p[1] != q[1]);
}

static void t_uniform_grid(void)
{
    /* n = 6: a = 2 columns, b = 3 rows; n = 5 (prime): one row of 5 cells; n = 32: 4 x 8 (not
     * 5 rows of 7 with the last one partly empty, which was biased); every cell exactly once */
    for (uint64_t px = 0; px < 5; px++) {
        double p[2];
        rf_sample_2d(RF_SAMPLER_UNIFORM, 5, 6, px, 0, px * 13, p);
        RF_CHECK(p[0] == 0.75 && p[1] == 2.5 / 3.0);
        rf_sample_2d(RF_SAMPLER_UNIFORM, 4, 5, px, 0, 1, p);
        RF_CHECK(p[0] == 0.5 && p[1] == 4.5 / 5.0);
        rf_sample_2d(RF_SAMPLER_UNIFORM, 31, 32, px, 0, 1, p);
        RF_CHECK(p[0] == 3.5 / 4.0 && p[1] == 7.5 / 8.0);
        for (uint32_t n = 1; n <= 40; n++) {
            /* another dimension (shuffled): the mean of the n points is the square's centre */
            double mx = 0.0, my = 0.0;
            for (uint32_t k = 0; k < n; k++) {
                rf_sample_2d(RF_SAMPLER_UNIFORM, k, n, px, 3, 7, p);
                mx += p[0], my += p[1];
            }
            RF_CHECK_NEAR(mx / n, 0.5, 1e-12, 0);
            RF_CHECK_NEAR(my / n, 0.5, 1e-12, 0);
        }
        rf_sample_2d(RF_SAMPLER_UNIFORM, 0, 1, px, 0, 1, p);
        RF_CHECK(p[0] == 0.5 && p[1] == 0.5);
        /* the pixel position (dimension 0): cell k in every pixel; another dimension: every cell
         * centre once, in an order of its own */
        int cells[16] = {0}, moved = 0;
        for (uint32_t k = 0; k < 16; k++) {
            rf_sample_2d(RF_SAMPLER_UNIFORM, k, 16, px, 0, 99, p);
            RF_CHECK(p[0] == ((k % 4) + 0.5) / 4.0 && p[1] == ((k / 4) + 0.5) / 4.0);
            rf_sample_2d(RF_SAMPLER_UNIFORM, k, 16, px, 1, 99, p);
            int cx = (int)(p[0] * 4), cy = (int)(p[1] * 4);
            RF_CHECK(p[0] == (cx + 0.5) / 4.0 && p[1] == (cy + 0.5) / 4.0);
            cells[cy * 4 + cx]++;
            moved += cy * 4 + cx != (int)k;
        }
        for (int c = 0; c < 16; c++)
            RF_CHECK_EQ_INT(cells[c], 1);
        RF_CHECK(moved > 0);
        RF_CHECK(rf_sample_1d(RF_SAMPLER_UNIFORM, 2, 8, px, 0, 0) == 2.5 / 8.0);
    }
}

static void t_samples_in_unit_square(void)
{
    static const uint32_t ns[] = {1, 2, 3, 4, 7, 16, 33, 64, 1000};
    int bad = 0;
    for (int s = 0; s < RF_SAMPLER_COUNT; s++)
        for (size_t q = 0; q < sizeof ns / sizeof ns[0]; q++)
            for (uint64_t px = 0; px < 20; px++)
                for (uint32_t dim = 0; dim < 3; dim++)
                    for (uint32_t k = 0; k < ns[q]; k++) {
                        double p[2], a[2];
                        rf_sample_2d((RfSampler)s, k, ns[q], px, dim, 8, p);
                        rf_sample_2d((RfSampler)s, k, ns[q], px, dim, 8, a);
                        double x = rf_sample_1d((RfSampler)s, k, ns[q], px, dim, 8);
                        bad += !(p[0] >= 0.0 && p[0] < 1.0 && p[1] >= 0.0 && p[1] < 1.0 && x >= 0.0 && x < 1.0);
                        /* deterministic: the same arguments give the same bits */
                        bad += memcmp(p, a, sizeof p) != 0;
                        bad += x != rf_sample_1d((RfSampler)s, k, ns[q], px, dim, 8);
                    }
    RF_CHECK_EQ_INT(bad, 0);
    /* the seed changes the samples (except the uniform grid) */
    double p[2], a[2];
    rf_sample_2d(RF_SAMPLER_SOBOL, 3, 16, 5, 0, 1, p);
    rf_sample_2d(RF_SAMPLER_SOBOL, 3, 16, 5, 0, 2, a);
    RF_CHECK(p[0] != a[0] && p[1] != a[1]);
    /* random: exactly the generator's dimensions 2d and 2d + 1 */
    rf_sample_2d(RF_SAMPLER_RANDOM, 3, 16, 5, 4, 1, p);
    RF_CHECK(p[0] == rf_rng_uniform(5, 3, 8, 1) && p[1] == rf_rng_uniform(5, 3, 9, 1));
    RF_CHECK(rf_sample_1d(RF_SAMPLER_RANDOM, 3, 16, 5, 4, 1) == rf_rng_uniform(5, 3, 8, 1));
}

/* Dimension 0 of the stratified sampler is the renderer's historical k x k jitter, bit for bit. */
static void t_stratified_dim0_is_renderer_pattern(void)
{
    static const int ns[2] = {4, 16};
    int bad = 0;
    for (int q = 0; q < 2; q++) {
        int n = ns[q], side = n == 4 ? 2 : 4;
        for (uint64_t px = 0; px < 300; px++)
            for (uint64_t seed = 0; seed < 3; seed++)
                for (int k = 0; k < n; k++) {
                    double u = rf_rng_uniform(px * 1000003, (uint32_t)k, 0, seed);
                    double v = rf_rng_uniform(px * 1000003, (uint32_t)k, 1, seed);
                    double x = ((k % side) + u) / side, y = ((k / side) + v) / side;
                    double p[2];
                    rf_sample_2d(RF_SAMPLER_STRATIFIED, (uint32_t)k, (uint32_t)n, px * 1000003, 0, seed, p);
                    bad += memcmp(&p[0], &x, sizeof x) != 0 || memcmp(&p[1], &y, sizeof y) != 0;
                }
    }
    RF_CHECK_EQ_INT(bad, 0);
}

/* The cell order of sample k: dimension 0 keeps k, the others are shuffled differently per
 * dimension and pixel, and the shuffles reach every permutation. */
static void t_stratified_permutations(void)
{
    enum { D = 31 };
    static int order[D][16];
    for (uint32_t dim = 0; dim < D; dim++)
        for (uint32_t k = 0; k < 16; k++) {
            double p[2];
            rf_sample_2d(RF_SAMPLER_STRATIFIED, k, 16, 12345, dim, 6, p);
            order[dim][k] = (int)floor(p[0] * 4) + 4 * (int)floor(p[1] * 4);
        }
    for (int k = 0; k < 16; k++)
        RF_CHECK_EQ_INT(order[0][k], k);
    int same = 0;
    for (int a = 0; a < D; a++)
        for (int b = a + 1; b < D; b++)
            same += memcmp(order[a], order[b], sizeof order[a]) == 0;
    RF_CHECK_EQ_INT(same, 0);
    /* n = 4 in 1D: all 4! = 24 orders appear among 600 (pixel, dimension) pairs */
    int seen[256] = {0}, distinct = 0;
    for (uint64_t px = 0; px < 200; px++)
        for (uint32_t dim = 1; dim <= 3; dim++) {
            int code = 0;
            for (uint32_t k = 0; k < 4; k++)
                code = code * 4 + (int)floor(rf_sample_1d(RF_SAMPLER_STRATIFIED, k, 4, px, dim, 6) * 4);
            distinct += !seen[code]++;
        }
    RF_CHECK_EQ_INT(distinct, 24);
}

/* ∫∫ x y e^(x+y) over [0,1]^2 = (∫ x e^x)^2 = 1, estimated from 64 samples in each of 200
 * pixels. Observed RMS errors: random 0.145, stratified 0.0232, sobol 0.00785 (uniform, the
 * midpoint rule, 0.00576 in every pixel). For smooth integrands in 2D the rates are n^-1/2
 * (random), n^-1 (jittered) and about n^-3/2 (Owen-scrambled nets). */
static void t_convergence(void)
{
    double rms[RF_SAMPLER_COUNT];
    for (int s = 0; s < RF_SAMPLER_COUNT; s++) {
        double sq = 0.0;
        for (uint64_t px = 0; px < 200; px++) {
            double sum = 0.0;
            for (uint32_t k = 0; k < 64; k++) {
                double p[2];
                rf_sample_2d((RfSampler)s, k, 64, px, 1, 3, p);
                sum += p[0] * p[1] * exp(p[0] + p[1]);
            }
            double err = sum / 64.0 - 1.0;
            sq += err * err;
        }
        rms[s] = sqrt(sq / 200.0);
        if (getenv("RF_CHI2_VERBOSE"))
            fprintf(stderr, "rms %s %.3g\n", rf_sampler_name((RfSampler)s), rms[s]);
    }
    RF_CHECK(rms[RF_SAMPLER_STRATIFIED] < rms[RF_SAMPLER_RANDOM]);
    RF_CHECK(rms[RF_SAMPLER_SOBOL] < rms[RF_SAMPLER_RANDOM]);
    /* jittered 8 x 8: error ~ |grad f| h / sqrt(6 n) with h = 1/8 against sigma_f / sqrt(n),
     * a gain of sigma_f sqrt(6) / (|grad f| h) ~ 6.5 here; demand 4 of both */
    RF_CHECK(rms[RF_SAMPLER_STRATIFIED] < rms[RF_SAMPLER_RANDOM] / 4.0);
    RF_CHECK(rms[RF_SAMPLER_SOBOL] < rms[RF_SAMPLER_RANDOM] / 4.0);
    /* the scramble's quality: a plain random digital shift in place of the full Laine-Karras
     * hash keeps every net but gives 0.0146 here, no better than half the stratified error */
    RF_CHECK(rms[RF_SAMPLER_SOBOL] < rms[RF_SAMPLER_STRATIFIED] / 2.0);
    /* random: the standard error sigma_f / 8, sigma_f^2 = (∫ x^2 e^2x)^2 - 1 = ((e^2 - 1) / 4)^2 - 1 */
    RF_CHECK_NEAR(rms[RF_SAMPLER_RANDOM], sqrt(pow((exp(2.0) - 1.0) / 4.0, 2.0) - 1.0) / 8.0, 0.15, 0);
}

static void t_sampler_names(void)
{
    for (int s = 0; s < RF_SAMPLER_COUNT; s++)
        RF_CHECK_EQ_INT(rf_sampler_parse(rf_sampler_name((RfSampler)s)), s);
    RF_CHECK_STR(rf_sampler_name(RF_SAMPLER_STRATIFIED), "stratified");
    RF_CHECK_EQ_INT(rf_sampler_parse("sobol"), RF_SAMPLER_SOBOL);
    RF_CHECK_EQ_INT(rf_sampler_parse("Sobol"), -1);
    RF_CHECK_EQ_INT(rf_sampler_parse(""), -1);
    RF_CHECK_EQ_INT(rf_sampler_parse(NULL), -1);
    for (int f = 0; f < RF_FILTER_COUNT; f++)
        RF_CHECK_EQ_INT(rf_filter_parse(rf_filter_name((RfFilterKind)f)), f);
    RF_CHECK_STR(rf_filter_name(RF_FILTER_MITCHELL), "mitchell");
    RF_CHECK_EQ_INT(rf_filter_parse("gaussian"), RF_FILTER_GAUSSIAN);
    RF_CHECK_EQ_INT(rf_filter_parse("tent"), -1);
}

/* ---- warps: spot values, ranges, normalisation -------------------------------------------- */

static void t_warp_values(void)
{
    double x, y;
    rf_warp_disk(0.5, 0.5, &x, &y);
    RF_CHECK(x == 0.0 && y == 0.0);
    rf_warp_disk(1.0, 0.5, &x, &y); /* (a, b) = (1, 0): radius 1, angle 0 */
    RF_CHECK(x == 1.0 && y == 0.0);
    rf_warp_disk(1.0, 1.0, &x, &y); /* the corner goes to the diagonal: angle pi/4 */
    RF_CHECK_NEAR(x, sqrt(0.5), 1e-15, 0);
    RF_CHECK_NEAR(y, sqrt(0.5), 1e-15, 0);
    rf_warp_disk(0.25, 0.5, &x, &y); /* (a, b) = (-0.5, 0): radius -0.5 at angle 0 */
    RF_CHECK(x == -0.5 && y == 0.0);
    RfVec3 d = rf_warp_sphere(0.0, 0.3);
    RF_CHECK(d.z == 1.0 && d.x == 0.0 && d.y == 0.0);
    d = rf_warp_sphere(0.5, 0.25); /* the equator at phi = pi/2 */
    RF_CHECK_NEAR(d.y, 1.0, 1e-15, 0);
    RF_CHECK(d.z == 0.0);
    RF_CHECK_NEAR(rf_warp_cone_pdf(-1.0), 1.0 / (4.0 * RF_PI), 1e-15, 0);
    RF_CHECK_NEAR(rf_warp_cone_pdf(0.0), 1.0 / (2.0 * RF_PI), 1e-15, 0);
    d = rf_warp_cone(1.0, 0.0, 0.5); /* the rim: theta = 60 degrees */
    RF_CHECK_NEAR(d.z, 0.5, 1e-15, 0);
    RF_CHECK_NEAR(d.x, sqrt(0.75), 1e-15, 0);
    /* Phong lobe: pdf(+z, n = 1) = 2 / (2 pi); u = 0.25, n = 1 gives z = 0.25^(1/2) = 0.5 */
    RF_CHECK_NEAR(rf_warp_cos_power_pdf(rf_vec3(0, 0, 1), 1.0), 1.0 / RF_PI, 1e-15, 0);
    RF_CHECK(rf_warp_cos_power_pdf(rf_vec3(1, 0, 0), 3.0) == 0.0);
    RF_CHECK(rf_warp_cos_power_pdf(rf_vec3(0, 0.6, -0.8), 3.0) == 0.0);
    d = rf_warp_cos_power(0.25, 0.5, 1.0);
    RF_CHECK_NEAR(d.z, 0.5, 1e-15, 0);
    RF_CHECK_NEAR(d.x, -sqrt(0.75), 1e-15, 0);

    RfTestRng r = {17};
    int bad = 0;
    for (int i = 0; i < 20000; i++) {
        double u = rf_test_uniform(&r, 0, 1), v = rf_test_uniform(&r, 0, 1);
        rf_warp_disk(u, v, &x, &y);
        bad += !(x * x + y * y <= 1.0 + 1e-15);
        RfVec3 a = rf_warp_sphere(u, v), b = rf_warp_cone(u, v, 0.3), c = rf_warp_cos_power(u, v, 7.0);
        bad += fabs(rf_vec3_length(a) - 1.0) > 1e-15 || fabs(rf_vec3_length(b) - 1.0) > 1e-15 ||
               fabs(rf_vec3_length(c) - 1.0) > 1e-15;
        bad += !(b.z >= 0.3 && c.z >= 0.0);
    }
    RF_CHECK_EQ_INT(bad, 0);
    /* near the pole the cone keeps its digits: 1 - z = u (1 - cos_max) = 1e-12 */
    d = rf_warp_cone(1e-4, 0.0, 1.0 - 1e-8);
    RF_CHECK_NEAR(d.x, sqrt(1e-12 * (2.0 - 1e-12)), 1e-6, 0);
}

/* The Phong lobe's density integrates to 1 over the hemisphere (z, phi) in [0,1] x [0, 2 pi). */
static void t_cos_power_normalised(void)
{
    static const double ns[4] = {1, 3.5, 10, 100};
    for (int j = 0; j < 4; j++) {
        Chi2Setup s = {"norm", 1, 1, 0, 1, 0, 2.0 * RF_PI, density_lobe, &ns[j]};
        BinCtx c;
        c.s = &s;
        c.a = 0.0;
        c.b0 = 0.0;
        c.b1 = 2.0 * RF_PI;
        RF_CHECK_NEAR(simpson(outer_fn, &c, 0.0, 1.0, 1e-13), 1.0, 1e-9, 0);
    }
}

static void check_frame(RfVec3 n)
{
    RfFrame f = rf_frame(n);
    RfVec3 c = rf_vec3_cross(f.s, f.t);
    double err = fmax(fabs(rf_vec3_length(f.s) - 1.0), fabs(rf_vec3_length(f.t) - 1.0));
    err = fmax(err, fmax(fabs(rf_vec3_dot(f.s, f.t)), fabs(rf_vec3_dot(f.s, n))));
    err = fmax(err, fabs(rf_vec3_dot(f.t, n)));
    err = fmax(err, fmax(fabs(c.x - n.x), fmax(fabs(c.y - n.y), fabs(c.z - n.z))));
    rf_test_checks++;
    if (!(err < 1e-14))
        rf_test_fail(__FILE__, __LINE__, "frame of (%a %a %a): error %.3g", n.x, n.y, n.z, err);
    RfVec3 w = rf_frame_to_world(&f, rf_vec3(0.2, -0.3, 0.5));
    RfVec3 e = rf_vec3_add(rf_vec3_add(rf_vec3_scale(f.s, 0.2), rf_vec3_scale(f.t, -0.3)), rf_vec3_scale(n, 0.5));
    RF_CHECK(w.x == e.x && w.y == e.y && w.z == e.z);
}

static void t_frame(void)
{
    RfFrame f = rf_frame(rf_vec3(0, 0, 1));
    RF_CHECK(f.s.x == 1.0 && f.s.y == 0.0 && f.s.z == 0.0 && f.t.x == 0.0 && f.t.y == 1.0 && f.t.z == 0.0);
    f = rf_frame(rf_vec3(0, 0, -1)); /* Frisvad's singular case */
    RF_CHECK(f.s.x == 1.0 && f.t.y == -1.0);
    check_frame(rf_vec3(0, 0, -1));
    check_frame(rf_vec3(0, 0, 1));
    check_frame(rf_vec3(1, 0, 0));
    check_frame(rf_vec3(0, 1, 0));
    check_frame(rf_vec3(-0.0, 0, -1));
    check_frame(rf_vec3(1, 0, -0.0));
    check_frame(rf_vec3_normalize(rf_vec3(1e-9, 2e-9, -1)));
    check_frame(rf_vec3_normalize(rf_vec3(1e-9, 0, 1)));
    RfTestRng r = {99};
    for (int i = 0; i < 5000; i++) {
        double u = rf_test_uniform(&r, 0, 1), v = rf_test_uniform(&r, 0, 1);
        check_frame(rf_warp_sphere(u, v));
    }
}

/* ---- filters ---------------------------------------------------------------------------------- */

static double mitchell_row(double x, const void *ctx)
{
    return rf_filter_eval((const RfFilter *)ctx, x, 0.0);
}

static void t_filters(void)
{
    RfFilter box = rf_filter_default(RF_FILTER_BOX), gau = rf_filter_default(RF_FILTER_GAUSSIAN),
             mit = rf_filter_default(RF_FILTER_MITCHELL);
    RF_CHECK(box.kind == RF_FILTER_BOX && box.radius == 0.5);
    RF_CHECK(gau.kind == RF_FILTER_GAUSSIAN && gau.radius == 1.5 && gau.sigma == 0.5);
    RF_CHECK(mit.kind == RF_FILTER_MITCHELL && mit.radius == 2.0);

    RF_CHECK(rf_filter_eval(&box, 0.0, 0.0) == 1.0);
    RF_CHECK(rf_filter_eval(&box, 0.5, -0.5) == 1.0);
    RF_CHECK(rf_filter_eval(&box, 0.3, -0.2) == 1.0);
    RF_CHECK(rf_filter_eval(&box, 0.5000001, 0.0) == 0.0);
    RF_CHECK(rf_filter_eval(&box, 0.0, -0.75) == 0.0);

    /* g(x) = exp(-2 x^2) - exp(-4.5), e^-4.5 = 0.011108996538242306, e^-0.5 = 0.6065306597126334:
     * g(0)^2 = 0.98889100346175769^2, g(0) g(0.5) = 0.98889100346175769 * 0.59542166317439109,
     * g(1) g(-0.25) = (e^-2 - e^-4.5)(e^-0.125 - e^-4.5) = 0.12422628667 * 0.87138790 */
    RF_CHECK_NEAR(rf_filter_eval(&gau, 0.0, 0.0), 0.9779054167276021, 1e-14, 0);
    RF_CHECK_NEAR(rf_filter_eval(&gau, 0.0, 0.5), 0.5888071259793924, 1e-14, 0);
    RF_CHECK_NEAR(rf_filter_eval(&gau, 1.0, -0.25), 0.10824928384200691, 1e-14, 0);
    RF_CHECK(rf_filter_eval(&gau, 1.5, 0.0) == 0.0);
    RF_CHECK(rf_filter_eval(&gau, 0.0, -1.6) == 0.0);
    RF_CHECK(rf_filter_eval(&gau, 1.49, 0.0) > 0.0);

    /* Mitchell-Netravali B = C = 1/3 by hand: k(0) = (6 - 2B)/6 = 8/9; k(1/2) = (7/8 - 3 + 16/3)/6
     * = 77/144; k(1) = 1/18 from either piece; k(3/2) = (-7/3 * 27/8 + 12 * 9/4 - 20 * 3/2 + 32/3)/6
     * = -5/144 (the negative lobe); k(2) = 0 */
    RF_CHECK_NEAR(rf_filter_eval(&mit, 0.0, 0.0), 64.0 / 81.0, 1e-15, 0);
    RF_CHECK_NEAR(rf_filter_eval(&mit, 0.5, 0.0), 77.0 / 144.0 * 8.0 / 9.0, 1e-15, 0);
    RF_CHECK_NEAR(rf_filter_eval(&mit, -1.0, 0.0), 1.0 / 18.0 * 8.0 / 9.0, 1e-14, 0);
    RF_CHECK_NEAR(rf_filter_eval(&mit, 1.0 - 1e-12, 0.0), 1.0 / 18.0 * 8.0 / 9.0, 1e-10, 0);
    RF_CHECK_NEAR(rf_filter_eval(&mit, 1.5, -0.5), -5.0 / 144.0 * 77.0 / 144.0, 1e-14, 0);
    RF_CHECK_NEAR(rf_filter_eval(&mit, 2.0, 0.0), 0.0, 0, 1e-16);
    RF_CHECK(rf_filter_eval(&mit, 2.01, 0.0) == 0.0);
    RF_CHECK(rf_filter_eval(&mit, 0.0, -3.0) == 0.0);
    /* the 1D kernel integrates to 1: ∫ k(x) k(0) dx = k(0), Simpson exact on each cubic piece */
    double integral = 0.0;
    for (int piece = -2; piece < 2; piece++)
        integral += simpson(mitchell_row, &mit, piece, piece + 1, 1e-15);
    RF_CHECK_NEAR(integral / (8.0 / 9.0), 1.0, 0, 1e-9);
    /* a fine midpoint sum agrees, independent of the pieces */
    double mid = 0.0;
    for (int i = 0; i < 40000; i++)
        mid += rf_filter_eval(&mit, -2.0 + (i + 0.5) * 1e-4, 0.0);
    RF_CHECK_NEAR(mid * 1e-4 / (8.0 / 9.0), 1.0, 0, 1e-8);
}

const RfTest rf_tests_sampling[] = {
    {"sampling_chi2_pvalue", t_chi2_pvalue},
    {"sampling_chi2_samplers", t_chi2_samplers},
    {"sampling_chi2_shuffles", t_chi2_shuffles},
    {"sampling_chi2_warps", t_chi2_warps},
    {"sampling_chi2_rejects_wrong_pdf", t_chi2_rejects_wrong_pdf},
    {"sampling_stratified_cells", t_stratified_cells},
    {"sampling_sobol_elementary_intervals", t_sobol_elementary_intervals},
    {"sampling_sobol_recorded_values", t_sobol_recorded_values},
    {"sampling_runs", t_sample_runs},
    {"sampling_sobol_dimensions_decorrelated", t_sobol_dimensions_decorrelated},
    {"sampling_uniform_grid", t_uniform_grid},
    {"sampling_samples_in_unit_square", t_samples_in_unit_square},
    {"sampling_stratified_dim0_is_renderer_pattern", t_stratified_dim0_is_renderer_pattern},
    {"sampling_stratified_permutations", t_stratified_permutations},
    {"sampling_convergence", t_convergence},
    {"sampling_names", t_sampler_names},
    {"sampling_warp_values", t_warp_values},
    {"sampling_cos_power_normalised", t_cos_power_normalised},
    {"sampling_frame", t_frame},
    {"sampling_filters", t_filters},
    RF_TEST_END,
};
