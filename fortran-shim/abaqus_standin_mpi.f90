! Stand-ins for the Abaqus utility routines the shim calls, for hosts that run the shim
! under MPI outside Abaqus (tests/hosts_mpi.rs): every process of MPI_COMM_WORLD is one
! rank of the analysis. The host initializes MPI before its first UEXTERNALDB call.
! Never link this into an Abaqus user library: Abaqus provides the real routines.

!> GETRANK(KPROCESSNUM): this process's rank in MPI_COMM_WORLD.
subroutine getrank(kprocessnum)
  implicit none
  include 'mpif.h'
  integer, intent(out) :: kprocessnum
  integer :: ierr
  call MPI_COMM_RANK(MPI_COMM_WORLD, kprocessnum, ierr)
end subroutine getrank

!> GETNUMCPUS(NUMPROCESSES): the number of processes, the size of MPI_COMM_WORLD.
subroutine getnumcpus(numprocesses)
  implicit none
  include 'mpif.h'
  integer, intent(out) :: numprocesses
  integer :: ierr
  call MPI_COMM_SIZE(MPI_COMM_WORLD, numprocesses, ierr)
end subroutine getnumcpus

!> GETCOMMUNICATOR(): the communicator of the analysis's processes, MPI_COMM_WORLD.
integer function getcommunicator()
  implicit none
  include 'mpif.h'
  getcommunicator = MPI_COMM_WORLD
end function getcommunicator

!> STDB_ABQERR(LOP, STRING, INTV, REALV, CHARV): as abaqus_standin.f, but LOP = -3 ends
!> every process (MPI_ABORT), as an analysis error ends the whole Abaqus job.
subroutine stdb_abqerr(lop, string, intv, realv, charv)
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  include 'mpif.h'
  integer, intent(in) :: lop
  character(len=*), intent(in) :: string
  integer, intent(in) :: intv(*)
  double precision, intent(in) :: realv(*)
  character(len=8), intent(in) :: charv(*)
  integer :: rank, ierr
  call MPI_COMM_RANK(MPI_COMM_WORLD, rank, ierr)
  write (error_unit, '(a,i0,a,i0,2a)') 'STDB_ABQERR rank ', rank, ' ', lop, ': ', trim(string)
  flush (error_unit)
  if (lop == -3) call MPI_ABORT(MPI_COMM_WORLD, 3, ierr)
end subroutine stdb_abqerr
