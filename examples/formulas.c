/* librefray example: formulas of the lecture script, through the registry (as `refray formula`
 * runs them, JSON in and out) and as plain C functions of the headers.
 *   formulas
 * Prints one line per formula. */
#include <stdio.h>
#include <stdlib.h>

#include <refray/formula.h>
#include <refray/optics.h>
#include <refray/vec.h>

/* one formula of the registry on JSON inputs; prints "ID: outputs" */
static int run(const char *id, const char *inputs)
{
    const RfFormula *f = rf_formula_find(id);
    char *out = NULL;
    if (!f) {
        fprintf(stderr, "no formula %s\n", id);
        return 1;
    }
    int bad = rf_formula_run_json(f, inputs, &out);
    printf("%s: %s\n", id, out ? out : "(out of memory)");
    free(out);
    return bad;
}

int main(void)
{
    int bad = 0;
    printf("%zu formulas\n", rf_formula_count());
    bad |= run("reflect", "{\"n\": [0, 1, 0], \"dir\": [1, -1, 0]}");
    bad |= run("luminance", "{\"rgb\": [1, 0.5, 0.25]}");
    bad |= run("fresnel", "{\"eta_i\": 1, \"eta_t\": 1.5, \"cos_i\": 1}");
    /* the inline vector functions need no registry */
    RfVec3 c = rf_vec3_cross(rf_vec3(1, 0, 0), rf_vec3(0, 1, 0));
    printf("cross: %g %g %g\n", c.x, c.y, c.z);
    /* and the optics of §3.8.1 as C: Snell at 30 degrees from air into glass */
    RfSnell s = rf_snell(1.0, 1.5, 30.0 * RF_PI / 180.0);
    printf("snell: theta_t %.17g deg\n", s.theta_t * 180.0 / RF_PI);
    return bad;
}
