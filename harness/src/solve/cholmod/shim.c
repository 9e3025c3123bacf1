/* Supernodal sparse Cholesky of a real symmetric matrix through CHOLMOD (SuiteSparse),
 * for harness/src/solve/cholmod/mod.rs. The shim owns the cholmod_common, so the Rust
 * side never depends on CHOLMOD's struct layouts. Integers are SuiteSparse_long
 * (64-bit on LP64 Linux), the `cholmod_l_*` interface. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/cholmod.h>

typedef struct {
    cholmod_common common;
    cholmod_factor *factor;
    SuiteSparse_long n;
} jl_cholmod;

/* Factors A (n×n, CSC with both triangles stored; CHOLMOD reads the upper one, stype 1).
 * Returns 0 with *out set; 1 if A is not positive definite (*minor = the column where
 * the factorization stopped); -1 out of memory or another CHOLMOD error (*status). */
int jl_cholmod_factor(SuiteSparse_long n, const SuiteSparse_long *col_ptr,
                      const SuiteSparse_long *row_idx, const double *values,
                      jl_cholmod **out, SuiteSparse_long *minor, int *status)
{
    *out = NULL;
    *minor = -1;
    *status = 0;
    jl_cholmod *h = calloc(1, sizeof *h);
    if (h == NULL) {
        *status = CHOLMOD_OUT_OF_MEMORY;
        return -1;
    }
    cholmod_l_start(&h->common);
    h->common.print = 0;
    h->common.error_handler = NULL;
    /* Always LLᵀ: CHOLMOD's simplicial LDLᵀ (its choice for small, sparse factors)
     * would factor an indefinite matrix without pivoting instead of refusing it. */
    h->common.supernodal = CHOLMOD_SUPERNODAL;
    h->n = n;
    cholmod_sparse a;
    memset(&a, 0, sizeof a);
    a.nrow = (size_t)n;
    a.ncol = (size_t)n;
    a.nzmax = (size_t)col_ptr[n];
    a.p = (void *)col_ptr;
    a.i = (void *)row_idx;
    a.x = (void *)values;
    a.stype = 1;
    a.itype = CHOLMOD_LONG;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    h->factor = cholmod_l_analyze(&a, &h->common);
    if (h->factor != NULL) {
        cholmod_l_factorize(&a, h->factor, &h->common);
    }
    *status = h->common.status;
    if (h->factor != NULL && h->common.status == CHOLMOD_NOT_POSDEF) {
        *minor = (SuiteSparse_long)h->factor->minor;
    }
    if (h->factor == NULL || h->common.status != CHOLMOD_OK) {
        int code = (h->common.status == CHOLMOD_NOT_POSDEF) ? 1 : -1;
        cholmod_l_free_factor(&h->factor, &h->common);
        cholmod_l_finish(&h->common);
        free(h);
        return code;
    }
    *out = h;
    return 0;
}

/* X = A⁻¹ B for ncol columns (both n × ncol, column-major). Returns 0, or the CHOLMOD
 * status on failure. */
int jl_cholmod_solve(jl_cholmod *h, int64_t ncol, const double *b, double *x)
{
    cholmod_dense rhs;
    memset(&rhs, 0, sizeof rhs);
    rhs.nrow = (size_t)h->n;
    rhs.ncol = (size_t)ncol;
    rhs.nzmax = (size_t)h->n * (size_t)ncol;
    rhs.d = (size_t)h->n;
    rhs.x = (void *)b;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    cholmod_dense *sol = cholmod_l_solve(CHOLMOD_A, h->factor, &rhs, &h->common);
    if (sol == NULL) {
        return h->common.status != CHOLMOD_OK ? h->common.status : CHOLMOD_INVALID;
    }
    memcpy(x, sol->x, (size_t)h->n * (size_t)ncol * sizeof(double));
    cholmod_l_free_dense(&sol, &h->common);
    return 0;
}

/* Frees the factor and the common. */
void jl_cholmod_free(jl_cholmod *h)
{
    if (h != NULL) {
        cholmod_l_free_factor(&h->factor, &h->common);
        cholmod_l_finish(&h->common);
        free(h);
    }
}
