!> A stand-in for Abaqus/Standard around camclay9_umat_abaqus.for (tests/umat/host_files.cmake): the
!> message file job.msg on Fortran unit 7, and the utility routine XIT, which here closes it, says so on
!> standard output and ends the process with exit code 3 (Abaqus ends the analysis). The include file
!> aba_param.inc of this folder stands in for Abaqus' own.
subroutine mock_abaqus_start() bind(c, name='mock_abaqus_start_')
  implicit none
  open (7, file='job.msg', status='replace', action='write')
end subroutine mock_abaqus_start

subroutine xit()
  implicit none
  close (7)
  write (*, '(a)') 'mock Abaqus: XIT called, analysis ended'
  flush (6)
  stop 3
end subroutine xit
