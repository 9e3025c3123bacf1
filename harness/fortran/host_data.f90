! Shared data and helpers of the Fortran host programs: the same numbers as
! ../c/host.h (block on a plane, Appendix C, stress form with AREA = 1; the sweep's
! two-point model). Output records as in the C hosts: "<name> <number> ...".
module host_data
  use, intrinsic :: iso_c_binding, only: c_double, c_double_complex
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

  !> The stand-in results file of step 2, increment `kinc` (format: abaqus_standin.f):
  !> per point its node header (node j, 3 components) and CDISP record: separation 0,
  !> slip x(j) in the local 1-direction, 0 in the 2-direction, real parts then imaginary.
  subroutine write_results_file(kinc, x, corrupt)
    integer, intent(in) :: kinc
    complex(c_double_complex), intent(in) :: x(:)
    logical, intent(in) :: corrupt
    integer :: u, j
    open (newunit=u, file='jointlin-standin.fil', status='replace', action='write')
    write (u, '(a,i0)') '2000 2 2 ', kinc
    do j = 1, size(x)
       write (u, '(a,i0,a)') '1504 2 ', j, ' 3'
       if (corrupt) then
          write (u, '(a,5es25.17)') '1521 0', 0d0, x(j)%re, 0d0, 0d0, x(j)%im
       else
          write (u, '(a,6es25.17)') '1521 0', 0d0, x(j)%re, 0d0, 0d0, x(j)%im, 0d0
       end if
    end do
    close (u)
  end subroutine write_results_file

  subroutine record(name, values)
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: values(:)
    write (*, '(a,*(1x,es25.17e3))') name, values
  end subroutine record
end module host_data
