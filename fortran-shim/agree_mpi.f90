! jl_allreduce_max over the host's MPI communicator (the build with MPI=yes): the
! element-wise maximum of buf over all ranks, in place. The communicator is the one
! Abaqus hands to user subroutines, GETCOMMUNICATOR() (outside Abaqus:
! abaqus_standin_mpi.f90). Compile with the mpif.h of the MPI the host runs with (for
! Abaqus the MPI it ships, e.g. Intel MPI's include directory); the library libjointlin.so
! itself has no MPI dependency.
!
!   buf(n)  the integers to reduce, replaced by their maximum over the ranks
!   ranks   the number of processes the shim expects (GETNUMCPUS)
!   status  0 reduced, 1 no communicator (MPI not initialized or MPI_COMM_NULL),
!           2 MPI error, 3 communicator of another size than ranks
subroutine jl_allreduce_max(buf, n, ranks, status)
  use, intrinsic :: iso_c_binding, only: c_int32_t
  implicit none
  include 'mpif.h'
  integer, intent(in) :: n, ranks
  integer(c_int32_t), intent(inout) :: buf(n)
  integer, intent(out) :: status
  integer, external :: getcommunicator
  integer :: comm, size, ierr
  logical :: up
  call MPI_INITIALIZED(up, ierr)
  status = 1
  if (ierr /= MPI_SUCCESS .or. .not. up) return
  comm = getcommunicator()
  if (comm == MPI_COMM_NULL) return
  status = 2
  call MPI_COMM_SIZE(comm, size, ierr)
  if (ierr /= MPI_SUCCESS) return
  status = 3
  if (size /= ranks) return
  status = 2
  call MPI_ALLREDUCE(MPI_IN_PLACE, buf, n, MPI_INTEGER4, MPI_MAX, comm, ierr)
  if (ierr == MPI_SUCCESS) status = 0
end subroutine jl_allreduce_max
