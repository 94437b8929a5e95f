!> C-callable entry points besides the UMAT itself (which C calls as umat_ with the Abaqus list).
module ccix_capi
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
  use ccix_props, only: check_props, message_len
  implicit none
  private
  public :: camclay9_check_props

contains

  !> Check a PROPS vector and the sizes without integrating anything (umat-interface.md). code = 0 if
  !> valid; else the PROPS slot (or -1 NPROPS, -2 NSTATV, -3 NTENS, -4 NDI) and a NUL-terminated
  !> message of at most message_capacity bytes naming slot, value and allowed range.
  recursive subroutine camclay9_check_props(props, nprops, nstatv, ntens, ndi, code, message, &
                                  message_capacity) bind(c, name='camclay9_check_props')
    integer(c_int), intent(in), value :: nprops, nstatv, ntens, ndi, message_capacity
    real(c_double), intent(in) :: props(*)
    integer(c_int), intent(out) :: code
    character(kind=c_char), intent(out) :: message(*)
    character(len=message_len) :: msg
    integer :: i, n, icode
    call check_props(props, int(nprops), int(nstatv), int(ntens), int(ndi), icode, msg)
    code = icode
    if (message_capacity <= 0) return
    n = min(len_trim(msg), message_capacity - 1)
    do i = 1, n
      message(i) = msg(i:i)
    end do
    message(n + 1) = c_null_char
  end subroutine camclay9_check_props

end module ccix_capi
