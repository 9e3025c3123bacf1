/*
 * Block on a plane, stick case (thesis Appendix C, model.md section 8), through the
 * UINTER-style entry jointlin_uinter of libjointlin.so:
 *
 * 1. time domain (LINPER = 0): the overclosure closes the contact (p = 2), then both
 *    tangential slips follow a prescribed loop for CYCLES cycles of STEPS increments:
 *    s1 = A sin(omega t), s2 = A/2 (1 - cos(omega t)). Record per increment:
 *      td k t s1 s2 p tau1 tau2 kt1 kt2 sfd dissipation(STATEV(5))
 * 2. steady state (LINPER = 1): a store (estimate A) with one increment open; the block
 *    point (base state from step 1, viscous damping) and a second point that never saw
 *    LINPER = 0 (STRESS(1) = p on entry, structural damping) are linearized at
 *    FREQR = omega / (2 pi):
 *      ss id freqr p0 a1 a2 kstar1 kstar2 dvisc1 dvisc2 dstruct1 dstruct2 kn
 *         statev52..57 statev1
 *    then both report A back, the pass ends: "ss_action action pass".
 */
#include "host.h"

#define CYCLES 3
#define STEPS 48

typedef struct {
    double stress[3], ddsddr[9], dviscous[9], dstructural[9];
    double statev[HOST_NSTATV], sfd, pnewdt, rdisp[3], drdisp[3], time[2], dtime;
    double props[HOST_NPROPS], coords[3], area;
    int32_t node, lopenclose;
    jointlin_uinter_report report;
} point;

static void point_init(point *p, double damping, double x) {
    memset(p, 0, sizeof *p);
    host_props(p->props, damping);
    p->pnewdt = 1.0;
    p->area = 1.0;
    p->node = 1;
    p->lopenclose = -1;
    p->coords[0] = x;
}

static int32_t call(const jointlin_store *store, point *p, double freqr, int32_t kstep,
                    int32_t kinc, int32_t linper) {
    static const char name[] = "BLOCK-ON-PLANE";
    return jointlin_uinter(store, p->stress, p->ddsddr, p->dviscous, p->dstructural,
                           p->statev, &p->sfd, &p->pnewdt, p->rdisp, p->drdisp, p->time,
                           p->dtime, freqr, name, strlen(name), p->props, p->coords, p->area,
                           p->node, 3, HOST_NSTATV, HOST_NPROPS, 3, kstep, kinc, linper,
                           &p->lopenclose, &p->report);
}

int main(void) {
    if ((jointlin_abi_version() >> 16) != JOINTLIN_ABI_VERSION_MAJOR) {
        fprintf(stderr, "ABI major version mismatch\n");
        return 2;
    }
    const double a = HOST_AMPLITUDE, omega = HOST_OMEGA;
    const double dt = 2.0 * HOST_PI / (omega * STEPS);
    point block;
    point_init(&block, 0.0, 0.0);

    /* 1. time domain, general step 1 */
    double s_prev[2] = {0.0, 0.0};
    for (int k = 1; k <= CYCLES * STEPS; k++) {
        double t = k * dt;
        double s[2] = {a * sin(omega * t), 0.5 * a * (1.0 - cos(omega * t))};
        block.rdisp[0] = HOST_H_BLOCK;
        block.drdisp[0] = k == 1 ? HOST_H_BLOCK : 0.0;
        for (int i = 0; i < 2; i++) {
            block.rdisp[i + 1] = s[i];
            block.drdisp[i + 1] = s[i] - s_prev[i];
            s_prev[i] = s[i];
        }
        block.time[0] = block.time[1] = t - dt;
        block.dtime = dt;
        host_check(call(NULL, &block, 0.0, 1, k, 0), "uinter LINPER=0");
        if (block.lopenclose != 1) {
            fprintf(stderr, "contact not closed at increment %d\n", k);
            return 2;
        }
        double rec[11] = {k,
                          t,
                          s[0],
                          s[1],
                          block.stress[0],
                          block.stress[1],
                          block.stress[2],
                          block.ddsddr[1 + 1 * 3],
                          block.ddsddr[2 + 2 * 3],
                          block.sfd,
                          block.statev[4]};
        host_print("td", rec, 11);
    }

    /* 2. steady state, step 2, increment 1 */
    jointlin_store_config config;
    host_check(jointlin_store_config_default(&config), "config default");
    config.initial_amplitude = a;
    jointlin_store *store = NULL;
    host_check(jointlin_store_new(&config, &store), "store new");
    const double time[2] = {0.0, 0.0}, freqr = omega / (2.0 * HOST_PI);
    host_check(jointlin_uexternaldb(store, 0, 0, time, 0.0, 0, 0), "LOP 0");
    host_check(jointlin_uexternaldb(store, 5, 0, time, 0.0, 2, 0), "LOP 5");
    host_check(jointlin_uexternaldb(store, 1, 0, time, 0.0, 2, 1), "LOP 1");

    point fresh;
    point_init(&fresh, 1.0, 10.0);
    fresh.stress[0] = block.stress[0]; /* never closed in a general step: p0 on entry */
    point *points[2] = {&block, &fresh};
    for (int j = 0; j < 2; j++) {
        point *p = points[j];
        p->dtime = 0.0;
        p->time[0] = p->time[1] = 0.0;
        host_check(call(store, p, freqr, 2, 1, 1), "uinter LINPER=1");
        double rec[19] = {(double)p->report.point,
                          freqr,
                          p->report.pressure,
                          p->report.amplitude[0],
                          p->report.amplitude[1],
                          p->ddsddr[1 + 1 * 3],
                          p->ddsddr[2 + 2 * 3],
                          p->dviscous[1 + 1 * 3],
                          p->dviscous[2 + 2 * 3],
                          p->dstructural[1 + 1 * 3],
                          p->dstructural[2 + 2 * 3],
                          p->ddsddr[0]};
        memcpy(rec + 12, p->statev + 51, 6 * sizeof(double));
        rec[18] = p->statev[0];
        host_print("ss", rec, 19);
        host_check(jointlin_store_report(store, p->report.point, 1, p->report.amplitude),
                   "report");
    }
    host_check(jointlin_uexternaldb(store, 2, 0, time, 0.0, 2, 1), "LOP 2");
    host_check(jointlin_uexternaldb(store, 6, 0, time, 0.0, 2, 0), "LOP 6");
    host_check(jointlin_uexternaldb(store, 3, 0, time, 0.0, 2, 0), "LOP 3");
    int32_t action = -1, pass = -1;
    host_check(jointlin_store_next_action(store, &action, &pass), "next action");
    double rec[2] = {action, pass};
    host_print("ss_action", rec, 2);
    jointlin_store_free(store);
    return 0;
}
