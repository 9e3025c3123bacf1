/*
 * NTHREADS pthreads call jointlin_uinter concurrently against one store, as
 * Abaqus's threads call UINTER: per increment, every thread handles its share of the
 * points (a LINPER = 0 general-step call on the point's own STATEV, then LINPER = 1 with
 * the store's estimate, then jointlin_store_report), while the main thread makes the
 * UEXTERNALDB calls between increments. The whole multi-pass sweep is run once serially
 * and once threaded; every output double must be bitwise equal. Built with
 * -fsanitize=thread (ThreadSanitizer), or run under valgrind --tool=helgrind/drd, or built
 * with -fsanitize=address,undefined (scripts/robustness.sh).
 *
 * Exit status 0 and "uinter_threads: ok ..." on success.
 */
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jointlin.h"

#define NTHREADS 8
#define NPOINTS 32
#define NINC 3
#define NSTATV 57
#define NPROPS 12

typedef struct {
    double stress[3], ddsddr[9], dviscous[9], dstructural[9];
    double statev[NSTATV], sfd, pnewdt, rdisp[3], drdisp[3], coords[3];
    int32_t lopenclose;
    jointlin_uinter_report report;
} point;

typedef struct {
    const jointlin_store *store;
    point *pts;
    int first, stride, kinc, step;
    double freqr;
    int failed;
} job;

