! jointlin_abaqus: the state the Abaqus-signature shims (uinter.f, uexternaldb.f) share.
!
! The iteration store handle lives here, in a module variable. UEXTERNALDB creates it at
! LOP = 0 (or 4) of the first analysis in the process, from a small configuration file:
! the file named by the environment variable JOINTLIN_CONFIG, else ./jointlin.cfg. No
! file: no store; UINTER then works in general steps (LINPER = 0) and stops the analysis
! with a message at LINPER = 1. The handle is never freed by the shims (an Abaqus job ends
! with its process); hosts that outlive the analysis call jl_close.
!
! Threads: UEXTERNALDB is called by one thread of the process; UINTER, called by many
! threads at once, only reads the handle (the store itself is thread-safe). jl_open,
! jl_close and jl_after_pass change module state and run only inside UEXTERNALDB.
!
! Processes (ranks): at jl_open the shim asks the host for its process number and the
! number of processes, with Abaqus's utility routines GETRANK(KPROCESSNUM) and
! GETNUMCPUS(NUMPROCESSES) (outside Abaqus: abaqus_standin.f, or abaqus_standin_mpi.f90
! under MPI). With more than one process every rank has its own store for the contact
! points of its domain and its own restart file, <restart_file>.r<rank>. At LOP 3 the
! ranks first agree on the increments to re-run (jl_agree): through the host's MPI
! communicator (GETCOMMUNICATOR) when the shim was built with MPI=yes and MPI is up,
! else through files beside the restart files (jointlin_store_agree_files; the job
! directory must be shared by all ranks). Only rank 0 logs the next action and writes
! the action file.
!
! Configuration file: one "key = value" per line; "#" or "!" starts a comment; keys and
! word values are case-insensitive; unset keys keep the C API defaults
! (jointlin_store_config_default).
!
!   initial_amplitude = 4.4e-4     ! amplitude estimate of the first increment (required)
!   rtol = 1e-3                    ! relative tolerance
!   atol = 0                       ! absolute tolerance (length)
!   scheme = secant                ! direct | relaxation | secant
!   max_passes = 20                ! iteration passes before giving up
!   sweep_step = 0                 ! KSTEP of the steady-state step (0 = every step)
!   kinc_numbering = sequential    ! original | sequential (a new job per re-run pass)
!   restart_file = jointlin.restart  ! store file: written at LOP 2 (LRESTART >= 1) and 3,
!                                  ! read at LOP 4, and at LOP 0 when it exists
!                                  ! (several ranks: jointlin.restart.r<rank>)
!   action_file = jointlin.next    ! written at LOP 3: "action NAME", "pass N",
!                                  ! "increments k1 k2 ..." (for a driver script)
!   agree_timeout = 600            ! seconds a rank waits for the others' pass files
!                                  ! (file protocol only)
!
! With restart_file set, every pass can be a separate Abaqus job: the first LOP 0 of a
! job restores the store from the file when it exists (delete it to start over).
!
! Errors of the C API stop the analysis through Abaqus's STDB_ABQERR (LOP = -3) with the
! detail from jointlin_last_error; outside Abaqus link abaqus_standin.f, which provides a
! stand-in STDB_ABQERR.
module jointlin_abaqus
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  use jointlin
  implicit none
  private
  public :: jl_store, jl_open, jl_close, jl_check, jl_error_text, jl_report, &
       jl_contact_record, jl_after_pass
  public :: jl_agree, jl_rank

  !> The store shared by UINTER and UEXTERNALDB (c_null_ptr until LOP 0 created it).
  type(c_ptr), save :: handle = c_null_ptr
  !> 1 once jl_open looked for the configuration (found or not).
  logical, save :: opened = .false.
  character(len=1024), save :: action_file = ' '
  !> This process's rank (0-based) and the number of ranks, from GETRANK and GETNUMCPUS.
  integer, save :: rank = 0, ranks = 1
  !> Seconds a rank waits for the other ranks' pass files (file protocol).
  real(c_double), save :: agree_timeout = 600

