! jointlin: Fortran 2018 bindings (ISO_C_BINDING) for the C API in include/jointlin.h.
!
! One-to-one with the header: every JOINTLIN_* constant is an integer(c_int32_t)
! parameter, every struct a bind(C) derived type with the same components in the same
! order, every function an interface with the same name, argument names and types.
! tests/hosts_module.rs parses both files and fails when they drift apart.
!
! Mapping rules (what the test checks):
!   int32_t / int64_t / size_t / double    -> integer(c_int32_t) / integer(c_int64_t) /
!                                             integer(c_size_t) / real(c_double), value
!   T *  (T one of the above)              -> the same type by reference; const T * is
!                                             intent(in), T * intent(out) or intent(inout)
!   const char * / char *                  -> character(kind=c_char) :: x(*)
!   struct jointlin_X *                    -> type(jointlin_X) by reference; the pointers
!                                             that may be NULL are optional (absent = NULL)
!   struct jointlin_store * (opaque)       -> type(c_ptr), value (c_null_ptr = NULL)
!   struct jointlin_store **               -> type(c_ptr), intent(out)
!   uint32_t result                        -> integer(c_int32_t) (Fortran has no unsigned)
!   const char * result                    -> type(c_ptr) (a static C string)
!   const char * struct component          -> type(c_ptr) (use c_loc of a character array)
!
! The module holds no procedures of its own: a Fortran program that uses it links only
! libjointlin (gfortran -I<dir of jointlin.mod> prog.f90 -ljointlin). Units and meaning of
! every argument: see the comments in include/jointlin.h.
module jointlin
  use, intrinsic :: iso_c_binding, only: c_int32_t, c_int64_t, c_size_t, c_double, &
       c_char, c_ptr
  implicit none
  private :: c_int32_t, c_int64_t, c_size_t, c_double, c_char, c_ptr

  ! ---- constants (#define in jointlin.h) ----
  integer(c_int32_t), parameter :: JOINTLIN_ABI_VERSION_MAJOR = 0
  integer(c_int32_t), parameter :: JOINTLIN_ABI_VERSION_MINOR = 7
  integer(c_int32_t), parameter :: JOINTLIN_OK = 0
  integer(c_int32_t), parameter :: JOINTLIN_ERR_NULL = 1
  integer(c_int32_t), parameter :: JOINTLIN_ERR_NON_FINITE = 2
  integer(c_int32_t), parameter :: JOINTLIN_ERR_OUT_OF_RANGE = 3
  integer(c_int32_t), parameter :: JOINTLIN_ERR_OVERFLOW = 4
  integer(c_int32_t), parameter :: JOINTLIN_ERR_PROPS = 5
  integer(c_int32_t), parameter :: JOINTLIN_ERR_SIZE = 6
  integer(c_int32_t), parameter :: JOINTLIN_ERR_NO_SOLUTION = 7
  integer(c_int32_t), parameter :: JOINTLIN_ERR_NOT_CONVERGED = 8
  integer(c_int32_t), parameter :: JOINTLIN_ERR_UNKNOWN_POINT = 9
  integer(c_int32_t), parameter :: JOINTLIN_ERR_SEQUENCE = 10
  integer(c_int32_t), parameter :: JOINTLIN_ERR_IO = 11
  integer(c_int32_t), parameter :: JOINTLIN_ERR_PANIC = 12
  integer(c_int32_t), parameter :: JOINTLIN_LAW_MINDLIN = 0
  integer(c_int32_t), parameter :: JOINTLIN_LAW_JENKINS = 1
  integer(c_int32_t), parameter :: JOINTLIN_RULE_THESIS = 0
  integer(c_int32_t), parameter :: JOINTLIN_RULE_MASING = 1
  integer(c_int32_t), parameter :: JOINTLIN_METHOD_GRADED = 0
  integer(c_int32_t), parameter :: JOINTLIN_METHOD_SIMPSON = 1
  integer(c_int32_t), parameter :: JOINTLIN_METHOD_GAUSS = 2
  integer(c_int32_t), parameter :: JOINTLIN_SIMPSON_DEFAULT_INTERVALS = 256
  integer(c_int32_t), parameter :: JOINTLIN_GAUSS_DEFAULT_POINTS = 64
  integer(c_int32_t), parameter :: JOINTLIN_REGIME_OPEN = 0
  integer(c_int32_t), parameter :: JOINTLIN_REGIME_STICK = 1
  integer(c_int32_t), parameter :: JOINTLIN_REGIME_MICROSLIP = 2
  integer(c_int32_t), parameter :: JOINTLIN_REGIME_SLIDING = 3
  integer(c_int32_t), parameter :: JOINTLIN_POINT_STATE_LEN = 23
  integer(c_int32_t), parameter :: JOINTLIN_NORMAL_LINEAR = 0
  integer(c_int32_t), parameter :: JOINTLIN_NORMAL_HERTZ = 1
  integer(c_int32_t), parameter :: JOINTLIN_POINT3D_MAX_CELLS = 128
  integer(c_int32_t), parameter :: JOINTLIN_POINT3D_DEFAULT_CELLS = 32
  integer(c_int32_t), parameter :: JOINTLIN_POINT3D_STATE_LEN = 261
  integer(c_int32_t), parameter :: JOINTLIN_POINT_DERIVATIVE_COLUMNS_MAX = 4096
  integer(c_int32_t), parameter :: JOINTLIN_DESCRIBE_INTEGRATED = 0
  integer(c_int32_t), parameter :: JOINTLIN_DESCRIBE_TABULATED = 1
  integer(c_int32_t), parameter :: JOINTLIN_UINTER_MIN_NPROPS = 7
  integer(c_int32_t), parameter :: JOINTLIN_UINTER_MAX_NPROPS = 12
  integer(c_int32_t), parameter :: JOINTLIN_UINTER_MIN_NSTATV = 57
  integer(c_int32_t), parameter :: JOINTLIN_SCHEME_DIRECT = 0
  integer(c_int32_t), parameter :: JOINTLIN_SCHEME_RELAXATION = 1
  integer(c_int32_t), parameter :: JOINTLIN_SCHEME_SECANT = 2
  integer(c_int32_t), parameter :: JOINTLIN_KINC_ORIGINAL = 0
  integer(c_int32_t), parameter :: JOINTLIN_KINC_SEQUENTIAL = 1
  integer(c_int32_t), parameter :: JOINTLIN_ACTION_RUNNING = 0
  integer(c_int32_t), parameter :: JOINTLIN_ACTION_RUN_SWEEP = 1
  integer(c_int32_t), parameter :: JOINTLIN_ACTION_RUN_PASS = 2
  integer(c_int32_t), parameter :: JOINTLIN_ACTION_RUN_FINAL = 3
  integer(c_int32_t), parameter :: JOINTLIN_ACTION_DONE = 4
  integer(c_int32_t), parameter :: JOINTLIN_ACTION_FAILED = 5

  ! ---- structs ----
  type, bind(C) :: jointlin_contact
     integer(c_int32_t) :: law
     integer(c_int32_t) :: rule
     real(c_double) :: mu
     real(c_double) :: normal_force
     real(c_double) :: k_t0
  end type jointlin_contact

  type, bind(C) :: jointlin_method
     integer(c_int32_t) :: kind
     integer(c_int32_t) :: points
  end type jointlin_method

  type, bind(C) :: jointlin_linearization
     real(c_double) :: k_star
     real(c_double) :: d_star
     real(c_double) :: eta
     real(c_double) :: energy_per_cycle
     real(c_double) :: peak_force
     real(c_double) :: slip_limit
     real(c_double) :: amplitude_ratio
     integer(c_int32_t) :: regime
  end type jointlin_linearization

  type, bind(C) :: jointlin_cubic_linearization
     real(c_double) :: k_star
     real(c_double) :: d_star
     real(c_double) :: energy_per_cycle
  end type jointlin_cubic_linearization

  type, bind(C) :: jointlin_step
     real(c_double) :: force
     real(c_double) :: tangent
     real(c_double) :: dissipated
  end type jointlin_step

  type, bind(C) :: jointlin_contact3d
     integer(c_int32_t) :: law
     integer(c_int32_t) :: cells
     real(c_double) :: mu
     real(c_double) :: k_t0
     integer(c_int32_t) :: normal_law
     real(c_double) :: normal_stiffness
     real(c_double) :: r_star
  end type jointlin_contact3d

  type, bind(C) :: jointlin_step3d
     real(c_double) :: force(3)
     real(c_double) :: stiffness(9)
     real(c_double) :: dissipated
     integer(c_int32_t) :: regime
  end type jointlin_step3d

  type, bind(C) :: jointlin_linearization3d
     real(c_double) :: k_star(2)
     real(c_double) :: d_star(2)
     real(c_double) :: energy_per_cycle
     integer(c_int32_t) :: regime
  end type jointlin_linearization3d

  type, bind(C) :: jointlin_linearization3d_matrix
     real(c_double) :: k_star(4)
     real(c_double) :: d_star(4)
     real(c_double) :: semi_axes(2)
     real(c_double) :: angle
     real(c_double) :: energy_per_cycle
     integer(c_int32_t) :: regime
  end type jointlin_linearization3d_matrix

  type, bind(C) :: jointlin_store_config
     real(c_double) :: initial_amplitude
     real(c_double) :: rtol
     real(c_double) :: atol
     integer(c_int32_t) :: scheme
     integer(c_int32_t) :: max_passes
     integer(c_int32_t) :: sweep_step
     integer(c_int32_t) :: kinc_numbering
     type(c_ptr) :: restart_path
     integer(c_size_t) :: restart_path_len
  end type jointlin_store_config

  type, bind(C) :: jointlin_pass_stats
     integer(c_int32_t) :: pass
     integer(c_int32_t) :: kind
     integer(c_int32_t) :: increments_run
     integer(c_int32_t) :: increments_converged
     integer(c_int64_t) :: evaluations
     integer(c_int64_t) :: not_reported
  end type jointlin_pass_stats

  type, bind(C) :: jointlin_point_status
     real(c_double) :: estimate(2)
     real(c_double) :: computed(2)
     integer(c_int32_t) :: directions
     integer(c_int32_t) :: converged
     integer(c_int32_t) :: passes
     integer(c_int32_t) :: reason
  end type jointlin_point_status

  type, bind(C) :: jointlin_uinter_report
     integer(c_int64_t) :: point
     integer(c_int32_t) :: closed
     integer(c_int32_t) :: directions
     real(c_double) :: pressure
     real(c_double) :: amplitude(2)
     real(c_double) :: k_star(2)
     real(c_double) :: d_star(2)
     real(c_double) :: eta(2)
     integer(c_int32_t) :: regime(2)
     real(c_double) :: energy_per_cycle
     real(c_double) :: dissipated_power
  end type jointlin_uinter_report

  ! ---- functions ----
  interface
     function jointlin_abi_version() bind(C, name='jointlin_abi_version')
       import :: c_int32_t
       integer(c_int32_t) :: jointlin_abi_version
     end function jointlin_abi_version

     function jointlin_status_message(code) bind(C, name='jointlin_status_message')
       import :: c_int32_t, c_ptr
       integer(c_int32_t), value :: code
       type(c_ptr) :: jointlin_status_message
     end function jointlin_status_message

     function jointlin_last_error(buf, len) bind(C, name='jointlin_last_error')
       import :: c_char, c_size_t
       character(kind=c_char), intent(out) :: buf(*)
       integer(c_size_t), value :: len
       integer(c_size_t) :: jointlin_last_error
     end function jointlin_last_error

     function jointlin_linearize(contact, amplitude, omega, method, out) &
          bind(C, name='jointlin_linearize')
       import :: c_int32_t, c_double, jointlin_contact, jointlin_method, &
            jointlin_linearization
       type(jointlin_contact), intent(in) :: contact
       real(c_double), value :: amplitude
       real(c_double), value :: omega
       type(jointlin_method), intent(in), optional :: method
       type(jointlin_linearization), intent(out) :: out
       integer(c_int32_t) :: jointlin_linearize
     end function jointlin_linearize

     function jointlin_linearize_cubic(k_lin, alpha, amplitude, out) &
          bind(C, name='jointlin_linearize_cubic')
       import :: c_int32_t, c_double, jointlin_cubic_linearization
       real(c_double), value :: k_lin
       real(c_double), value :: alpha
       real(c_double), value :: amplitude
       type(jointlin_cubic_linearization), intent(out) :: out
       integer(c_int32_t) :: jointlin_linearize_cubic
     end function jointlin_linearize_cubic

     function jointlin_cubic_force(k_lin, alpha, x, force, tangent) &
          bind(C, name='jointlin_cubic_force')
       import :: c_int32_t, c_double
       real(c_double), value :: k_lin
       real(c_double), value :: alpha
       real(c_double), value :: x
       real(c_double), intent(out) :: force
       real(c_double), intent(out) :: tangent
       integer(c_int32_t) :: jointlin_cubic_force
     end function jointlin_cubic_force

     ! C allows state_out == state; Fortran forbids passing one array as both (state is
     ! intent(in)): step a copy, or call with state_out = a second array.
     function jointlin_point_step(contact, state, slip, state_out, out) &
          bind(C, name='jointlin_point_step')
       import :: c_int32_t, c_double, jointlin_contact, jointlin_step
       type(jointlin_contact), intent(in) :: contact
       real(c_double), intent(in) :: state(*)
       real(c_double), value :: slip
       real(c_double), intent(inout) :: state_out(*)
       type(jointlin_step), intent(out) :: out
       integer(c_int32_t) :: jointlin_point_step
     end function jointlin_point_step

     function jointlin_point_step_derivatives(contact, state, d_state, slip, d_slip, &
          columns, state_out, d_state_out, out, d_force) &
          bind(C, name='jointlin_point_step_derivatives')
       import :: c_int32_t, c_size_t, c_double, jointlin_contact, jointlin_step
       type(jointlin_contact), intent(in) :: contact
       real(c_double), intent(in) :: state(*)
       real(c_double), intent(in) :: d_state(*)
       real(c_double), value :: slip
       real(c_double), intent(in) :: d_slip(*)
       integer(c_size_t), value :: columns
       real(c_double), intent(inout) :: state_out(*)
       real(c_double), intent(inout) :: d_state_out(*)
       type(jointlin_step), intent(out) :: out
       real(c_double), intent(inout) :: d_force(*)
       integer(c_int32_t) :: jointlin_point_step_derivatives
     end function jointlin_point_step_derivatives

     function jointlin_point3d_step(contact, state, disp, state_out, out) &
          bind(C, name='jointlin_point3d_step')
       import :: c_int32_t, c_double, jointlin_contact3d, jointlin_step3d
       type(jointlin_contact3d), intent(in) :: contact
       real(c_double), intent(in) :: state(*)
       real(c_double), intent(in) :: disp(*)
       real(c_double), intent(inout) :: state_out(*)
       type(jointlin_step3d), intent(out) :: out
       integer(c_int32_t) :: jointlin_point3d_step
     end function jointlin_point3d_step

     function jointlin_linearize3d(contact, normal_force, amplitude_1, amplitude_2, &
          omega, out) bind(C, name='jointlin_linearize3d')
       import :: c_int32_t, c_double, jointlin_contact3d, jointlin_linearization3d
       type(jointlin_contact3d), intent(in) :: contact
       real(c_double), value :: normal_force
       real(c_double), value :: amplitude_1
       real(c_double), value :: amplitude_2
       real(c_double), value :: omega
       type(jointlin_linearization3d), intent(out) :: out
       integer(c_int32_t) :: jointlin_linearize3d
     end function jointlin_linearize3d

     function jointlin_linearize3d_phasors(contact, normal_force, u_hat, omega, method, &
          out) bind(C, name='jointlin_linearize3d_phasors')
       import :: c_int32_t, c_double, jointlin_contact3d, jointlin_linearization3d_matrix
       type(jointlin_contact3d), intent(in) :: contact
       real(c_double), value :: normal_force
       real(c_double), intent(in) :: u_hat(4)
       real(c_double), value :: omega
       integer(c_int32_t), value :: method
       type(jointlin_linearization3d_matrix), intent(out) :: out
       integer(c_int32_t) :: jointlin_linearize3d_phasors
     end function jointlin_linearize3d_phasors

     function jointlin_screw_preload(torque, pitch, d2, mu_thread, mu_head, d_km, &
          preload) bind(C, name='jointlin_screw_preload')
       import :: c_int32_t, c_double
       real(c_double), value :: torque, pitch, d2, mu_thread, mu_head, d_km
       real(c_double), intent(out) :: preload
       integer(c_int32_t) :: jointlin_screw_preload
     end function jointlin_screw_preload

     function jointlin_store_config_default(out) &
          bind(C, name='jointlin_store_config_default')
       import :: c_int32_t, jointlin_store_config
       type(jointlin_store_config), intent(out) :: out
       integer(c_int32_t) :: jointlin_store_config_default
     end function jointlin_store_config_default

     function jointlin_store_new(config, out) bind(C, name='jointlin_store_new')
       import :: c_int32_t, c_ptr, jointlin_store_config
       type(jointlin_store_config), intent(in) :: config
       type(c_ptr), intent(out) :: out
       integer(c_int32_t) :: jointlin_store_new
     end function jointlin_store_new

     subroutine jointlin_store_free(store) bind(C, name='jointlin_store_free')
       import :: c_ptr
       type(c_ptr), value :: store
     end subroutine jointlin_store_free

     function jointlin_store_register_point(store, name, name_len, node, coords, mcrd, id) &
          bind(C, name='jointlin_store_register_point')
       import :: c_int32_t, c_int64_t, c_size_t, c_double, c_char, c_ptr
       type(c_ptr), value :: store
       character(kind=c_char), intent(in) :: name(*)
       integer(c_size_t), value :: name_len
       integer(c_int32_t), value :: node
       real(c_double), intent(in) :: coords(*)
       integer(c_int32_t), value :: mcrd
       integer(c_int64_t), intent(out) :: id
       integer(c_int32_t) :: jointlin_store_register_point
     end function jointlin_store_register_point

     function jointlin_store_estimate(store, point, kinc, amp) &
          bind(C, name='jointlin_store_estimate')
       import :: c_int32_t, c_int64_t, c_double, c_ptr
       type(c_ptr), value :: store
       integer(c_int64_t), value :: point
       integer(c_int32_t), value :: kinc
       real(c_double), intent(out) :: amp(2)
       integer(c_int32_t) :: jointlin_store_estimate
     end function jointlin_store_estimate

     function jointlin_store_report(store, point, kinc, amp) &
          bind(C, name='jointlin_store_report')
       import :: c_int32_t, c_int64_t, c_double, c_ptr
       type(c_ptr), value :: store
       integer(c_int64_t), value :: point
       integer(c_int32_t), value :: kinc
       real(c_double), intent(in) :: amp(2)
       integer(c_int32_t) :: jointlin_store_report
     end function jointlin_store_report

     function jointlin_store_report_node(store, node, kinc, amp, reported) &
          bind(C, name='jointlin_store_report_node')
       import :: c_int32_t, c_double, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t), value :: node
       integer(c_int32_t), value :: kinc
       real(c_double), intent(in) :: amp(2)
       integer(c_int32_t), intent(out) :: reported
       integer(c_int32_t) :: jointlin_store_report_node
     end function jointlin_store_report_node

     function jointlin_store_next_action(store, action, pass) &
          bind(C, name='jointlin_store_next_action')
       import :: c_int32_t, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t), intent(out) :: action
       integer(c_int32_t), intent(out) :: pass
       integer(c_int32_t) :: jointlin_store_next_action
     end function jointlin_store_next_action

     function jointlin_store_rerun_increments(store, kinc, cap, count) &
          bind(C, name='jointlin_store_rerun_increments')
       import :: c_int32_t, c_size_t, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t), intent(inout) :: kinc(*)
       integer(c_size_t), value :: cap
       integer(c_size_t), intent(out) :: count
       integer(c_int32_t) :: jointlin_store_rerun_increments
     end function jointlin_store_rerun_increments

     function jointlin_store_pass_stats(store, pass, out) &
          bind(C, name='jointlin_store_pass_stats')
       import :: c_int32_t, c_ptr, jointlin_pass_stats
       type(c_ptr), value :: store
       integer(c_int32_t), value :: pass
       type(jointlin_pass_stats), intent(out) :: out
       integer(c_int32_t) :: jointlin_store_pass_stats
     end function jointlin_store_pass_stats

     function jointlin_store_point_status(store, point, kinc, out) &
          bind(C, name='jointlin_store_point_status')
       import :: c_int32_t, c_int64_t, c_ptr, jointlin_point_status
       type(c_ptr), value :: store
       integer(c_int64_t), value :: point
       integer(c_int32_t), value :: kinc
       type(jointlin_point_status), intent(out) :: out
       integer(c_int32_t) :: jointlin_store_point_status
     end function jointlin_store_point_status

     function jointlin_store_point_count(store, count) &
          bind(C, name='jointlin_store_point_count')
       import :: c_int32_t, c_int64_t, c_ptr
       type(c_ptr), value :: store
       integer(c_int64_t), intent(out) :: count
       integer(c_int32_t) :: jointlin_store_point_count
     end function jointlin_store_point_count

     function jointlin_store_restore(store) bind(C, name='jointlin_store_restore')
       import :: c_int32_t, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t) :: jointlin_store_restore
     end function jointlin_store_restore

     function jointlin_store_new_ranked(config, rank, ranks, out) &
          bind(C, name='jointlin_store_new_ranked')
       import :: c_int32_t, c_ptr, jointlin_store_config
       type(jointlin_store_config), intent(in) :: config
       integer(c_int32_t), value :: rank
       integer(c_int32_t), value :: ranks
       type(c_ptr), intent(out) :: out
       integer(c_int32_t) :: jointlin_store_new_ranked
     end function jointlin_store_new_ranked

     function jointlin_store_restart_path(store, buf, cap, len) &
          bind(C, name='jointlin_store_restart_path')
       import :: c_int32_t, c_size_t, c_char, c_ptr
       type(c_ptr), value :: store
       character(kind=c_char), intent(out) :: buf(*)
       integer(c_size_t), value :: cap
       integer(c_size_t), intent(out) :: len
       integer(c_int32_t) :: jointlin_store_restart_path
     end function jointlin_store_restart_path

     function jointlin_store_set_model(store, bytes, len) &
          bind(C, name='jointlin_store_set_model')
       import :: c_int32_t, c_size_t, c_char, c_ptr
       type(c_ptr), value :: store
       character(kind=c_char), intent(in) :: bytes(*)
       integer(c_size_t), value :: len
       integer(c_int32_t) :: jointlin_store_set_model
     end function jointlin_store_set_model

     function jointlin_store_pass_summary(store, summary, cap, len) &
          bind(C, name='jointlin_store_pass_summary')
       import :: c_int32_t, c_size_t, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t), intent(inout) :: summary(*)
       integer(c_size_t), value :: cap
       integer(c_size_t), intent(out) :: len
       integer(c_int32_t) :: jointlin_store_pass_summary
     end function jointlin_store_pass_summary

     function jointlin_store_pass_agree(store, reduced, len) &
          bind(C, name='jointlin_store_pass_agree')
       import :: c_int32_t, c_size_t, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t), intent(in) :: reduced(*)
       integer(c_size_t), value :: len
       integer(c_int32_t) :: jointlin_store_pass_agree
     end function jointlin_store_pass_agree

     function jointlin_store_agree_files(store, rank, ranks, timeout) &
          bind(C, name='jointlin_store_agree_files')
       import :: c_int32_t, c_double, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t), value :: rank
       integer(c_int32_t), value :: ranks
       real(c_double), value :: timeout
       integer(c_int32_t) :: jointlin_store_agree_files
     end function jointlin_store_agree_files

     function jointlin_uexternaldb(store, lop, lrestart, time, dtime, kstep, kinc) &
          bind(C, name='jointlin_uexternaldb')
       import :: c_int32_t, c_double, c_ptr
       type(c_ptr), value :: store
       integer(c_int32_t), value :: lop
       integer(c_int32_t), value :: lrestart
       real(c_double), intent(in) :: time(2)
       real(c_double), value :: dtime
       integer(c_int32_t), value :: kstep
       integer(c_int32_t), value :: kinc
       integer(c_int32_t) :: jointlin_uexternaldb
     end function jointlin_uexternaldb

     function jointlin_uinter(store, stress, ddsddr, dviscous, dstructural, statev, sfd, &
          pnewdt, rdisp, drdisp, time, dtime, freqr, ciname, ciname_len, props, coords, &
          area, node, ndir, nstatv, nprops, mcrd, kstep, kinc, linper, lopenclose, report) &
          bind(C, name='jointlin_uinter')
       import :: c_int32_t, c_size_t, c_double, c_char, c_ptr, jointlin_uinter_report
       type(c_ptr), value :: store
       real(c_double), intent(inout) :: stress(*)
       real(c_double), intent(inout) :: ddsddr(*)
       real(c_double), intent(inout) :: dviscous(*)
       real(c_double), intent(inout) :: dstructural(*)
       real(c_double), intent(inout) :: statev(*)
       real(c_double), intent(inout) :: sfd
       real(c_double), intent(inout) :: pnewdt
       real(c_double), intent(in) :: rdisp(*)
       real(c_double), intent(in) :: drdisp(*)
       real(c_double), intent(in) :: time(2)
       real(c_double), value :: dtime
       real(c_double), value :: freqr
       character(kind=c_char), intent(in) :: ciname(*)
       integer(c_size_t), value :: ciname_len
       real(c_double), intent(in) :: props(*)
       real(c_double), intent(in) :: coords(*)
       real(c_double), value :: area
       integer(c_int32_t), value :: node
       integer(c_int32_t), value :: ndir
       integer(c_int32_t), value :: nstatv
       integer(c_int32_t), value :: nprops
       integer(c_int32_t), value :: mcrd
       integer(c_int32_t), value :: kstep
       integer(c_int32_t), value :: kinc
       integer(c_int32_t), value :: linper
       integer(c_int32_t), intent(inout) :: lopenclose
       type(jointlin_uinter_report), intent(out), optional :: report
       integer(c_int32_t) :: jointlin_uinter
     end function jointlin_uinter

     function jointlin_uinter_props_check(props, nprops) &
          bind(C, name='jointlin_uinter_props_check')
       import :: c_int32_t, c_double
       real(c_double), intent(in) :: props(*)
       integer(c_int32_t), value :: nprops
       integer(c_int32_t) :: jointlin_uinter_props_check
     end function jointlin_uinter_props_check
  end interface
end module jointlin