static const double props[NPROPS] = {JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS, 0.3, 1282.7,
                                     0.0, 1.0e4, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
static const double zero_time[2] = {0.0, 0.0};
static const double freqs[NINC] = {3.0, 5.0, 8.0};

static int32_t uinter(const jointlin_store *store, point *p, double freqr, int32_t kinc,
                      int32_t linper) {
    static const char name[] = "THREADS";
    return jointlin_uinter(store, p->stress, p->ddsddr, p->dviscous, p->dstructural,
                           p->statev, &p->sfd, &p->pnewdt, p->rdisp, p->drdisp, zero_time,
                           0.1, freqr, name, sizeof name - 1, props, p->coords, 1.0, 0, 3,
                           NSTATV, NPROPS, 3, 2, kinc, linper, &p->lopenclose, &p->report);
}

/* One increment's work for the points first, first + stride, ... */
static void *work(void *arg) {
    job *j = arg;
    for (int i = j->first; i < NPOINTS; i += j->stride) {
        point *p = &j->pts[i];
        /* general step: move the slips a little (history grows with every call) */
        double s1 = 1e-4 * (1 + i % 5) * (j->step % 2 ? -1.0 : 1.0);
        p->drdisp[0] = 0.0;
        p->drdisp[1] = s1 - p->rdisp[1];
        p->drdisp[2] = -0.5 * s1 - p->rdisp[2];
        p->rdisp[1] = s1;
        p->rdisp[2] = -0.5 * s1;
        if (uinter(NULL, p, 0.0, j->kinc, 0) != JOINTLIN_OK) j->failed = 1;
        if (uinter(j->store, p, j->freqr, j->kinc, 1) != JOINTLIN_OK) j->failed = 1;
        double omega = 2.0 * 3.14159265358979323846 * j->freqr;
        double amp[2];
        for (int d = 0; d < 2; d++) {
            double k = p->ddsddr[4 + 4 * d] + 300.0 - 2.0 * omega * omega;
            double c = omega * p->dviscous[4 + 4 * d];
            amp[d] = (0.05 + 0.004 * i + 0.01 * d) / __builtin_sqrt(k * k + c * c);
        }
        if (jointlin_store_report(j->store, p->report.point, j->kinc, amp) != JOINTLIN_OK)
            j->failed = 1;
    }
    return NULL;
}

static void check(int32_t status, const char *what) {
    if (status != JOINTLIN_OK) {
        char detail[256];
        jointlin_last_error(detail, sizeof detail);
        fprintf(stderr, "%s: %s (%s)\n", what, jointlin_status_message(status), detail);
        exit(2);
    }
}

/* Runs the whole sweep with `nthreads` workers; appends every output double to `trace`. */
static size_t sweep(int nthreads, double *trace, size_t cap) {
    jointlin_store_config cfg;
    check(jointlin_store_config_default(&cfg), "config");
    cfg.initial_amplitude = 1e-4;
    cfg.rtol = 1e-7;
    cfg.kinc_numbering = JOINTLIN_KINC_SEQUENTIAL;
    jointlin_store *store = NULL;
    check(jointlin_store_new(&cfg, &store), "store");
    point *pts = calloc(NPOINTS, sizeof *pts);
    for (int i = 0; i < NPOINTS; i++) {
        pts[i].rdisp[0] = pts[i].drdisp[0] = 1e-4 * (1.0 + 0.05 * i);
        pts[i].coords[0] = 0.5 * i;
        pts[i].pnewdt = 1.0;
        pts[i].lopenclose = -1;
    }
    size_t n = 0;
    int step = 0;
    for (int passes = 0; passes < 30; passes++) {
        int32_t action, pass, list[NINC];
        size_t count = 0;
        check(jointlin_store_next_action(store, &action, &pass), "next");
        if (action == JOINTLIN_ACTION_RUN_SWEEP) {
            for (int i = 0; i < NINC; i++) list[i] = i + 1;
            count = NINC;
        } else if (action == JOINTLIN_ACTION_RUN_PASS || action == JOINTLIN_ACTION_RUN_FINAL) {
            check(jointlin_store_rerun_increments(store, list, NINC, &count), "rerun");
        } else {
            break;
        }
        check(jointlin_uexternaldb(store, 0, 0, zero_time, 0.0, 2, 0), "LOP 0");
        for (size_t i = 0; i < count; i++) {
            int32_t kinc = (int32_t)i + 1;
            check(jointlin_uexternaldb(store, 1, 0, zero_time, 0.0, 2, kinc), "LOP 1");
            pthread_t tid[NTHREADS];
            job jobs[NTHREADS];
            for (int t = 0; t < nthreads; t++) {
                jobs[t] = (job){store, pts, t, nthreads, kinc, step, freqs[list[i] - 1], 0};
                if (nthreads == 1)
                    work(&jobs[t]);
                else if (pthread_create(&tid[t], NULL, work, &jobs[t]) != 0)
                    exit(3);
            }
            for (int t = 0; t < nthreads; t++) {
                if (nthreads > 1) pthread_join(tid[t], NULL);
                if (jobs[t].failed) {
                    fprintf(stderr, "a call failed in thread %d\n", t);
                    exit(4);
                }
            }
            step++;
            for (int p = 0; p < NPOINTS && n + 64 < cap; p++) {
                const point *q = &pts[p];
                memcpy(trace + n, q->stress, sizeof q->stress);
                n += 3;
                memcpy(trace + n, q->ddsddr, sizeof q->ddsddr);
                n += 9;
                memcpy(trace + n, q->dviscous, sizeof q->dviscous);
                n += 9;
                memcpy(trace + n, q->statev, sizeof q->statev);
                trace[n] = 0.0; /* STATEV(1) = store id: registration order is the threads' */
                n += NSTATV;
                trace[n++] = q->report.amplitude[0];
                trace[n++] = q->report.amplitude[1];
            }
            check(jointlin_uexternaldb(store, 2, 0, zero_time, 0.0, 2, kinc), "LOP 2");
        }
        check(jointlin_uexternaldb(store, 3, 0, zero_time, 0.0, 2, 0), "LOP 3");
    }
    int32_t action, pass;
    check(jointlin_store_next_action(store, &action, &pass), "next");
    if (action != JOINTLIN_ACTION_DONE) {
        fprintf(stderr, "sweep not done: action %d after pass %d\n", action, pass);
        exit(5);
    }
    trace[n++] = pass;
    jointlin_store_free(store);
    free(pts);
    return n;
}

int main(void) {
    size_t cap = 1 << 20;
    double *serial = malloc(cap * sizeof *serial), *threaded = malloc(cap * sizeof *threaded);
    size_t ns = sweep(1, serial, cap);
    for (int round = 0; round < 3; round++) {
        size_t nt = sweep(NTHREADS, threaded, cap);
        if (nt != ns || memcmp(serial, threaded, ns * sizeof *serial) != 0) {
            fprintf(stderr, "round %d: threaded run differs from the serial run\n", round);
            return 1;
        }
    }
    printf("uinter_threads: ok, %d threads x 3 rounds = serial run bitwise (%zu doubles, %g passes)\n",
           NTHREADS, ns, serial[ns - 1]);
    free(serial);
    free(threaded);
    return 0;
}
