! A domain-decomposed FE job in miniature, run under MPI through the Abaqus-signature shim
! (tests/hosts_mpi.rs): a chain of 8 contact points (each a unit mass on its joint to
! ground, neighbours coupled by springs of 400, the first one forced with 0.25) swept over
! 5 frequencies and iterated over passes, every pass a separate "job" (the store lives in
! the ranks' restart files between jobs, kinc_numbering = sequential).
!
! Rank r of n owns points block(r) (contiguous) and calls UINTER for them only; per
! increment the ranks sum their k*, d* into the full chain (each rank fills only its own
! entries, so the sum is exact), every rank solves the same tridiagonal system and reports
! its own points' amplitudes. UEXTERNALDB does the rest: per-rank stores and restart files
! (sweep_mpi.cfg), and at LOP 3 the agreement on the increments to re-run (through the
! communicator with the shim built MPI=yes, through files with MPI=no).
!
! Each rank appends its records to records.r<rank> (numbers to 17 digits):
!   inc pass sweep point estimate kstar dstar amplitude
!   local pass rank rerun-flags...   (this rank's own decision, before the agreement)
!   next action pass count kinc...
!
! Environment (the restart test):
!   JL_KILL="pass done rank"   after the LOP 2 (restart data written) of the done-th
!                              increment of that pass, all ranks meet, then that rank
!                              kills itself (SIGKILL): the job dies there.
!   JL_RESUME="pass done"      a restart job: LOP 4 restores every rank's store from its
!                              restart file, and the pass continues after its done-th
!                              increment (the pass's increments are this rank's
!                              resume.r<rank>, written when the pass started).
program sweep_mpi
  use, intrinsic :: iso_c_binding
  use jointlin
  use jointlin_abaqus, only: jl_store, jl_report, jl_close, jl_check
  implicit none
  include 'mpif.h'
  external :: uinter, uexternaldb

  integer, parameter :: npoints = 8, nfreq = 5, ndir = 2, mcrd = 3, npred = 1
  integer, parameter :: nstatv = 57, nprops = 12
  real(c_double), parameter :: freqs(nfreq) = [1.5d0, 2.2d0, 3.0d0, 4.0d0, 5.0d0]
  real(c_double), parameter :: mass = 1, coupling = 400, force = 0.25d0
  real(c_double), parameter :: pi = 3.14159265358979323846d0
  real(c_double), parameter :: kn = 1d4

  real(c_double), allocatable :: stress(:, :), ddsddr(:, :, :), dviscous(:, :, :), &
       dstructural(:, :, :), statev(:, :), sfd(:), pnewdt(:), rdisp(:, :), drdisp(:, :), &
       props(:, :), coords(:, :)
  integer, allocatable :: lopenclose(:)
  real(c_double) :: time(2) = 0, kall(npoints), dall(npoints), kmine(npoints), &
       dmine(npoints), amp(npoints), est(npoints)
  integer :: rank, nranks, ierr, first, last, j, i, u, action, pass, count, list(nfreq)
  integer :: stop_at(3), resume(2), from
  character(len=64) :: env
  logical :: killing, resuming

  call MPI_INIT(ierr)
  call MPI_COMM_RANK(MPI_COMM_WORLD, rank, ierr)
  call MPI_COMM_SIZE(MPI_COMM_WORLD, nranks, ierr)
  first = rank * npoints / nranks + 1
  last = (rank + 1) * npoints / nranks
  allocate (stress(ndir, first:last), ddsddr(ndir, ndir, first:last), &
       dviscous(ndir, ndir, first:last), dstructural(ndir, ndir, first:last), &
       statev(nstatv, first:last), sfd(first:last), pnewdt(first:last), &
       rdisp(ndir, first:last), drdisp(ndir, first:last), props(nprops, first:last), &
       coords(mcrd, first:last), lopenclose(first:last))
  ! UINTER reads STRESS (the stress at the start of the increment): never uninitialized
  ! memory, which a restart job's heap may fill with a non-finite pattern.
  stress = 0; ddsddr = 0; dviscous = 0; dstructural = 0; statev = 0; sfd = 0; pnewdt = 1
  rdisp = 0; drdisp = 0
  do j = first, last
     props(:, j) = [0d0, 0d0, 0.3d0, 1282.7d0, 0d0, kn, 0d0, 0d0, 0d0, 0d0, 0d0, 0d0]
     coords(:, j) = [real(j - 1, c_double), 0d0, 0d0]
  end do
  write (env, '(a,i0)') 'records.r', rank
  open (newunit=u, file=trim(env), position='append', action='write')

  stop_at = 0
  call get_environment_variable('JL_KILL', env)
  killing = len_trim(env) > 0
  if (killing) read (env, *) stop_at
  resume = 0
  call get_environment_variable('JL_RESUME', env)
  resuming = len_trim(env) > 0

  if (resuming) then
     read (env, *) resume
     pass = resume(1)
     from = resume(2) + 1
     call read_list(list, count)
     call uexternaldb(4, 0, time, 0d0, 2, 0) ! restart analysis: restore the store
     call preload()
  else
     action = JOINTLIN_ACTION_RUN_SWEEP
     pass = 1
     count = nfreq
     list = [(i, i = 1, nfreq)]
     from = 1
  end if
  do
     if (from == 1) then ! a new job for this pass
        call uexternaldb(0, 0, time, 0d0, 0, 0)
        call write_list(list, count)
        call preload()
        call uexternaldb(5, 0, time, 0d0, 2, 0)
     end if
     do i = from, count
        call increment(pass, i, list(i))
        if (killing .and. pass == stop_at(1) .and. i == stop_at(2)) then
           call MPI_BARRIER(MPI_COMM_WORLD, ierr) ! every rank's restart data is written
           if (rank == stop_at(3)) call kill_me()
           call MPI_BARRIER(MPI_COMM_WORLD, ierr) ! never passes: the job dies
        end if
     end do
     from = 1
     call uexternaldb(6, 0, time, 0d0, 2, 0)
     call record_local(pass)
     call uexternaldb(3, 0, time, 0d0, 0, 0)
     call next(action, pass, list, count)
     call jl_close() ! end of the job: the store survives in the restart files
     if (action /= JOINTLIN_ACTION_RUN_PASS .and. action /= JOINTLIN_ACTION_RUN_FINAL) exit
  end do
  close (u)
  call MPI_FINALIZE(ierr)

contains

  !> The static step (general, LINPER = 0): the preload closes every own contact.
  subroutine preload()
    do j = first, last
       statev(:, j) = 0
       stress(:, j) = 0
       rdisp(:, j) = [2d-4 * (1 + 0.1d0 * (j - 1)), 0d0]
       drdisp(:, j) = rdisp(:, j)
       lopenclose(j) = -1
       call call_uinter(j, 0d0, 1, 1, 0)
    end do
  end subroutine preload

  !> Increment kinc (1..count) of the running pass, sweep increment `sweep`.
  subroutine increment(pass, kinc, sweep)
    integer, intent(in) :: pass, kinc, sweep
    real(c_double) :: omega
    integer(c_int64_t) :: id
    omega = 2 * pi * freqs(sweep)
    call uexternaldb(1, 0, time, 0d0, 2, kinc)
    kmine = 0
    dmine = 0
    do j = first, last
       call call_uinter(j, freqs(sweep), 2, kinc, 1)
       kmine(j) = ddsddr(2, 2, j)
       dmine(j) = dviscous(2, 2, j)
    end do
    call MPI_ALLREDUCE(kmine, kall, npoints, MPI_DOUBLE_PRECISION, MPI_SUM, MPI_COMM_WORLD, &
         ierr)
    call MPI_ALLREDUCE(dmine, dall, npoints, MPI_DOUBLE_PRECISION, MPI_SUM, MPI_COMM_WORLD, &
         ierr)
    call solve(omega, kall, dall, amp)
    do j = first, last
       id = int(statev(1, j), c_int64_t)
       est(j) = estimate_of(id, sweep)
       call jl_report(id, kinc, [amp(j), 0d0])
       write (u, '(a,3(1x,i0),4(1x,es25.17e3))') 'inc', pass, sweep, j, est(j), &
            kall(j), dall(j), amp(j)
    end do
    flush (u)
    call uexternaldb(2, 1, time, 0d0, 2, kinc) ! LRESTART = 1: restart data written
  end subroutine increment

  !> The estimate the store handed out to point id at sweep increment `sweep`.
  function estimate_of(id, sweep) result(a)
    integer(c_int64_t), intent(in) :: id
    integer, intent(in) :: sweep
    real(c_double) :: a
    type(jointlin_point_status) :: ps
    call jl_check(jointlin_store_point_status(jl_store(), id, int(sweep, c_int32_t), ps), &
         'point status')
    a = ps%estimate(1)
  end function estimate_of

  !> |x| of the chain (tridiagonal, Thomas algorithm).
  subroutine solve(omega, k, d, x)
    real(c_double), intent(in) :: omega, k(npoints), d(npoints)
    real(c_double), intent(out) :: x(npoints)
    complex(c_double_complex) :: c(npoints), r(npoints), b, off
    integer :: n
    off = cmplx(-coupling, 0d0, c_double_complex)
    b = diag(omega, k, d, 1)
    c(1) = off / b
    r(1) = cmplx(force, 0d0, c_double_complex) / b
    do n = 2, npoints
       b = diag(omega, k, d, n) - off * c(n - 1)
       c(n) = off / b
       r(n) = (-off * r(n - 1)) / b
    end do
    do n = npoints - 1, 1, -1
       r(n) = r(n) - c(n) * r(n + 1)
    end do
    x = abs(r)
  end subroutine solve

  !> Diagonal entry n of the chain's dynamic stiffness.
  complex(c_double_complex) function diag(omega, k, d, n)
    real(c_double), intent(in) :: omega, k(npoints), d(npoints)
    integer, intent(in) :: n
    real(c_double) :: springs
    springs = merge(1d0, 2d0, n == 1 .or. n == npoints)
    diag = cmplx(k(n) + springs * coupling - mass * omega * omega, omega * d(n), &
         c_double_complex)
  end function diag

  !> "local pass rank flags": this rank's own re-run flags, before LOP 3 agrees.
  subroutine record_local(pass)
    integer, intent(in) :: pass
    integer(c_int32_t) :: buf(4 + 3 * nfreq)
    integer(c_size_t) :: len
    integer :: n
    call jl_check(jointlin_store_pass_summary(jl_store(), buf, int(size(buf), c_size_t), &
         len), 'pass summary')
    n = (int(len) - 4) / 3
    write (u, '(a,*(1x,i0))') 'local', pass, rank, buf(5 + 2 * n:4 + 3 * n)
    flush (u)
  end subroutine record_local

  !> The store's next action and increments, recorded.
  subroutine next(action, pass, list, count)
    integer, intent(out) :: action, pass, list(:), count
    integer(c_int32_t) :: a, p, k(nfreq)
    integer(c_size_t) :: n
    call jl_check(jointlin_store_next_action(jl_store(), a, p), 'next action')
    call jl_check(jointlin_store_rerun_increments(jl_store(), k, int(nfreq, c_size_t), n), &
         'rerun increments')
    action = a
    pass = p
    count = int(n)
    list(1:count) = k(1:count)
    write (u, '(a,*(1x,i0))') 'next', action, pass, count, list(1:count)
    flush (u)
  end subroutine next

  !> The increments of the pass being started, for a restart job (resume.r<rank>).
  subroutine write_list(list, count)
    integer, intent(in) :: list(:), count
    integer :: v
    character(len=32) :: name
    write (name, '(a,i0)') 'resume.r', rank
    open (newunit=v, file=trim(name), status='replace', action='write')
    write (v, *) count, list(1:count)
    close (v)
  end subroutine write_list

  subroutine read_list(list, count)
    integer, intent(out) :: list(:), count
    integer :: v
    character(len=32) :: name
    write (name, '(a,i0)') 'resume.r', rank
    open (newunit=v, file=trim(name), status='old', action='read')
    read (v, *) count, list(1:count)
    close (v)
  end subroutine read_list

  subroutine kill_me()
    integer :: status
    status = kill(getpid(), 9) ! GNU extension: SIGKILL to this process
    error stop 'SIGKILL did not stop the process'
  end subroutine kill_me

  subroutine call_uinter(j, freqr, kstep, kinc, linper)
    integer, intent(in) :: j, kstep, kinc, linper
    real(c_double), intent(in) :: freqr
    character(len=80) :: ciname, secname, mainname
    real(c_double) :: flux(2), ddfddt(2, 2), ddsddt(ndir, 2), ddfddr(2, ndir), sed, spd, &
         svd, scd, temp(2), dtemp(2), predef(2, npred), dpred(2, npred), alocaldir(3, 3), &
         drot(2, 2), area, chrlngth
    integer :: lstate, lsdi, lprint
    ciname = 'CHAIN'
    secname = 'SLAVE'
    mainname = 'MAIN'
    flux = 0; ddfddt = 0; ddsddt = 0; ddfddr = 0; sed = 0; spd = 0; svd = 0; scd = 0
    temp = 0; dtemp = 0; predef = 0; dpred = 0; alocaldir = 0; drot = 0
    area = 1; chrlngth = 1; lstate = 0; lsdi = 0; lprint = 0
    call uinter(stress(:, j), ddsddr(:, :, j), dviscous(:, :, j), dstructural(:, :, j), &
         flux, ddfddt, ddsddt, ddfddr, statev(:, j), sed, sfd(j), spd, svd, scd, &
         pnewdt(j), rdisp(:, j), drdisp(:, j), temp, dtemp, predef, dpred, time, 0d0, &
         freqr, ciname, secname, mainname, props(:, j), coords(:, j), alocaldir, drot, &
         area, chrlngth, 0, ndir, nstatv, npred, nprops, mcrd, kstep, kinc, 0, linper, &
         lopenclose(j), lstate, lsdi, lprint)
  end subroutine call_uinter
end program sweep_mpi
