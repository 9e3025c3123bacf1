! The same linearization from Fortran, through the jointlin module.
program hello
  use, intrinsic :: iso_c_binding, only: c_int32_t
  use jointlin
  implicit none
  type(jointlin_contact) :: c
  type(jointlin_linearization) :: l
  integer(c_int32_t) :: status
  c = jointlin_contact(JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS, 0.3d0, 2d0, 1282.7d0)
  status = jointlin_linearize(c, 4.401d-4, 1.3d0, out=l) ! method omitted: NULL, default
  if (status /= JOINTLIN_OK) error stop 'jointlin_linearize failed'
  print '(a,g0.6,a,g0.6,a)', 'k* = ', l%k_star, ' N/mm, d* = ', l%d_star, ' N s/mm'
end program hello
