! Smallest program over the shim: UEXTERNALDB at LOP 0 without a configuration file (no
! store), a general-step UINTER call, and the ABI version of the loaded libjointlin.so.
program shim_check
  use jointlin, only: jointlin_abi_version, JOINTLIN_ABI_VERSION_MAJOR
  implicit none
  external :: uinter, uexternaldb
  double precision :: time(2) = 0, stress(2) = 0, ddsddr(2, 2), dv(2, 2), ds(2, 2)
  double precision :: statev(57) = 0, rdisp(2) = [2d-4, 1d-5], drdisp(2) = [2d-4, 1d-5]
  double precision :: props(7) = [0d0, 0d0, 0.3d0, 1282.7d0, 0d0, 1d4, 0d0]
  double precision :: coords(3) = 0, t2(2, 2), f(2), sed, sfd, spd, svd, scd, pnewdt = 1
  integer :: lopenclose = -1, lstate, lsdi, lprint
  character(len=80) :: ciname = 'CHECK', secname = 'S', mainname = 'M' ! CHARACTER*80 in UINTER
  call uexternaldb(0, 0, time, 0d0, 1, 0)
  call uinter(stress, ddsddr, dv, ds, f, t2, t2, t2, statev, sed, sfd, spd, svd, scd, &
       pnewdt, rdisp, drdisp, f, f, f, f, time, 1d0, 0d0, ciname, secname, mainname, props, &
       coords, t2, t2, 1d0, 1d0, 0, 2, 57, 1, 7, 3, 1, 1, 0, 0, lopenclose, lstate, lsdi, &
       lprint)
  if (ishft(jointlin_abi_version(), -16) /= JOINTLIN_ABI_VERSION_MAJOR) error stop 'ABI'
  write (*, '(a,2(1x,es25.17e3),1x,i0)') 'shim_check', stress, lopenclose
end program shim_check
