/* refray: the numeric policy. Every tolerance of the library lives here, with its reason.
 * Exact formulas use no tolerance at all; these only decide classifications (is a matrix
 * singular, is a basis orthonormal) that have no exact answer in floating point. */
#ifndef REFRAY_NUMERIC_H
#define REFRAY_NUMERIC_H

/* Relative pivot size below which Gaussian elimination calls a matrix singular: a pivot
 * |p| <= RF_SINGULAR_REL * max|a_ij| means the matrix is within a few ulps of a singular one
 * (the elimination error is O(n * eps) relative to the largest entry, eps = 2.2e-16). */
#define RF_SINGULAR_REL 1e-13

/* Tolerance for the structural predicates "orthogonal", "orthonormal", "similarity":
 * |(M^T M)_ij - lambda * delta_ij| <= RF_STRUCTURE_TOL * lambda. A product of a few exact
 * rotations built from sin/cos is orthonormal to about 1e-15; 1e-12 leaves room for chains of
 * transforms while rejecting any genuine non-uniform scale or shear. */
#define RF_STRUCTURE_TOL 1e-12

/* Grazing transmission (§3.8.1): sin^2(theta_t) = (eta_i/eta_t)^2 sin^2(theta_i) is computed
 * with a relative error of a few ulps (the degree-to-radian conversion, sin or 1 - cos^2, the
 * ratio, the squares), so an incidence given exactly at the critical angle can come out as
 * 1 + 1e-15. FORMULAS.md pins "total internal reflection only beyond the critical angle": a
 * value up to 1 + RF_TIR_SLACK counts as grazing (theta_t = 90 deg, cos_t = 0). 1e-14 is ~45
 * ulps of 1; for eta_i/eta_t = 1.5 it shifts the TIR onset by under 5e-15 rad. */
#define RF_TIR_SLACK 1e-14

/* A polygon is degenerate (collinear) when twice its vector area |N| is at most this times
 * the square of its extent: decimal coordinates of truly collinear points leave |N| of a few
 * ulps of ext^2 (1e-16), while the thinnest SPD polygon has |N| / ext^2 above 1e-4. The same
 * ratio decides "up is parallel to the view direction" and the convexity hint.
 */
#define RF_SCENE_DEGENERATE_REL 1e-12

/* Self-intersection (§3.8): a shadow, reflected or refracted ray starts at the hit point moved
 * off the surface, along the geometric normal to the side it leaves by, by RF_RAY_OFFSET_REL * S
 * (rf_hit_offset_origin). S is the largest |coordinate| of the hit point and of the ray's
 * origin (RfSurfaceHit.scale): p = o + t d carries a rounding error of a few ulps of them
 * (2.2e-16 relative; the stable sphere and watertight triangle tests keep t to a few ulps), so
 * 1e-13 is ~450 times that error. S has no floor, so the policy scales with the scene: whitted
 * scaled by any power of ten from 1e-12 to 1e12 renders the same bits, and moved by 1e6 it keeps
 * 99.97 % of its pixels within 1e-6 (tests/test_robust.c). A cone's quadratic loses more digits
 * on thin cones, and an instance's hit passes through two rounded matrices: their S is
 * multiplied by the factors below (`make stress` measured acne on the SPD tree and rings at
 * 1e-12 without them; 0 with). */
#define RF_RAY_OFFSET_REL 1e-13
#define RF_RAY_OFFSET_CONE 1e4
#define RF_RAY_OFFSET_INSTANCE 64.0

#endif
