C     Stand-ins for the Abaqus utility routines the shim calls, for running UINTER and
C     UEXTERNALDB outside Abaqus (tests, the Fortran host programs) in one process.
C     Never link this into an Abaqus user library: Abaqus provides the real ones.
C     Hosts running under MPI link abaqus_standin_mpi.f90 instead.
C
C     STDB_ABQERR(LOP, STRING, INTV, REALV, CHARV): LOP = 1 information, -1 warning,
C     -2 error, -3 error that ends the analysis (here: ERROR STOP 3).
      SUBROUTINE STDB_ABQERR(LOP, STRING, INTV, REALV, CHARV)
      USE ISO_FORTRAN_ENV, ONLY: ERROR_UNIT
      INCLUDE 'ABA_PARAM.INC'
      CHARACTER*(*) STRING
      CHARACTER*8 CHARV(*)
      DIMENSION INTV(*), REALV(*)
      WRITE (ERROR_UNIT, '(A,I0,2A)') 'STDB_ABQERR ', LOP, ': ',
     1 TRIM(STRING)
      IF (LOP .EQ. -3) ERROR STOP 3
      RETURN
      END
C
C     GETRANK(KPROCESSNUM): this process's rank; one process: 0.
      SUBROUTINE GETRANK(KPROCESSNUM)
      INCLUDE 'ABA_PARAM.INC'
      KPROCESSNUM = 0
      RETURN
      END
C
C     GETNUMCPUS(NUMPROCESSES): the number of processes of the analysis; here 1.
      SUBROUTINE GETNUMCPUS(NUMPROCESSES)
      INCLUDE 'ABA_PARAM.INC'
      NUMPROCESSES = 1
      RETURN
      END
