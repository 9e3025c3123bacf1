! The two-point, three-increment sweep of ../c/sweep.c, run as an Abaqus user's job
! sequence would run it: every pass is a separate "job" that calls the shim subroutines
! UEXTERNALDB and UINTER; between jobs the store lives only in its restart file
! (jl_close frees it; the next LOP 0 re-creates it from the configuration and restores
! it), and the next pass's increments come from the action file, as a driver script
! would read them. Increments are numbered 1..m in every job (kinc_numbering =
! sequential); records print the sweep increment number. With the argument `urdfil` the
! host reports its amplitudes as an Abaqus job does: it writes the increment's contact
! output records (1504 node header, 1521 CDISP with real and imaginary parts) to the
! stand-in results file and calls the shim's URDFIL, which reads them through the stand-in
! POSFIL and DBFILE; `urdfil-corrupt` writes a CDISP record of 5 attributes, which URDFIL
! must refuse. Same records as the C host:
!   preload id p
!   inc pass kinc point estimate kstar dstar amplitude
!   stats pass kind run converged evaluations not_reported
!   next action pass count kinc...
!   points n
program sweep
  use, intrinsic :: iso_c_binding
  use jointlin
  use jointlin_abaqus, only: jl_store, jl_report, jl_close, jl_check
  use host_data
  implicit none
  external :: uinter, uexternaldb, urdfil

  integer, parameter :: ndir = 2, mcrd = 3, npred = 1, npoints = 2, ninc = 3
  real(c_double) :: stress(ndir, npoints) = 0, ddsddr(ndir, ndir, npoints) = 0
  real(c_double) :: dviscous(ndir, ndir, npoints) = 0, dstructural(ndir, ndir, npoints) = 0
  real(c_double) :: statev(nstatv, npoints) = 0, sfd(npoints) = 0, pnewdt(npoints) = 1
  real(c_double) :: rdisp(ndir, npoints) = 0, drdisp(ndir, npoints) = 0
  real(c_double) :: props(nprops, npoints), coords(mcrd, npoints) = 0
  integer :: lopenclose(npoints) = -1
  real(c_double) :: time(2) = 0, omega, freqr, kstar(npoints), dstar(npoints), amp(2)
  complex(c_double_complex) :: z11, z22, z12, det, x(npoints)
  type(jointlin_pass_stats) :: st
  type(jointlin_point_status) :: ps
  integer :: list(ninc), count, action, pass, i, j, kinc
  integer(c_int64_t) :: id, n
  character(len=16) :: mode
  integer :: lstop, lovrwrt

  call get_command_argument(1, mode)

  do j = 1, npoints
     props(:, j) = block_props(0d0)
     coords(1, j) = 10 * (j - 1)
     rdisp(1, j) = merge(h_block, h_second, j == 1)
     drdisp(1, j) = rdisp(1, j)
     call call_uinter(j, 0d0, 1, 1, 0)
     call record('preload', [real(j, c_double), stress(1, j)])
  end do

  action = JOINTLIN_ACTION_RUN_SWEEP
  pass = 1
  count = ninc
  list = [(i, i = 1, ninc)]
  call record('next', [real(action, c_double), real(pass, c_double), 0d0])
  do
     ! one job
     call uexternaldb(0, 0, time, 0d0, 0, 0)
     call uexternaldb(5, 0, time, 0d0, 2, 0)
     do i = 1, count
        kinc = list(i)
        omega = sweep_omega(kinc)
        freqr = omega / (2 * pi)
        call uexternaldb(1, 0, time, 0d0, 2, i)
        do j = 1, npoints
           call call_uinter(j, freqr, 2, i, 1)
           kstar(j) = ddsddr(2, 2, j)
           dstar(j) = dviscous(2, 2, j)
        end do
        z11 = cmplx(kc + kstar(1) - mass * omega * omega, omega * dstar(1), c_double_complex)
        z22 = cmplx(kc + kstar(2) - mass * omega * omega, omega * dstar(2), c_double_complex)
        z12 = cmplx(-kc, 0d0, c_double_complex)
        det = z11 * z22 - z12 * z12
        x = [force * z22 / det, -z12 * force / det]
        if (mode(1:6) == 'urdfil') then
           call write_results_file(i, x, mode == 'urdfil-corrupt')
           call urdfil(lstop, lovrwrt, 2, i, 0d0, time)
        end if
        do j = 1, npoints
           id = int(statev(1, j), c_int64_t)
           amp = [abs(x(j)), 0d0]
           if (mode(1:6) /= 'urdfil') call jl_report(id, i, amp)
           call jl_check(jointlin_store_point_status(jl_store(), id, int(kinc, c_int32_t), ps), &
                'point status')
           call record('inc', [real(pass, c_double), real(kinc, c_double), real(id, c_double), &
                ps%estimate(1), kstar(j), dstar(j), amp(1)])
        end do
        call uexternaldb(2, 0, time, 0d0, 2, i)
     end do
     call uexternaldb(6, 0, time, 0d0, 2, 0)
     call uexternaldb(3, 0, time, 0d0, 0, 0)
     call jl_check(jointlin_store_pass_stats(jl_store(), int(pass, c_int32_t), st), 'stats')
     call record('stats', [real(st%pass, c_double), real(st%kind, c_double), &
          real(st%increments_run, c_double), real(st%increments_converged, c_double), &
          real(st%evaluations, c_double), real(st%not_reported, c_double)])
     call jl_check(jointlin_store_point_count(jl_store(), n), 'point count')
     call jl_close() ! end of the job: the store survives in its restart file
     call read_action_file('sweep.next', action, pass, list, count)
     call record('next', [real(action, c_double), real(pass, c_double), real(count, c_double), &
          real(list(1:count), c_double)])
     if (action /= JOINTLIN_ACTION_RUN_PASS .and. action /= JOINTLIN_ACTION_RUN_FINAL) exit
  end do
  call record('points', [real(n, c_double)])

