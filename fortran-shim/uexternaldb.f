C     jointlin UEXTERNALDB: drives the iteration store from Abaqus's analysis events
C     (jointlin_uexternaldb in include/jointlin.h). Fixed form, as Abaqus compiles it.
C
C     LOP 0 (start of analysis) and 4 (start of a restart analysis): at the first call
C     in the process, create the store from the configuration file ($JOINTLIN_CONFIG,
C     else ./jointlin.cfg; see jointlin_abaqus.f90); without one, jointlin runs
C     without a store and these calls do nothing. Every LOP is then forwarded. Before
C     LOP 3 (end of analysis) the ranks of a job with several processes agree on the
C     increments to re-run (JL_AGREE: MPI or files); after it the next action is
C     logged to stderr (the job's .log) and written to the action file when one is
C     configured (rank 0).
C
C     Abaqus calls UEXTERNALDB from one thread per process, never at the same time as
C     UINTER; every process (rank) calls it with the same LOP sequence.
      SUBROUTINE UEXTERNALDB(LOP,LRESTART,TIME,DTIME,KSTEP,KINC)
C
      USE ISO_C_BINDING, ONLY: C_ASSOCIATED, C_INT32_T
      USE JOINTLIN, ONLY: JOINTLIN_UEXTERNALDB
      USE JOINTLIN_ABAQUS, ONLY: JL_STORE, JL_OPEN, JL_CHECK,
     1 JL_AFTER_PASS, JL_AGREE
      INCLUDE 'ABA_PARAM.INC'
C
      DIMENSION TIME(2)
      INTEGER(C_INT32_T) ISTAT
C
      IF (LOP.EQ.0 .OR. LOP.EQ.4) CALL JL_OPEN(LOP)
      IF (.NOT. C_ASSOCIATED(JL_STORE())) RETURN
      IF (LOP.EQ.3) CALL JL_AGREE
      ISTAT = JOINTLIN_UEXTERNALDB(JL_STORE(), LOP, LRESTART, TIME,
     1 DTIME, KSTEP, KINC)
      CALL JL_CHECK(ISTAT, 'UEXTERNALDB')
      IF (LOP.EQ.3) CALL JL_AFTER_PASS
      RETURN
      END