contains

  !> The store handle (c_null_ptr when there is none).
  function jl_store() result(h)
    type(c_ptr) :: h
    h = handle
  end function jl_store

  !> The message of a status code plus the detail of the last failing call on this thread.
  function jl_error_text(status) result(text)
    integer(c_int32_t), intent(in) :: status
    character(len=:), allocatable :: text
    character(kind=c_char), pointer :: msg(:)
    character(kind=c_char) :: buf(512)
    integer(c_size_t) :: n, i
    integer :: m
    m = 0
    call c_f_pointer(jointlin_status_message(status), msg, [256])
    do while (m < 256)
       if (msg(m + 1) == c_null_char) exit
       m = m + 1
    end do
    allocate (character(len=m) :: text)
    do i = 1, m
       text(i:i) = msg(i)
    end do
    n = jointlin_last_error(buf, int(size(buf), c_size_t))
    n = min(n, int(size(buf) - 1, c_size_t))
    if (n > 0) then
       text = text // ' ('
       do i = 1, n
          text = text // buf(i)
       end do
       text = text // ')'
    end if
  end function jl_error_text

  !> Stops the analysis (STDB_ABQERR, LOP = -3) when `status` is not JOINTLIN_OK.
  subroutine jl_check(status, where)
    integer(c_int32_t), intent(in) :: status
    character(len=*), intent(in) :: where
    if (status == JOINTLIN_OK) return
    call jl_stop(where // ': ' // jl_error_text(status))
  end subroutine jl_check

  !> Stops the analysis (STDB_ABQERR, LOP = -3) with "jointlin <text>".
  subroutine jl_stop(text)
    character(len=*), intent(in) :: text
    external :: stdb_abqerr
    integer :: intv(1)
    real(c_double) :: realv(1)
    character(len=8) :: charv(1)
    character(len=:), allocatable :: msg
    integer :: i
    msg = 'jointlin ' // text
    do i = 1, len(msg)
       if (msg(i:i) == '%') msg(i:i) = ' ' ! STDB_ABQERR substitutes %I, %R, %S
    end do
    intv = 0
    realv = 0
    charv = ' '
    call stdb_abqerr(-3, msg(1:min(len(msg), 500)), intv, realv, charv)
  end subroutine jl_stop

  !> This process's rank and the number of ranks (valid after jl_open).
  subroutine jl_rank(r, n)
    integer, intent(out) :: r, n
    r = rank
    n = ranks
  end subroutine jl_rank

  !> Creates the store at the first LOP 0 or 4 of the process (see the module header).
  subroutine jl_open(lop)
    integer, intent(in) :: lop
    type(jointlin_store_config) :: config
    character(len=1024) :: restart, path
    ! The store copies the path bytes; the buffer only has to outlive jointlin_store_new.
    character(kind=c_char), target :: rbuf(1024)
    integer :: plen, status, i
    integer(c_size_t) :: n
    logical :: exists
    external :: getrank, getnumcpus
    if (opened) return
    opened = .true.
    call get_environment_variable('JOINTLIN_CONFIG', path, plen, status)
    if (status /= 0 .or. plen == 0) path = 'jointlin.cfg'
    inquire (file=trim(path), exist=exists)
    if (.not. exists) then
       write (error_unit, '(3a)') 'jointlin: no configuration file ', trim(path), &
            ': no iteration store (LINPER = 1 will stop the analysis)'
       return
    end if
    call getnumcpus(ranks)
    call getrank(rank)
    if (ranks < 1 .or. rank < 0 .or. rank >= ranks) then
       write (path, '(a,i0,a,i0)') 'GETRANK gave ', rank, ', GETNUMCPUS ', ranks
       call jl_stop(trim(path))
    end if
    call jl_check(jointlin_store_config_default(config), 'configuration defaults')
    restart = ' '
    call read_config(trim(path), config, restart)
    if (len_trim(restart) > 0) then
       do i = 1, len_trim(restart)
          rbuf(i) = restart(i:i)
       end do
       config%restart_path = c_loc(rbuf)
       config%restart_path_len = int(len_trim(restart), c_size_t)
    end if
    call jl_check(jointlin_store_new_ranked(config, int(rank, c_int32_t), &
         int(ranks, c_int32_t), handle), 'store from ' // trim(path))
    if (lop == 0 .and. len_trim(restart) > 0) then
       ! This rank's restart file (with several ranks <restart_file>.r<rank>).
       call jl_check(jointlin_store_restart_path(handle, rbuf, int(size(rbuf), c_size_t), n), &
            'restart path')
       restart = ' '
       do i = 1, int(n)
          restart(i:i) = rbuf(i)
       end do
       inquire (file=trim(restart), exist=exists)
       if (exists) then
          call jl_check(jointlin_store_restore(handle), 'restore from ' // trim(restart))
       end if
    end if
  end subroutine jl_open

  !> Frees the store (for hosts that outlive the analysis); the next LOP 0 creates a new
  !> one from the configuration (and its restart file).
  subroutine jl_close()
    call jointlin_store_free(handle)
    handle = c_null_ptr
    opened = .false.
  end subroutine jl_close

  !> Reports the amplitudes computed for store point `point` (STATEV(1) of its UINTER
  !> call) in increment `kinc` (e.g. from URDFIL, or a host's own solver).
  subroutine jl_report(point, kinc, amp)
    integer(c_int64_t), intent(in) :: point
    integer, intent(in) :: kinc
    real(c_double), intent(in) :: amp(2)
    call jl_check(jointlin_store_report(handle, point, int(kinc, c_int32_t), amp), 'report')
  end subroutine jl_report

  !> One contact output record of the results file (URDFIL): for record key 1521 (CDISP:
  !> separation, then the relative tangential displacements in the master surface's local
  !> 1- and 2-directions; in a steady-state dynamics step the real parts followed by the
  !> imaginary parts) of slave node `node`, reports the amplitudes |Re + i Im| of the
  !> tangential components for increment `kinc` to the node's store point. Other keys and
  !> real-only (static) CDISP records are left alone; a node UINTER never saw has no point
  !> and is skipped. `nattr` attributes in `attr` (record length − 2).
  subroutine jl_contact_record(key, node, kinc, nattr, attr)
    integer, intent(in) :: key, node, kinc, nattr
    real(c_double), intent(in) :: attr(*)
    real(c_double) :: amp(2)
    integer(c_int32_t) :: reported
    character(len=120) :: what
    if (key /= 1521 .or. .not. c_associated(handle)) return
    select case (nattr)
    case (2, 3) ! real only: not a steady-state dynamics increment
       return
    case (4) ! 2D: separation, slip 1; then their imaginary parts
       amp = [hypot(attr(2), attr(4)), 0d0]
    case (6) ! 3D: separation, slip 1, slip 2; then their imaginary parts
       amp = [hypot(attr(2), attr(5)), hypot(attr(3), attr(6))]
    case default
       write (what, '(a,i0,a,i0,a)') 'URDFIL: contact output record 1521 (CDISP) of node ', &
            node, ' has ', nattr, ' attributes, not 2, 3, 4 or 6'
       call jl_stop(trim(what))
    end select
    write (what, '(a,i0,a,i0)') 'URDFIL: report of node ', node, ' in increment ', kinc
    call jl_check(jointlin_store_report_node(handle, int(node, c_int32_t), &
         int(kinc, c_int32_t), amp, reported), trim(what))
  end subroutine jl_contact_record

  !> Before LOP 3, with several ranks: the ranks agree on the increments to re-run (module
  !> header). Through MPI: {len, -len} and then the pass summaries reduced by maximum over
  !> the host's communicator (jl_allreduce_max, agree_mpi.f90); without MPI
  !> (agree_nompi.f90, or MPI not running): jointlin_store_agree_files.
  subroutine jl_agree()
    integer(c_int32_t), allocatable :: buf(:)
    integer(c_int32_t) :: lens(2)
    integer(c_size_t) :: n, cap
    integer(c_int32_t) :: status
    integer :: mpi
    character(len=200) :: what
    external :: jl_allreduce_max
    if (ranks <= 1 .or. .not. c_associated(handle)) return
    lens = 0
    status = jointlin_store_pass_summary(handle, lens, 0_c_size_t, n)
    if (status /= JOINTLIN_ERR_SIZE) call jl_check(status, 'pass summary')
    lens = [int(n, c_int32_t), -int(n, c_int32_t)]
    call jl_allreduce_max(lens, 2, ranks, mpi)
    select case (mpi)
    case (0)
    case (1) ! no communicator: the file protocol
       call jl_check(jointlin_store_agree_files(handle, int(rank, c_int32_t), &
            int(ranks, c_int32_t), agree_timeout), 'agreement through files')
       return
    case (3)
       write (what, '(a,i0,a)') 'agreement: the MPI communicator does not have the ', &
            ranks, ' processes of GETNUMCPUS'
       call jl_stop(trim(what))
    case default
       call jl_stop('agreement: MPI_ALLREDUCE of the pass summary lengths failed')
    end select
    if (lens(1) /= -lens(2)) then
       write (what, '(a,i0,a,i0,a)') 'agreement: the ranks know different numbers of ' // &
            'increments (', (-lens(2) - 4) / 3, ' to ', (lens(1) - 4) / 3, ')'
       call jl_stop(trim(what))
    end if
    cap = n
    allocate (buf(cap))
    call jl_check(jointlin_store_pass_summary(handle, buf, cap, n), 'pass summary')
    call jl_allreduce_max(buf, int(n), ranks, mpi)
    if (mpi /= 0) call jl_stop('agreement: MPI_ALLREDUCE of the pass summaries failed')
    call jl_check(jointlin_store_pass_agree(handle, buf, n), 'pass agreement')
  end subroutine jl_agree

  !> After LOP 3: logs the next action to stderr and writes the action file if configured
  !> (rank 0 only: all ranks agreed on it).
  subroutine jl_after_pass()
    integer(c_int32_t) :: action, pass
    integer(c_int32_t), allocatable :: kinc(:)
    integer(c_size_t) :: count
    integer(c_int32_t) :: status
    character(len=10), parameter :: names(0:5) = [character(len=10) :: 'RUNNING', &
         'RUN_SWEEP', 'RUN_PASS', 'RUN_FINAL', 'DONE', 'FAILED']
    integer :: u
    call jl_check(jointlin_store_next_action(handle, action, pass), 'next action')
    allocate (kinc(1))
    status = jointlin_store_rerun_increments(handle, kinc, 0_c_size_t, count)
    if (status /= JOINTLIN_OK .and. status /= JOINTLIN_ERR_SIZE) call jl_check(status, 'rerun')
    deallocate (kinc)
    allocate (kinc(max(count, 1_c_size_t)))
    call jl_check(jointlin_store_rerun_increments(handle, kinc, int(size(kinc), c_size_t), &
         count), 'rerun increments')
    if (rank /= 0) return
    write (error_unit, '(a,a,a,i0,a,i0,a)') 'jointlin: next action ', &
         trim(names(action)), ' (pass ', pass, ', ', count, ' increments)'
    if (len_trim(action_file) > 0) then
       open (newunit=u, file=trim(action_file), status='replace', action='write')
       write (u, '(2a)') 'action ', trim(names(action))
       write (u, '(a,i0)') 'pass ', pass
       write (u, '(a)', advance='no') 'increments'
       if (count > 0) write (u, '(*(1x,i0))', advance='no') kinc(1:count)
       write (u, '(a)') ''
       close (u)
    end if
  end subroutine jl_after_pass

  subroutine read_config(path, config, restart)
    character(len=*), intent(in) :: path
    type(jointlin_store_config), intent(inout) :: config
    character(len=*), intent(inout) :: restart
    character(len=1024) :: line, key, value
    integer :: u, ios, eq, c, nline
    open (newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) call fail('cannot open')
    nline = 0
    do
       read (u, '(a)', iostat=ios) line
       if (ios /= 0) exit
       nline = nline + 1
       c = scan(line, '#!')
       if (c > 0) line(c:) = ' '
       if (len_trim(line) == 0) cycle
       eq = index(line, '=')
       if (eq == 0) call fail('line without "="')
       key = lower(adjustl(line(:eq - 1)))
       value = adjustl(line(eq + 1:))
       select case (trim(key))
       case ('initial_amplitude')
          config%initial_amplitude = real_value()
       case ('rtol')
          config%rtol = real_value()
       case ('atol')
          config%atol = real_value()
       case ('scheme')
          select case (lower(value))
          case ('direct')
             config%scheme = JOINTLIN_SCHEME_DIRECT
          case ('relaxation')
             config%scheme = JOINTLIN_SCHEME_RELAXATION
          case ('secant')
             config%scheme = JOINTLIN_SCHEME_SECANT
          case default
             call fail('scheme must be direct, relaxation or secant')
          end select
       case ('max_passes')
          config%max_passes = int_value()
       case ('sweep_step')
          config%sweep_step = int_value()
       case ('kinc_numbering')
          select case (lower(value))
          case ('original')
             config%kinc_numbering = JOINTLIN_KINC_ORIGINAL
          case ('sequential')
             config%kinc_numbering = JOINTLIN_KINC_SEQUENTIAL
          case default
             call fail('kinc_numbering must be original or sequential')
          end select
       case ('restart_file')
          restart = trim(value)
       case ('action_file')
          action_file = trim(value)
       case ('agree_timeout')
          agree_timeout = real_value()
          if (.not. (agree_timeout > 0)) call fail('agree_timeout must be > 0 (seconds)')
       case default
          call fail('unknown key "' // trim(key) // '"')
       end select
    end do
    close (u)
  contains
    function real_value() result(v)
      real(c_double) :: v
      read (value, *, iostat=ios) v
      if (ios /= 0) call fail('not a number: ' // trim(value))
    end function real_value
    function int_value() result(v)
      integer(c_int32_t) :: v
      read (value, *, iostat=ios) v
      if (ios /= 0) call fail('not an integer: ' // trim(value))
    end function int_value
    subroutine fail(what)
      character(len=*), intent(in) :: what
      character(len=16) :: num
      external :: stdb_abqerr
      integer :: intv(1)
      real(c_double) :: realv(1)
      character(len=8) :: charv(1)
      write (num, '(i0)') nline
      intv = 0
      realv = 0
      charv = ' '
      call stdb_abqerr(-3, 'jointlin: ' // path // ':' // trim(num) // ': ' // what, &
           intv, realv, charv)
    end subroutine fail
  end subroutine read_config

  pure function lower(s) result(t)
    character(len=*), intent(in) :: s
    character(len=len_trim(s)) :: t
    integer :: i, c
    t = s(1:len(t))
    do i = 1, len(t)
       c = iachar(t(i:i))
       if (c >= iachar('A') .and. c <= iachar('Z')) t(i:i) = achar(c + 32)
    end do
  end function lower
end module jointlin_abaqus
