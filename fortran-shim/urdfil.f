C     jointlin URDFIL: reports the contact amplitudes an Abaqus steady-state dynamics
C     increment computed to the iteration store, so that UEXTERNALDB can compare them
C     with the amplitudes UINTER linearized at (model.md section 7). Abaqus calls URDFIL
C     at the end of every increment that wrote to the results file (.fil); the deck
C     requests the contact output there:
C       *CONTACT FILE, NSET=<slave nodes>, MASTER=<master surface>, SLAVE=<slave surface>
C       CDISP
C     Record 1504 names the slave node, record 1521 (CDISP) holds its separation and
C     relative tangential displacements, real parts then imaginary parts in a steady-state
C     dynamics step (Abaqus results file format); jl_contact_record turns each CDISP
C     record into the node's amplitudes and calls the store. LOVRWRT = 1: the next
C     increment overwrites this one's records, so the file stays the size of one
C     increment. Only POSFIL and DBFILE are called, as the manual allows in URDFIL.
      SUBROUTINE URDFIL(LSTOP,LOVRWRT,KSTEP,KINC,DTIME,TIME)
C
      USE JOINTLIN_ABAQUS, ONLY: JL_CONTACT_RECORD
      INCLUDE 'ABA_PARAM.INC'
C
      DIMENSION ARRAY(513),JRRAY(NPRECD,513),TIME(2)
      EQUIVALENCE (ARRAY(1),JRRAY(1,1))
C
      CALL POSFIL(KSTEP,KINC,ARRAY,JRCD)
      IF (JRCD .EQ. 0) THEN
         NODE = 0
   10    CONTINUE
         CALL DBFILE(0,ARRAY,JRCD)
         IF (JRCD .EQ. 0) THEN
            KEY = JRRAY(1,2)
            IF (KEY .EQ. 1504) NODE = JRRAY(1,3)
            CALL JL_CONTACT_RECORD(KEY,NODE,KINC,JRRAY(1,1)-2,ARRAY(3))
            GO TO 10
         END IF
      END IF
      LSTOP = 0
      LOVRWRT = 1
      RETURN
      END
