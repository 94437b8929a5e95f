!> How the UMAT talks to its host beyond the Abaqus argument list: where its messages go, and how it
!> ends the analysis on input that no smaller step can repair (invalid PROPS or sizes). This is the
!> variant for any host (the libraries, camclay9_umat.f90); umat/src/abaqus/ccix_host.f90 is the one
!> of the Abaqus file (its message file and XIT). docs/umat.md, "Errors", says what each host sees.
!>
!> A host build can end the analysis its own way without editing this file: compiled through the C
!> preprocessor with the macro CAMCLAY9_STOP_HOOK defined as the name of a subroutine of the host,
!>     gfortran -cpp -DCAMCLAY9_STOP_HOOK=my_stop -c camclay9_umat.f90
!> the call in host_stop below becomes a call of my_stop(message) (character(len=*) message; from C,
!> void my_stop_(const char *message, size_t length)), which shows the message where the host shows
!> its own and stops the host its way. The call is written in capitals for that reason (the
!> preprocessor replaces only the exact spelling); without the macro it calls the default below,
!> camclay9_stop_hook, which writes the message on standard error. If the hook returns, error stop.
module ccix_host
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private

  !> The unit of the UMAT's messages: standard error.
  integer, parameter, public :: message_unit = error_unit

  public :: host_warning, host_stop

contains

  !> One line for the host's user about a call the UMAT rejected (PNEWDT < 1); the analysis goes on.
  !> Flushed: gfortran buffers standard error when it is not a terminal, and the host's own messages
  !> (C's stderr, unbuffered) would otherwise come before it.
  recursive subroutine host_warning(message)
    character(len=*), intent(in) :: message
    write (message_unit, '(a)') message
    flush (message_unit)
  end subroutine host_warning

  !> message where the host shows it, then the host's way to stop: here the hook, then error stop. The
  !> message unit is flushed first: error stop writes its own line straight to standard error, so with
  !> standard error redirected to a file (buffered) that line came before the message.
  recursive subroutine host_stop(message)
    character(len=*), intent(in) :: message
    call CAMCLAY9_STOP_HOOK(message)
    flush (message_unit)
    error stop 'Cam-Clay IX UMAT: analysis stopped (the message above says why)'
  end subroutine host_stop

  !> The stop hook when the host gives none: the message on standard error.
  recursive subroutine camclay9_stop_hook(message)
    character(len=*), intent(in) :: message
    write (message_unit, '(a)') message
    flush (message_unit)
  end subroutine camclay9_stop_hook

end module ccix_host
