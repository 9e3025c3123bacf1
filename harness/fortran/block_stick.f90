! Block on a plane, stick case, through the Abaqus-signature shim subroutines UINTER and
! UEXTERNALDB (fortran-shim/uinter.f, uexternaldb.f), exactly as Abaqus would call them.
! Same runs and records as ../c/block_stick.c:
!   td k t s1 s2 p tau1 tau2 kt1 kt2 sfd dissipation(STATEV(5))        (LINPER = 0)
!   ss id freqr p0 a1 a2 kstar1 kstar2 dvisc1 dvisc2 dstruct1 dstruct2 kn
!      statev52..57 statev1                                             (LINPER = 1)
!   ss_action action pass
! The store comes from the configuration file named by JOINTLIN_CONFIG
! (block_stick.cfg: initial_amplitude = 4.401e-4).
program block_stick
  use, intrinsic :: iso_c_binding
  use jointlin
  use jointlin_abaqus, only: jl_store, jl_report, jl_close, jl_check
  use host_data
  implicit none
  external :: uinter, uexternaldb

  integer, parameter :: cycles = 3, steps = 48, ndir = 3, mcrd = 3, npred = 1
  type :: point
     real(c_double) :: stress(ndir) = 0, ddsddr(ndir, ndir) = 0
     real(c_double) :: dviscous(ndir, ndir) = 0, dstructural(ndir, ndir) = 0
     real(c_double) :: statev(nstatv) = 0, sfd = 0, pnewdt = 1
     real(c_double) :: rdisp(ndir) = 0, drdisp(ndir) = 0, props(nprops) = 0
     real(c_double) :: coords(mcrd) = 0
     integer :: lopenclose = -1
  end type point
  type(point), target :: block, fresh
  type(point), pointer :: p
  type(jointlin_point_status) :: st
  real(c_double) :: dt, t, s(2), s_prev(2), time(2), freqr, p0, rec(19)
  integer :: k, i, j
  integer(c_int32_t) :: action, pass

  block%props = block_props(0d0)
  dt = 2 * pi / (omega_block * steps)
  s_prev = 0
  ! 1. time domain, general step 1
  do k = 1, cycles * steps
     t = k * dt
     s = [amplitude * sin(omega_block * t), 0.5d0 * amplitude * (1 - cos(omega_block * t))]
     block%rdisp(1) = h_block
     block%drdisp(1) = merge(h_block, 0d0, k == 1)
     do i = 1, 2
        block%rdisp(i + 1) = s(i)
        block%drdisp(i + 1) = s(i) - s_prev(i)
     end do
     s_prev = s
     time = t - dt
     call call_uinter(block, 0d0, dt, time, 1, k, 0)
     if (block%lopenclose /= 1) error stop 'contact not closed'
     call record('td', [real(k, c_double), t, s, block%stress, block%ddsddr(2, 2), &
          block%ddsddr(3, 3), block%sfd, block%statev(5)])
  end do

  ! 2. steady state, step 2, increment 1
  time = 0
  freqr = omega_block / (2 * pi)
  call uexternaldb(0, 0, time, 0d0, 0, 0)
  call uexternaldb(5, 0, time, 0d0, 2, 0)
  call uexternaldb(1, 0, time, 0d0, 2, 1)
  fresh%props = block_props(1d0)
  fresh%coords(1) = 10
  fresh%stress(1) = block%stress(1) ! never closed in a general step: p0 on entry
  do j = 1, 2
     if (j == 1) then
        p => block
     else
        p => fresh
     end if
     p0 = merge(p%statev(2), p%stress(1), p%statev(4) == 1)
     call call_uinter(p, freqr, 0d0, time, 2, 1, 1)
     call jl_check(jointlin_store_point_status(jl_store(), int(p%statev(1), c_int64_t), &
          1_c_int32_t, st), 'point status')
     rec(1:12) = [p%statev(1), freqr, p0, st%estimate, p%ddsddr(2, 2), p%ddsddr(3, 3), &
          p%dviscous(2, 2), p%dviscous(3, 3), p%dstructural(2, 2), p%dstructural(3, 3), &
          p%ddsddr(1, 1)]
     rec(13:18) = p%statev(52:57)
     rec(19) = p%statev(1)
     call record('ss', rec)
     call jl_report(int(p%statev(1), c_int64_t), 1, st%estimate)
  end do
  call uexternaldb(2, 0, time, 0d0, 2, 1)
  call uexternaldb(6, 0, time, 0d0, 2, 0)
  call uexternaldb(3, 0, time, 0d0, 2, 0)
  call jl_check(jointlin_store_next_action(jl_store(), action, pass), 'next action')
  call record('ss_action', [real(action, c_double), real(pass, c_double)])
  call jl_close()

contains

  subroutine call_uinter(q, freqr, dtime, time, kstep, kinc, linper)
    type(point), intent(inout) :: q
    real(c_double), intent(in) :: freqr, dtime, time(2)
    integer, intent(in) :: kstep, kinc, linper
    character(len=80) :: ciname, secname, mainname
    real(c_double) :: flux(2), ddfddt(2, 2), ddsddt(ndir, 2), ddfddr(2, ndir), sed, spd, &
         svd, scd, temp(2), dtemp(2), predef(2, npred), dpred(2, npred), alocaldir(3, 3), &
         drot(2, 2), area, chrlngth
    integer :: lstate, lsdi, lprint
    ciname = 'BLOCK-ON-PLANE'
    secname = 'SLAVE'
    mainname = 'MAIN'
    flux = 0; ddfddt = 0; ddsddt = 0; ddfddr = 0; sed = 0; spd = 0; svd = 0; scd = 0
    temp = 0; dtemp = 0; predef = 0; dpred = 0; alocaldir = 0; drot = 0
    area = 1; chrlngth = 1; lstate = 0; lsdi = 0; lprint = 0
    call uinter(q%stress, q%ddsddr, q%dviscous, q%dstructural, flux, ddfddt, ddsddt, &
         ddfddr, q%statev, sed, q%sfd, spd, svd, scd, q%pnewdt, q%rdisp, q%drdisp, temp, &
         dtemp, predef, dpred, time, dtime, freqr, ciname, secname, mainname, q%props, &
         q%coords, alocaldir, drot, area, chrlngth, 1, ndir, nstatv, npred, nprops, mcrd, &
         kstep, kinc, 0, linper, q%lopenclose, lstate, lsdi, lprint)
  end subroutine call_uinter
end program block_stick
