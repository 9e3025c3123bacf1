! jl_allreduce_max without MPI (the default build, MPI=no): always "no communicator", so
! the shim's ranks agree through files (jointlin_store_agree_files). agree_mpi.f90 is the
! same routine over the host's MPI communicator.
!
!   buf(n)  the integers to reduce (unchanged here)
!   ranks   the number of processes the shim expects (GETNUMCPUS)
!   status  0 reduced, 1 no communicator, 2 MPI error, 3 communicator of another size
subroutine jl_allreduce_max(buf, n, ranks, status)
  use, intrinsic :: iso_c_binding, only: c_int32_t
  implicit none
  integer, intent(in) :: n, ranks
  integer(c_int32_t), intent(inout) :: buf(n)
  integer, intent(out) :: status
  status = 1
end subroutine jl_allreduce_max