contains

  subroutine call_uinter(j, freqr, kstep, kinc, linper)
    integer, intent(in) :: j, kstep, kinc, linper
    real(c_double), intent(in) :: freqr
    character(len=80) :: ciname, secname, mainname
    real(c_double) :: flux(2), ddfddt(2, 2), ddsddt(ndir, 2), ddfddr(2, ndir), sed, spd, &
         svd, scd, temp(2), dtemp(2), predef(2, npred), dpred(2, npred), alocaldir(3, 3), &
         drot(2, 2), area, chrlngth
    integer :: lstate, lsdi, lprint
    ciname = 'SWEEP-PAIR'
    secname = 'SLAVE'
    mainname = 'MAIN'
    flux = 0; ddfddt = 0; ddsddt = 0; ddfddr = 0; sed = 0; spd = 0; svd = 0; scd = 0
    temp = 0; dtemp = 0; predef = 0; dpred = 0; alocaldir = 0; drot = 0
    area = 1; chrlngth = 1; lstate = 0; lsdi = 0; lprint = 0
    call uinter(stress(:, j), ddsddr(:, :, j), dviscous(:, :, j), dstructural(:, :, j), &
         flux, ddfddt, ddsddt, ddfddr, statev(:, j), sed, sfd(j), spd, svd, scd, &
         pnewdt(j), rdisp(:, j), drdisp(:, j), temp, dtemp, predef, dpred, time, 0d0, &
         freqr, ciname, secname, mainname, props(:, j), coords(:, j), alocaldir, drot, &
         area, chrlngth, j, ndir, nstatv, npred, nprops, mcrd, kstep, kinc, 0, linper, &
         lopenclose(j), lstate, lsdi, lprint)
  end subroutine call_uinter

  !> Reads what UEXTERNALDB wrote at LOP 3: "action NAME", "pass N", "increments k...".
  subroutine read_action_file(path, action, pass, list, count)
    character(len=*), intent(in) :: path
    integer, intent(out) :: action, pass, list(:), count
    character(len=16) :: word, name
    character(len=256) :: line
    integer :: u, ios
    open (newunit=u, file=path, status='old', action='read')
    read (u, *) word, name
    select case (trim(name))
    case ('RUN_PASS')
       action = JOINTLIN_ACTION_RUN_PASS
    case ('RUN_FINAL')
       action = JOINTLIN_ACTION_RUN_FINAL
    case ('DONE')
       action = JOINTLIN_ACTION_DONE
    case ('FAILED')
       action = JOINTLIN_ACTION_FAILED
    case default
       error stop 'unexpected action'
    end select
    read (u, *) word, pass
    read (u, '(a)') line
    close (u)
    line = adjustl(line(len('increments') + 1:))
    count = 0
    do while (len_trim(line) > 0 .and. count < size(list))
       count = count + 1
       read (line, *, iostat=ios) list(count)
       if (ios /= 0) error stop 'bad action file'
       line = adjustl(line(index(line, ' '):))
    end do
  end subroutine read_action_file
end program sweep
