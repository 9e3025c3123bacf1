C     The user subroutine file of an Abaqus job that uses jointlin (abaqus job=...
C     user=user.f). Abaqus builds a user library only when a job names one; jointlin's
C     UINTER, UEXTERNALDB and URDFIL come from libjointlin_abaqus.a through the link_sl
C     line of abaqus_v6.env, so this file holds only subroutines of your own, none here
C     (do not add a UINTER, UEXTERNALDB or URDFIL: they would be defined twice).
      SUBROUTINE JLSTUB
      RETURN
      END
