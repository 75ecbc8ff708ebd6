/* refray: square matrices as value types (row-major m[row][col]), and the generic n x n
 * routines (n <= 4) that every fixed-size function forwards to, so that each algorithm
 * (product, inverse, solve) exists once. */
#ifndef REFRAY_MAT_H
#define REFRAY_MAT_H

#include "refray/status.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct { double m[2][2]; } RfMat2;
typedef struct { double m[3][3]; } RfMat3;
typedef struct { double m[4][4]; } RfMat4;

#define RF_MATN_MAX 4

/* Generic routines on row-major n x n arrays (1 <= n <= RF_MATN_MAX). Outputs may alias inputs. */
void rf_matn_identity(int n, double *out);
void rf_matn_mul(int n, const double *a, const double *b, double *out);
void rf_matn_transpose(int n, const double *a, double *out);
void rf_matn_mul_vec(int n, const double *a, const double *x, double *out);
/* Determinant by partial-pivoting elimination. */
double rf_matn_det(int n, const double *a);
/* Inverse by Gauss-Jordan elimination with partial pivoting; RF_ERR_SINGULAR when a pivot
 * falls under RF_SINGULAR_REL times the largest entry (numeric.h), RF_ERR_DOMAIN for a NaN or
 * infinite entry. out is left untouched then. */
RfStatus rf_matn_inverse(int n, const double *a, double *out);
/* Solves a x = b (same pivoting and singularity rule). */
RfStatus rf_matn_solve(int n, const double *a, const double *b, double *x);
/* max_ij |(A^T A)_ij - lambda delta_ij| <= RF_STRUCTURE_TOL * lambda for some lambda > 0:
 * the columns are orthogonal with one common length sqrt(lambda) (rotation x uniform scale,
 * possibly with a reflection). *lambda gets the mean squared column length. */
int rf_matn_is_similarity(int n, const double *a, double *lambda);
/* As above with lambda = 1. */
int rf_matn_is_orthogonal(int n, const double *a);
/* Embeds an n x n linear part a and a translation b into the (n+1) x (n+1) homogeneous
 * matrix (§4.5.2). out has (n+1)^2 entries. */
void rf_matn_affine(int n, const double *a, const double *b, double *out);

/* Fixed sizes. */
RfMat2 rf_mat2_identity(void);
RfMat2 rf_mat2_mul(RfMat2 a, RfMat2 b);
RfVec2 rf_mat2_mul_vec(RfMat2 a, RfVec2 x);

RfMat3 rf_mat3_identity(void);
RfMat3 rf_mat3_rows(RfVec3 r0, RfVec3 r1, RfVec3 r2);
RfMat3 rf_mat3_mul(RfMat3 a, RfMat3 b);
RfMat3 rf_mat3_transpose(RfMat3 a);
RfVec3 rf_mat3_mul_vec(RfMat3 a, RfVec3 x);
double rf_mat3_det(RfMat3 a);
RfStatus rf_mat3_inverse(RfMat3 a, RfMat3 *out);

RfMat4 rf_mat4_identity(void);
RfMat4 rf_mat4_mul(RfMat4 a, RfMat4 b);
RfMat4 rf_mat4_transpose(RfMat4 a);
RfVec4 rf_mat4_mul_vec(RfMat4 a, RfVec4 x);
double rf_mat4_det(RfMat4 a);
RfStatus rf_mat4_inverse(RfMat4 a, RfMat4 *out);
/* The upper-left 3 x 3 (linear) part, and the homogeneous matrix of A x + b. */
RfMat3 rf_mat4_linear(RfMat4 a);
RfMat4 rf_mat4_affine(RfMat3 a, RfVec3 b);

#ifdef __cplusplus
}
#endif

#endif
