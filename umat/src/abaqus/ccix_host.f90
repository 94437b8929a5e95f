!> How the UMAT talks to Abaqus/Standard beyond the argument list (the file camclay9_umat_abaqus.for;
!> umat/src/ccix_host.f90 is the variant for other hosts). Messages go to the message file, job.msg,
!> which user subroutines may write on Fortran unit 7 (Abaqus Analysis User's Guide, "Fortran unit
!> numbers"), in the "***ERROR:" / "***WARNING:" form of Abaqus' own messages; the analysis is ended
!> with the utility routine XIT (Abaqus User Subroutines Guide, "Utility routines", "Terminating an
!> analysis"), which closes Abaqus' files; a Fortran STOP from a user subroutine would not.
module ccix_host
  implicit none
  private

  !> Abaqus/Standard's message file (.msg).
  integer, parameter, public :: message_unit = 7

  public :: host_warning, host_stop

contains

  !> One line in the .msg file about a call the UMAT rejected (PNEWDT < 1); the analysis goes on.
  !> Flushed, so that the line is in the file whatever becomes of the analysis after it.
  recursive subroutine host_warning(message)
    character(len=*), intent(in) :: message
    write (message_unit, '(a)') '***WARNING: ' // message
    flush (message_unit)
  end subroutine host_warning

  !> message in the .msg file, then XIT ends the analysis.
  recursive subroutine host_stop(message)
    character(len=*), intent(in) :: message
    external :: xit
    write (message_unit, '(a)') '***ERROR: ' // message
    flush (message_unit)
    call xit()
    error stop 'Cam-Clay IX UMAT: XIT returned'   ! XIT does not return in Abaqus
  end subroutine host_stop

end module ccix_host
