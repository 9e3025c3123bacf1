C     jointlin UINTER: Abaqus/Standard user interface law forwarding to the C API
C     (jointlin_uinter in include/jointlin.h). Fixed form, as Abaqus compiles it.
C
C     The 47 arguments are Abaqus's (model.md section 7). Forwarded: STRESS, DDSDDR,
C     DVISCOUS, DSTRUCTURAL, STATEV, SFD, PNEWDT, RDISP, DRDISP, TIME, DTIME, FREQR,
C     CINAME (with its length LEN_TRIM(CINAME) passed explicitly, so no compiler's
C     hidden-length convention matters), PROPS, COORDS, AREA, NODE, NDIR, NSTATV,
C     NPROPS, MCRD, KSTEP, KINC, LINPER, LOPENCLOSE. Not used and not changed: FLUX,
C     DDFDDT, DDSDDT, DDFDDR (thermal), SED, SPD, SVD, SCD, TEMP, DTEMP, PREDEF,
C     DPRED, SECNAME, MAINNAME, ALOCALDIR, DROT, CHRLNGTH, NPRED, KIT, LSTATE,
C     LSDI, LPRINT.
C
C     PROPS (NPROPS >= 7; *SURFACE INTERACTION, NAME=.., USER, PROPERTIES=12):
C       1 law 0 Mindlin / 1 Jenkins      2 unloading rule 0 thesis / 1 Masing
C       3 mu                             4 k_T0 per area (PROPS(8) = 0)
C       5 normal law 0 linear / 1 Hertz  6 k_N per area (linear) / E* (Hertz)
C       7 r* (Hertz)                     8 k_T0 source 0 PROPS(4) / 1 Hertz-Mindlin
C       9 G* (PROPS(8) = 1)              10 damping 0 DVISCOUS / 1 DSTRUCTURAL
C      11 quadrature 0 graded / 1 Simpson / 2 Gauss   12 points (0 = default)
C     STATEV (NSTATV >= 57; *SURFACE INTERACTION, ... DEPVAR=57):
C       1 store point id   2 p0   3 h0   4 closed flag   5 dissipation per area
C       6-28, 29-51 hysteresis states of tangential directions 1, 2
C      52-53 k* per area  54-55 d* per area  56 energy per cycle per area
C      57 dissipated power per area
C     The full tables: src/ffi/props.rs and fortran-shim/README.md.
C
C     The iteration store is the one UEXTERNALDB created (module jointlin_abaqus).
C     A failing call stops the analysis through STDB_ABQERR with the C API's message.
      SUBROUTINE UINTER(STRESS,DDSDDR,DVISCOUS,DSTRUCTURAL,FLUX,DDFDDT,
     1 DDSDDT,DDFDDR,STATEV,SED,SFD,SPD,SVD,SCD,PNEWDT,RDISP,DRDISP,
     2 TEMP,DTEMP,PREDEF,DPRED,TIME,DTIME,FREQR,CINAME,SECNAME,MAINNAME,
     3 PROPS,COORDS,ALOCALDIR,DROT,AREA,CHRLNGTH,NODE,NDIR,NSTATV,NPRED,
     4 NPROPS,MCRD,KSTEP,KINC,KIT,LINPER,LOPENCLOSE,LSTATE,LSDI,LPRINT)
C
      USE ISO_C_BINDING, ONLY: C_SIZE_T, C_INT32_T
      USE JOINTLIN, ONLY: JOINTLIN_UINTER
      USE JOINTLIN_ABAQUS, ONLY: JL_STORE, JL_CHECK
      INCLUDE 'ABA_PARAM.INC'
C
      CHARACTER*80 CINAME,SECNAME,MAINNAME
      DIMENSION STRESS(NDIR),DDSDDR(NDIR,NDIR),DVISCOUS(NDIR,NDIR),
     1 DSTRUCTURAL(NDIR,NDIR),FLUX(2),DDFDDT(2,2),DDSDDT(NDIR,2),
     2 DDFDDR(2,NDIR),STATEV(NSTATV),RDISP(NDIR),DRDISP(NDIR),
     3 TEMP(2),DTEMP(2),PREDEF(2,NPRED),DPRED(2,NPRED),TIME(2),
     4 PROPS(NPROPS),COORDS(MCRD),ALOCALDIR(3,3),DROT(2,2)
C
      INTEGER(C_SIZE_T) LENC
      INTEGER(C_INT32_T) ISTAT
C
      LENC = LEN_TRIM(CINAME)
      ISTAT = JOINTLIN_UINTER(JL_STORE(), STRESS, DDSDDR, DVISCOUS,
     1 DSTRUCTURAL, STATEV, SFD, PNEWDT, RDISP, DRDISP, TIME, DTIME,
     2 FREQR, CINAME, LENC, PROPS, COORDS, AREA, NODE, NDIR, NSTATV,
     3 NPROPS, MCRD, KSTEP, KINC, LINPER, LOPENCLOSE)
      CALL JL_CHECK(ISTAT, 'UINTER')
      RETURN
      END
