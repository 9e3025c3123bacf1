/*
 * Shared data and helpers of the C host programs (block_stick.c, sweep.c). The Fortran
 * hosts in ../fortran use the same numbers; tests/hosts.rs recomputes every printed
 * number with the Rust API.
 *
 * Output: one record per line, "<name> <number> <number> ...", numbers with 17
 * significant digits (%.17g round-trips a double).
 */
#ifndef JOINTLIN_HOST_H
#define JOINTLIN_HOST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jointlin.h"

/* Block on a plane, Appendix C, in UINTER's stress form with AREA = 1 (pressure =
 * force): mu = 0.3, k_T0 = 1282.7 N/mm, linear normal law k_N = 1e4 N/mm with the
 * overclosure 2e-4 mm, so F_N = p = 2 N; m = 0.002 t, omega = 1.3 rad/s. */
#define HOST_MU 0.3
#define HOST_KT0 1282.7
#define HOST_KN 1.0e4
#define HOST_H_BLOCK 2.0e-4
#define HOST_MASS 0.002
#define HOST_OMEGA 1.3
#define HOST_FORCE 0.5
#define HOST_PI 3.14159265358979323846
/* Mean amplitude of the thesis's stick loop (model.md section 8), the prescribed slip
 * amplitude of the time-domain run and the store's estimate in the steady-state run. */
#define HOST_AMPLITUDE 4.401e-4
/* The sweep (sweep.c, sweep.f90): two masses HOST_MASS, each on a contact point to
 * ground (points 1, 2 at overclosures HOST_H_BLOCK, HOST_H_SECOND: p = 2, 1), coupled
 * by a spring HOST_KC, force HOST_FORCE on mass 1, at three angular frequencies; the
 * store starts from a poor estimate and a tight tolerance, so it needs re-run passes. */
#define HOST_H_SECOND 1.0e-4
#define HOST_KC 600.0
#define HOST_SWEEP_OMEGA {1.3, 300.0, 500.0}
#define HOST_SWEEP_ESTIMATE 1.0e-4
#define HOST_SWEEP_RTOL 1.0e-6
#define HOST_SWEEP_MAX_PASSES 30
#define HOST_NSTATV 57
#define HOST_NPROPS 12

/* Exits with the C API's message when a call fails. */
static inline void host_check(int32_t status, const char *what) {
    if (status != JOINTLIN_OK) {
        char detail[512];
        jointlin_last_error(detail, sizeof detail);
        fprintf(stderr, "%s: %s (%s)\n", what, jointlin_status_message(status), detail);
        exit(2);
    }
}

/* PROPS of the block: Mindlin, thesis rule, mu, k_T0, linear normal law k_N;
 * `damping` 0 viscous (DVISCOUS), 1 structural (DSTRUCTURAL). */
static inline void host_props(double props[HOST_NPROPS], double damping) {
    const double p[HOST_NPROPS] = {JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS, HOST_MU,
                                   HOST_KT0, 0.0, HOST_KN, 0.0, 0.0, 0.0, damping, 0.0, 0.0};
    memcpy(props, p, sizeof p);
}

/* Prints "name v1 v2 ..." with n doubles. */
static inline void host_print(const char *name, const double *v, int n) {
    printf("%s", name);
    for (int i = 0; i < n; i++) printf(" %.17g", v[i]);
    printf("\n");
}

#endif
