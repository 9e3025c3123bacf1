C     The user subroutine file of an Abaqus job that uses jointlin (abaqus job=...
C     user=user.f). Abaqus builds a user library only when a job names one; jointlin's
C     UINTER and UEXTERNALDB come from libjointlin_abaqus.a through the link_sl line of
C     abaqus_v6.env, so this file holds only subroutines of your own, none here (do not
C     add a UINTER or UEXTERNALDB: they would be defined twice).
      SUBROUTINE JLSTUB
      RETURN
      END
