! Shared data and helpers of the Fortran host programs: the same numbers as
! ../c/host.h (block on a plane, Appendix C, stress form with AREA = 1; the sweep's
! two-point model). Output records as in the C hosts: "<name> <number> ...".
module host_data
  use, intrinsic :: iso_c_binding, only: c_double
  implicit none
  real(c_double), parameter :: mu = 0.3d0, kt0 = 1282.7d0, kn = 1.0d4
  real(c_double), parameter :: h_block = 2.0d-4, h_second = 1.0d-4
  real(c_double), parameter :: mass = 0.002d0, omega_block = 1.3d0, force = 0.5d0
  real(c_double), parameter :: pi = 3.14159265358979323846d0
  real(c_double), parameter :: amplitude = 4.401d-4
  real(c_double), parameter :: kc = 600.0d0
  real(c_double), parameter :: sweep_omega(3) = [1.3d0, 300.0d0, 500.0d0]
  integer, parameter :: nstatv = 57, nprops = 12
contains
  !> PROPS of the block: Mindlin, thesis rule, mu, k_T0, linear normal law k_N; damping
  !> 0 viscous (DVISCOUS), 1 structural (DSTRUCTURAL).
  function block_props(damping) result(props)
    real(c_double), intent(in) :: damping
    real(c_double) :: props(nprops)
    props = [0d0, 0d0, mu, kt0, 0d0, kn, 0d0, 0d0, 0d0, damping, 0d0, 0d0]
  end function block_props

  subroutine record(name, values)
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: values(:)
    write (*, '(a,*(1x,es25.17e3))') name, values
  end subroutine record
end module host_data
