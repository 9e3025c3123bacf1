! A stand-in for one Abaqus/Standard job of the two-point sweep model of sweep.f90, run
! as `abaqus_job job=NAME [input=... user=... interactive]` (Abaqus's own arguments; only
! job= is read) in the job directory: what a pass driver script
! (examples/abaqus/passes.sh, passes.py) starts for every pass. As Abaqus does, the job
! calls UEXTERNALDB at the start of the analysis (LOP 0: the shim reads ./jointlin.cfg
! and restores the store from its restart file), runs step 1 (the preload: UINTER with
! LINPER = 0 per point, UEXTERNALDB at the ends of its step and increment) and step 2,
! the steady-state sweep over the frequencies of ./sweep.frq (one `f,` line each, cycles
! per time; increment k is line k), with
! UINTER (LINPER = 1), the contact output of every increment in the stand-in results
! file read back by URDFIL, and UEXTERNALDB at the ends of increments, step and
! analysis (LOP 3 writes the action file). Its results, as *NODE PRINT would print
! them, go to NAME.dat: "increment k frequency f amplitude |x1| |x2|", 17 digits.
program abaqus_job
  use, intrinsic :: iso_c_binding
  use jointlin_abaqus, only: jl_close
  use host_data
  implicit none
  external :: uinter, uexternaldb, urdfil

  integer, parameter :: ndir = 2, mcrd = 3, npred = 1, npoints = 2
  real(c_double) :: stress(ndir, npoints) = 0, ddsddr(ndir, ndir, npoints) = 0
  real(c_double) :: dviscous(ndir, ndir, npoints) = 0, dstructural(ndir, ndir, npoints) = 0
  real(c_double) :: statev(nstatv, npoints) = 0, sfd(npoints) = 0, pnewdt(npoints) = 1
  real(c_double) :: rdisp(ndir, npoints) = 0, drdisp(ndir, npoints) = 0
  real(c_double) :: props(nprops, npoints), coords(mcrd, npoints) = 0
  integer :: lopenclose(npoints) = -1
  real(c_double) :: time(2) = 0, omega, kstar(npoints), dstar(npoints)
  real(c_double), allocatable :: freq(:)
  complex(c_double_complex) :: z11, z22, z12, det, x(npoints)
  character(len=256) :: arg, job
  integer :: i, j, dat, lstop, lovrwrt

  job = ''
  do i = 1, command_argument_count()
     call get_command_argument(i, arg)
     if (arg(1:4) == 'job=') job = arg(5:)
  end do
  if (len_trim(job) == 0) error stop 'abaqus_job: no job=NAME'
  call read_frequencies('sweep.frq', freq)

  call uexternaldb(0, 0, time, 0d0, 0, 0)
  ! Step 1: the preload, every contact closed by its normal law, in one increment with
  ! UEXTERNALDB at the step's and the increment's start and end (LOP 5, 1, 2, 6).
  call uexternaldb(5, 0, time, 0d0, 1, 0)
  call uexternaldb(1, 0, time, 0d0, 1, 1)
  do j = 1, npoints
     props(:, j) = block_props(0d0)
     coords(1, j) = 10 * (j - 1)
     rdisp(1, j) = merge(h_block, h_second, j == 1)
     drdisp(1, j) = rdisp(1, j)
     call call_uinter(j, 0d0, 1, 1, 0)
  end do
  call uexternaldb(2, 0, time, 0d0, 1, 1)
  call uexternaldb(6, 0, time, 0d0, 1, 0)
  ! Step 2: the steady-state sweep, increment i at the frequency of line i.
  open (newunit=dat, file=trim(job)//'.dat', status='replace', action='write')
  call uexternaldb(5, 0, time, 0d0, 2, 0)
  do i = 1, size(freq)
     omega = 2 * pi * freq(i)
     call uexternaldb(1, 0, time, 0d0, 2, i)
     do j = 1, npoints
        call call_uinter(j, freq(i), 2, i, 1)
        kstar(j) = ddsddr(2, 2, j)
        dstar(j) = dviscous(2, 2, j)
     end do
     z11 = cmplx(kc + kstar(1) - mass * omega * omega, omega * dstar(1), c_double_complex)
     z22 = cmplx(kc + kstar(2) - mass * omega * omega, omega * dstar(2), c_double_complex)
     z12 = cmplx(-kc, 0d0, c_double_complex)
     det = z11 * z22 - z12 * z12
     x = [force * z22 / det, -z12 * force / det]
     call write_results_file(i, x, .false.)
     call urdfil(lstop, lovrwrt, 2, i, 0d0, time)
     write (dat, '(a,i0,a,es25.17e3,a,2es25.17e3)') 'increment ', i, ' frequency ', &
          freq(i), ' amplitude', abs(x(1)), abs(x(2))
     call uexternaldb(2, 0, time, 0d0, 2, i)
  end do
  close (dat)
  call uexternaldb(6, 0, time, 0d0, 2, 0)
  call uexternaldb(3, 0, time, 0d0, 0, 0)
  call jl_close()

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

  !> The frequencies of a sweep.frq: the first field of every non-blank line.
  subroutine read_frequencies(path, freq)
    character(len=*), intent(in) :: path
    real(c_double), allocatable, intent(out) :: freq(:)
    character(len=256) :: line
    real(c_double) :: buf(1000), f
    integer :: u, ios, n, comma
    n = 0
    open (newunit=u, file=path, status='old', action='read')
    do
       read (u, '(a)', iostat=ios) line
       if (ios /= 0) exit
       if (len_trim(line) == 0) cycle
       comma = index(line, ',')
       if (comma > 0) line = line(:comma - 1)
       read (line, *) f
       n = n + 1
       if (n > size(buf)) error stop 'abaqus_job: more than 1000 frequencies'
       buf(n) = f
    end do
    close (u)
    freq = buf(1:n)
  end subroutine read_frequencies
end program abaqus_job
