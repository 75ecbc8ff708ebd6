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
 * (rf_hit_offset_origin). The hit point is put back on its surface first (pbrt-v4's
 * reprojection, tracer.c): a sphere's along its radius, a triangle's from its barycentric
 * coordinates, a plane's along its normal, so that its error no longer carries the rounding of
 * t, which grows with the distance the ray travelled. What is left is a few ulps of the numbers
 * the point is made of, and S is their size (RfSurfaceHit.scale): the largest |coordinate| of a
 * triangle's vertices, of a sphere's centre plus its radius, of a plane's point; 2e-15 is 18 u
 * (u = 2^-53), above pbrt's bounds (5 u for spheres, 7 u for triangles). S has no floor, so the
 * policy scales with the scene: whitted scaled by any power of ten from 1e-12 to 1e12 renders
 * the same bits, and moved by 1e8 (a million times its objects' extent) keeps 99.9 % of its
 * values within 1e-6 (tests/test_robust.c; the offset of 1e-13 of |p| and |o| that this
 * replaces lost 1.7 % there). A cone's hit point is not reprojected and its quadratic loses
 * more digits on thin cones; an instance's passes through two rounded matrices: their S is
 * the largest |coordinate| of the hit point and of the ray's origin, times the factors below
 * (the same absolute offsets as before, 1e-9 S and 6.4e-12 S, which `make stress` found free of
 * acne on the SPD tree and rings; below 1e-12 S cones showed acne). `make stress` and
 * `refray-verify --class surface --class acne --class leak --rays 1000000`: 0 acne. */
#define RF_RAY_OFFSET_REL 2e-15
#define RF_RAY_OFFSET_CONE 5e5
#define RF_RAY_OFFSET_INSTANCE 3200.0

#endif
