! UINTER through the Abaqus-signature shim from many OpenMP threads at once against one
! store, as Abaqus's threads call it (tests/threads.rs): per increment every thread handles
! its share of 32 points (a general-step LINPER = 0 call on the point's own STATEV, then
! LINPER = 1 with the store's estimate, then jl_report from the same thread), while the
! master thread makes the UEXTERNALDB calls between increments. A multi-pass sweep until
! the store is done; after each increment every point's outputs are printed in point
! order (STATEV(1), the store id, is left out: ids follow the order of registration,
! which is the threads'). The output must not depend on OMP_NUM_THREADS; the number of
! threads that handled points is written to stderr.
! Configuration: uinter_omp.cfg through JOINTLIN_CONFIG.
program uinter_omp
  use, intrinsic :: iso_c_binding
  use jointlin
  use jointlin_abaqus, only: jl_store, jl_report, jl_check
  use omp_lib, only: omp_get_thread_num
  implicit none
  external :: uinter, uexternaldb

  integer, parameter :: npoints = 32, ninc = 3, ndir = 3, mcrd = 3, npred = 1
  integer, parameter :: nstatv = 57, nprops = 12
  real(c_double), parameter :: freqs(ninc) = [3d0, 5d0, 8d0]
  real(c_double), parameter :: pi = 3.14159265358979323846d0
  real(c_double) :: stress(ndir, npoints) = 0, ddsddr(ndir, ndir, npoints) = 0, &
       dviscous(ndir, ndir, npoints) = 0, dstructural(ndir, ndir, npoints) = 0, &
       statev(nstatv, npoints) = 0, sfd(npoints) = 0, pnewdt(npoints) = 1, &
       rdisp(ndir, npoints) = 0, drdisp(ndir, npoints) = 0, props(nprops), &
       coords(mcrd, npoints) = 0, time(2) = 0
  integer :: lopenclose(npoints) = -1
  ! Per point, the OpenMP thread that handled it last: how many threads worked is
  ! written to stderr (stdout must not depend on OMP_NUM_THREADS).
  integer :: worker(npoints) = -1
  integer :: i, j, step, count, list(ninc)
  integer(c_int32_t) :: action, pass, k(ninc)
  integer(c_size_t) :: n

  props = [0d0, 0d0, 0.3d0, 1282.7d0, 0d0, 1d4, 0d0, 0d0, 0d0, 0d0, 0d0, 0d0]
  do j = 1, npoints
     rdisp(1, j) = 1d-4 * (1 + 0.05d0 * (j - 1))
     drdisp(1, j) = rdisp(1, j)
     coords(1, j) = 0.5d0 * (j - 1)
  end do
  step = 0
  action = JOINTLIN_ACTION_RUN_SWEEP ! the store appears at the first LOP 0
  do
     if (action == JOINTLIN_ACTION_RUN_SWEEP) then
        count = ninc
        list = [(i, i = 1, ninc)]
     else if (action == JOINTLIN_ACTION_RUN_PASS .or. action == JOINTLIN_ACTION_RUN_FINAL) then
        call jl_check(jointlin_store_rerun_increments(jl_store(), k, int(ninc, c_size_t), n), &
             'rerun increments')
        count = int(n)
        list(1:count) = k(1:count)
     else
        exit
     end if
     call uexternaldb(0, 0, time, 0d0, 2, 0)
     do i = 1, count
        call uexternaldb(1, 0, time, 0d0, 2, i)
        !$omp parallel do schedule(static, 1)
        do j = 1, npoints
           call work(j, i, step, freqs(list(i)))
           worker(j) = omp_get_thread_num()
        end do
        !$omp end parallel do
        step = step + 1
        do j = 1, npoints
           write (*, '(a,2(1x,i0),*(1x,es25.17e3))') 'pt', step, j, stress(:, j), &
                ddsddr(:, :, j), dviscous(:, :, j), statev(2:, j), sfd(j)
        end do
        call uexternaldb(2, 0, time, 0d0, 2, i)
     end do
     call uexternaldb(3, 0, time, 0d0, 2, 0)
     call jl_check(jointlin_store_next_action(jl_store(), action, pass), 'next action')
  end do
  if (action /= JOINTLIN_ACTION_DONE) error stop 'the sweep did not finish'
  write (*, '(a,1x,i0)') 'passes', pass
  write (0, '(a,1x,i0)') 'threads', count_distinct(worker)

contains

  !> The number of distinct values in v.
  integer function count_distinct(v)
    integer, intent(in) :: v(:)
    integer :: a
    count_distinct = 0
    do a = 1, size(v)
       if (all(v(:a - 1) /= v(a))) count_distinct = count_distinct + 1
    end do
  end function count_distinct

  !> One point's work in one increment: its own arrays only.
  subroutine work(j, kinc, step, freqr)
    integer, intent(in) :: j, kinc, step
    real(c_double), intent(in) :: freqr
    real(c_double) :: s1, omega, kk, c, amp(2)
    integer :: d
    s1 = 1d-4 * (1 + mod(j - 1, 5)) * merge(-1d0, 1d0, mod(step, 2) == 1)
    drdisp(:, j) = [0d0, s1 - rdisp(2, j), -0.5d0 * s1 - rdisp(3, j)]
    rdisp(2:3, j) = [s1, -0.5d0 * s1]
    call call_uinter(j, 0d0, kinc, 0)
    call call_uinter(j, freqr, kinc, 1)
    omega = 2 * pi * freqr
    do d = 1, 2
       kk = ddsddr(d + 1, d + 1, j) + 300 - 2 * omega * omega
       c = omega * dviscous(d + 1, d + 1, j)
       amp(d) = (0.05d0 + 0.004d0 * (j - 1) + 0.01d0 * (d - 1)) / sqrt(kk * kk + c * c)
    end do
    call jl_report(int(statev(1, j), c_int64_t), kinc, amp)
  end subroutine work

  subroutine call_uinter(j, freqr, kinc, linper)
    integer, intent(in) :: j, kinc, linper
    real(c_double), intent(in) :: freqr
    character(len=80) :: ciname, secname, mainname
    real(c_double) :: flux(2), ddfddt(2, 2), ddsddt(ndir, 2), ddfddr(2, ndir), sed, spd, &
         svd, scd, temp(2), dtemp(2), predef(2, npred), dpred(2, npred), alocaldir(3, 3), &
         drot(2, 2), area, chrlngth
    integer :: lstate, lsdi, lprint
    ciname = 'THREADS'
    secname = 'SLAVE'
    mainname = 'MAIN'
    flux = 0; ddfddt = 0; ddsddt = 0; ddfddr = 0; sed = 0; spd = 0; svd = 0; scd = 0
    temp = 0; dtemp = 0; predef = 0; dpred = 0; alocaldir = 0; drot = 0
    area = 1; chrlngth = 1; lstate = 0; lsdi = 0; lprint = 0
    call uinter(stress(:, j), ddsddr(:, :, j), dviscous(:, :, j), dstructural(:, :, j), &
         flux, ddfddt, ddsddt, ddfddr, statev(:, j), sed, sfd(j), spd, svd, scd, &
         pnewdt(j), rdisp(:, j), drdisp(:, j), temp, dtemp, predef, dpred, time, 0.1d0, &
         freqr, ciname, secname, mainname, props, coords(:, j), alocaldir, drot, &
         area, chrlngth, 0, ndir, nstatv, npred, nprops, mcrd, 2, kinc, 0, linper, &
         lopenclose(j), lstate, lsdi, lprint)
  end subroutine call_uinter
end program uinter_omp
