/*
 * Two contact points, three frequency increments, iterated by the store over passes
 * exactly as an Abaqus job sequence would be (UEXTERNALDB-style calls through
 * jointlin_uexternaldb, UINTER-style calls through jointlin_uinter), with this host
 * solving its own 2x2 complex system per increment:
 *
 *   [k1* + kc - m w^2 + i w d1*   -kc                        ] [x1]   [F]
 *   [-kc                          k2* + kc - m w^2 + i w d2* ] [x2] = [0]
 *
 * Point i is a contact to ground, so its slip amplitude is |x_i|. Increments keep their
 * sweep numbers in every pass (JOINTLIN_KINC_ORIGINAL). Records:
 *   preload id p                                     (LINPER = 0, step 1)
 *   inc pass kinc point estimate kstar dstar amplitude
 *   stats pass kind run converged evaluations not_reported
 *   next action pass count kinc...
 */
#include <complex.h>

#include "host.h"

#define NPOINTS 2
#define NINC 3

typedef struct {
    double stress[2], ddsddr[4], dviscous[4], dstructural[4];
    double statev[HOST_NSTATV], sfd, pnewdt, rdisp[2], drdisp[2];
    double props[HOST_NPROPS], coords[3];
    int32_t lopenclose;
    jointlin_uinter_report report;
} point;

static const double zero_time[2] = {0.0, 0.0};

static int32_t call(const jointlin_store *store, point *p, double freqr, int32_t kstep,
                    int32_t kinc, int32_t linper) {
    static const char name[] = "SWEEP-PAIR";
    return jointlin_uinter(store, p->stress, p->ddsddr, p->dviscous, p->dstructural,
                           p->statev, &p->sfd, &p->pnewdt, p->rdisp, p->drdisp, zero_time,
                           0.0, freqr, name, strlen(name), p->props, p->coords, 1.0, 0, 2,
                           HOST_NSTATV, HOST_NPROPS, 3, kstep, kinc, linper, &p->lopenclose,
                           &p->report);
}

static void db(const jointlin_store *store, int32_t lop, int32_t kstep, int32_t kinc) {
    char what[32];
    snprintf(what, sizeof what, "uexternaldb LOP %d", (int)lop);
    host_check(jointlin_uexternaldb(store, lop, 0, zero_time, 0.0, kstep, kinc), what);
}

int main(void) {
    const double omegas[NINC] = HOST_SWEEP_OMEGA;
    const double overclosure[NPOINTS] = {HOST_H_BLOCK, HOST_H_SECOND};
    point pts[NPOINTS];
    memset(pts, 0, sizeof pts);
    for (int j = 0; j < NPOINTS; j++) {
        point *p = &pts[j];
        host_props(p->props, 0.0);
        p->pnewdt = 1.0;
        p->lopenclose = -1;
        p->coords[0] = 10.0 * j;
        /* step 1, general: the preload closes the contact */
        p->rdisp[0] = p->drdisp[0] = overclosure[j];
        host_check(call(NULL, p, 0.0, 1, 1, 0), "uinter LINPER=0");
        double rec[2] = {j + 1, p->stress[0]};
        host_print("preload", rec, 2);
    }

    jointlin_store_config config;
    host_check(jointlin_store_config_default(&config), "config default");
    config.initial_amplitude = HOST_SWEEP_ESTIMATE;
    config.rtol = HOST_SWEEP_RTOL;
    config.max_passes = HOST_SWEEP_MAX_PASSES;
    config.sweep_step = 2;
    config.kinc_numbering = JOINTLIN_KINC_ORIGINAL;
    jointlin_store *store = NULL;
    host_check(jointlin_store_new(&config, &store), "store new");

    for (;;) {
        int32_t action = -1, pass = -1, list[NINC];
        size_t count = 0;
        host_check(jointlin_store_next_action(store, &action, &pass), "next action");
        host_check(jointlin_store_rerun_increments(store, list, NINC, &count), "rerun");
        double next[3 + NINC] = {action, pass, (double)count};
        for (size_t i = 0; i < count; i++) next[3 + i] = list[i];
        host_print("next", next, 3 + (int)count);
        if (action == JOINTLIN_ACTION_RUN_SWEEP) {
            for (int i = 0; i < NINC; i++) list[i] = i + 1;
            count = NINC;
        } else if (action != JOINTLIN_ACTION_RUN_PASS && action != JOINTLIN_ACTION_RUN_FINAL) {
            break;
        }
        /* one analysis: the static step 1 is skipped (the base state is in STATEV) */
        db(store, 0, 0, 0);
        db(store, 5, 2, 0);
        for (size_t i = 0; i < count; i++) {
            int32_t kinc = list[i];
            double omega = omegas[kinc - 1], freqr = omega / (2.0 * HOST_PI);
            db(store, 1, 2, kinc);
            double kstar[NPOINTS], dstar[NPOINTS];
            for (int j = 0; j < NPOINTS; j++) {
                host_check(call(store, &pts[j], freqr, 2, kinc, 1), "uinter LINPER=1");
                kstar[j] = pts[j].ddsddr[3];  /* DDSDDR(2,2) */
                dstar[j] = pts[j].dviscous[3]; /* DVISCOUS(2,2) */
            }
            double complex z11 = HOST_KC + kstar[0] - HOST_MASS * omega * omega +
                                 I * omega * dstar[0];
            double complex z22 = HOST_KC + kstar[1] - HOST_MASS * omega * omega +
                                 I * omega * dstar[1];
            double complex z12 = -HOST_KC;
            double complex det = z11 * z22 - z12 * z12;
            double complex x[NPOINTS] = {HOST_FORCE * z22 / det, -z12 * HOST_FORCE / det};
            for (int j = 0; j < NPOINTS; j++) {
                double amp[2] = {cabs(x[j]), 0.0};
                host_check(jointlin_store_report(store, pts[j].report.point, kinc, amp),
                           "report");
                double rec[7] = {pass,     kinc,     (double)pts[j].report.point,
                                 pts[j].report.amplitude[0], kstar[j], dstar[j], amp[0]};
                host_print("inc", rec, 7);
            }
            db(store, 2, 2, kinc);
        }
        db(store, 6, 2, 0);
        /* The end-of-pass agreement of a job with several ranks, here over one rank (the
         * maximum over itself): size query, summary, agreement (tests/hosts_mpi.rs runs it
         * over several). */
        size_t len = 0;
        int32_t summary[4 + 3 * NINC];
        if (jointlin_store_pass_summary(store, NULL, 0, &len) != JOINTLIN_ERR_SIZE ||
            len > sizeof summary / sizeof summary[0]) {
            fprintf(stderr, "pass summary size query failed\n");
            return 1;
        }
        host_check(jointlin_store_pass_summary(store, summary, len, &len), "pass summary");
        host_check(jointlin_store_pass_agree(store, summary, len), "pass agree");
        db(store, 3, 0, 0);
        jointlin_pass_stats st;
        host_check(jointlin_store_pass_stats(store, pass, &st), "pass stats");
        double rec[6] = {st.pass,           st.kind,           st.increments_run,
                         st.increments_converged, (double)st.evaluations,
                         (double)st.not_reported};
        host_print("stats", rec, 6);
    }
    int64_t n = 0;
    host_check(jointlin_store_point_count(store, &n), "point count");
    double rec[1] = {(double)n};
    host_print("points", rec, 1);
    jointlin_store_free(store);
    return 0;
}
