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
C
C     POSFIL and DBFILE: the results file URDFIL reads, here a text file that the host
C     program writes (name in the environment variable JOINTLIN_STANDIN_FIL, default
C     jointlin-standin.fil), one record a line: the record key, the number of integer
C     attributes, those integers, then the real attributes. An increment starts with the
C     line "2000 2 <step> <increment>". DBFILE returns each record as Abaqus does:
C     ARRAY(1) its length and ARRAY(2) its key as integers, then the attributes (integers
C     in the first half of their word, as EQUIVALENCE with JRRAY(NPRECD,*) reads them).
C
C     POSFIL(NSTEP, NINC, ARRAY, JRCD): positions the file after the header of step
C     NSTEP, increment NINC; JRCD = 0 if found, else 1.
      SUBROUTINE POSFIL(NSTEP, NINC, ARRAY, JRCD)
      INCLUDE 'ABA_PARAM.INC'
      DIMENSION ARRAY(*)
      COMMON /JLSFIL/ IUNIT, IOPEN
      CHARACTER*512 PATH
      CHARACTER*4096 LINE
      IF (IOPEN .NE. 0) CLOSE (IUNIT, IOSTAT=IOS)
      IOPEN = 0
      CALL GET_ENVIRONMENT_VARIABLE('JOINTLIN_STANDIN_FIL', PATH,
     1 LENP, ISTAT)
      IF (ISTAT .NE. 0 .OR. LENP .EQ. 0) PATH = 'jointlin-standin.fil'
      OPEN (NEWUNIT=IUNIT, FILE=TRIM(PATH), STATUS='OLD',
     1 ACTION='READ', IOSTAT=IOS)
      JRCD = 1
      IF (IOS .NE. 0) RETURN
      IOPEN = 1
   10 READ (IUNIT, '(A)', IOSTAT=IOS) LINE
      IF (IOS .NE. 0) RETURN
      READ (LINE, *, IOSTAT=IOS) KEY
      IF (IOS .NE. 0 .OR. KEY .NE. 2000) GO TO 10
      READ (LINE, *, IOSTAT=IOS) KEY, N, JSTEP, JINC
      IF (IOS .NE. 0) RETURN
      IF (JSTEP .NE. NSTEP .OR. JINC .NE. NINC) GO TO 10
      ARRAY(1) = 0
      JRCD = 0
      RETURN
      END
C
C     DBFILE(LOP, ARRAY, JRCD): LOP = 0 reads the next record of the increment POSFIL
C     found into ARRAY; JRCD = 1 at the end of the increment or file.
      SUBROUTINE DBFILE(LOP, ARRAY, JRCD)
      INCLUDE 'ABA_PARAM.INC'
      DIMENSION ARRAY(*)
      COMMON /JLSFIL/ IUNIT, IOPEN
      CHARACTER*4096 LINE
      INTEGER*4 IWORD(2)
      DIMENSION VALS(600)
      JRCD = 1
      IF (LOP .NE. 0 .OR. IOPEN .EQ. 0) RETURN
      READ (IUNIT, '(A)', IOSTAT=IOS) LINE
      IF (IOS .NE. 0) RETURN
      READ (LINE, *, IOSTAT=IOS) KEY, NINTS
      IF (IOS .NE. 0 .OR. KEY .EQ. 2000) RETURN
C     Count the words of the line: key, count, the attributes.
      NWORD = 0
      INWORD = 0
      DO I = 1, LEN_TRIM(LINE)
         IF (LINE(I:I) .EQ. ' ') THEN
            INWORD = 0
         ELSE IF (INWORD .EQ. 0) THEN
            NWORD = NWORD + 1
            INWORD = 1
         END IF
      END DO
      NATTR = NWORD - 2
      IF (NATTR .GT. 600) RETURN
      READ (LINE, *, IOSTAT=IOS) KEY, NINTS, (VALS(I), I = 1, NATTR)
      IF (IOS .NE. 0) RETURN
      IWORD(2) = 0
      IWORD(1) = NATTR + 2
      ARRAY(1) = TRANSFER(IWORD, 0D0)
      IWORD(1) = KEY
      ARRAY(2) = TRANSFER(IWORD, 0D0)
      DO I = 1, NATTR
         IF (I .LE. NINTS) THEN
            IWORD(1) = NINT(VALS(I))
            ARRAY(I + 2) = TRANSFER(IWORD, 0D0)
         ELSE
            ARRAY(I + 2) = VALS(I)
         END IF
      END DO
      JRCD = 0
      RETURN
      END
C
C     The stand-in results file's unit (NEWUNIT numbers are negative) and whether it is
C     open.
      BLOCK DATA JLSFILD
      COMMON /JLSFIL/ IUNIT, IOPEN
      DATA IUNIT, IOPEN /0, 0/
      END
