/*
 * A stand-in for the Abaqus/Standard executable as a user library sees it, for testing
 * the link line of examples/abaqus/abaqus_v6.env (tests/hosts_install.rs):
 *
 *   abaqus_loader <user library>
 *
 * It defines the utility routines Abaqus provides to user subroutines and the jointlin
 * shim calls (STDB_ABQERR, GETRANK, GETNUMCPUS, and POSFIL, DBFILE for URDFIL, here
 * an empty results file; Fortran names: lower case, one trailing
 * underscore, hidden CHARACTER lengths last), loads the user library with
 * dlopen(RTLD_NOW) -- so every undefined symbol of the library must resolve at once, from
 * this program or from the libraries the user library names, as inside Abaqus -- and
 * calls its UEXTERNALDB (LOP 0 without a configuration file: no store) and one
 * general-step UINTER (the call of fortran-shim/shim_check.f90), printing
 *   loader STRESS(1) STRESS(2) LOPENCLOSE
 * It is linked by gcc alone (gcc -rdynamic abaqus_loader.c -ldl): no Fortran runtime and
 * no libjointlin, which the user library must bring itself.
 */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* STDB_ABQERR(LOP, STRING, INTV, REALV, CHARV): LOP -3 ends the analysis. */
void stdb_abqerr_(const int *lop, const char *string, const int *intv, const double *realv,
                  const char *charv, size_t string_len, size_t charv_len) {
    (void)intv;
    (void)realv;
    (void)charv;
    (void)charv_len;
    fprintf(stderr, "STDB_ABQERR %d: %.*s\n", *lop, (int)string_len, string);
    if (*lop == -3) exit(3);
}

/* One process: rank 0 of 1 (what Abaqus returns outside MPI mode). */
void getrank_(int *rank) { *rank = 0; }
void getnumcpus_(int *n) { *n = 1; }
/* The results file has no increment: POSFIL does not find one, DBFILE is at its end. */
void posfil_(const int *nstep, const int *ninc, double *array, int *jrcd) {
    (void)nstep;
    (void)ninc;
    (void)array;
    *jrcd = 1;
}
void dbfile_(const int *lop, double *array, int *jrcd) {
    (void)lop;
    (void)array;
    *jrcd = 1;
}

typedef void uexternaldb_fn(const int *lop, const int *lrestart, const double *time,
                            const double *dtime, const int *kstep, const int *kinc);
typedef void uinter_fn(
    double *stress, double *ddsddr, double *dviscous, double *dstructural, double *flux,
    double *ddfddt, double *ddsddt, double *ddfddr, double *statev, double *sed,
    double *sfd, double *spd, double *svd, double *scd, double *pnewdt, double *rdisp,
    double *drdisp, double *temp, double *dtemp, double *predef, double *dpred,
    double *time, double *dtime, double *freqr, char *ciname, char *secname,
    char *mainname, double *props, double *coords, double *alocaldir, double *drot,
    double *area, double *chrlngth, int *node, int *ndir, int *nstatv, int *npred,
    int *nprops, int *mcrd, int *kstep, int *kinc, int *kit, int *linper,
    int *lopenclose, int *lstate, int *lsdi, int *lprint, size_t ciname_len,
    size_t secname_len, size_t mainname_len);

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s <user library>\n", argv[0]);
        return 2;
    }
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_GLOBAL);
    if (lib == NULL) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 1;
    }
    uexternaldb_fn *uexternaldb;
    uinter_fn *uinter;
    *(void **)&uexternaldb = dlsym(lib, "uexternaldb_");
    *(void **)&uinter = dlsym(lib, "uinter_");
    if (uexternaldb == NULL || uinter == NULL) {
        fprintf(stderr, "dlsym: %s\n", dlerror());
        return 1;
    }
    double time[2] = {0.0, 0.0}, dtime = 0.0;
    int lop = 0, lrestart = 0, kstep = 1, kinc0 = 0;
    uexternaldb(&lop, &lrestart, time, &dtime, &kstep, &kinc0);

    double stress[2] = {0}, ddsddr[4], dv[4], ds[4], t2[4], f[2], statev[57] = {0};
    double rdisp[2] = {2e-4, 1e-5}, drdisp[2] = {2e-4, 1e-5};
    double props[7] = {0.0, 0.0, 0.3, 1282.7, 0.0, 1e4, 0.0};
    double coords[3] = {0}, sed, sfd, spd, svd, scd, pnewdt = 1.0, one = 1.0, zero = 0.0;
    int node = 0, ndir = 2, nstatv = 57, npred = 1, nprops = 7, mcrd = 3, kinc = 1, kit = 0;
    int linper = 0, lopenclose = -1, lstate, lsdi, lprint;
    char ciname[80], secname[80], mainname[80];
    memset(ciname, ' ', 80);
    memset(secname, ' ', 80);
    memset(mainname, ' ', 80);
    memcpy(ciname, "CHECK", 5);
    memcpy(secname, "S", 1);
    memcpy(mainname, "M", 1);
    uinter(stress, ddsddr, dv, ds, f, t2, t2, t2, statev, &sed, &sfd, &spd, &svd, &scd,
           &pnewdt, rdisp, drdisp, f, f, f, f, time, &one, &zero, ciname, secname,
           mainname, props, coords, t2, t2, &one, &one, &node, &ndir, &nstatv, &npred,
           &nprops, &mcrd, &kstep, &kinc, &kit, &linper, &lopenclose, &lstate, &lsdi,
           &lprint, 80, 80, 80);
    printf("loader %.17e %.17e %d\n", stress[0], stress[1], lopenclose);
    return 0;
}
