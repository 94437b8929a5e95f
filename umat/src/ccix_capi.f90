!> C-callable entry points besides the UMAT itself (which C calls as umat_ with the Abaqus list).
module ccix_capi
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
  use ccix_props, only: check_props, message_len, prop_names, nprops_normal, n_statev_blocks, &
                        statev_block_names, statev_block_first, statev_block_size
  implicit none
  private
  public :: camclay9_check_props, camclay9_prop_name, camclay9_statev_block

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

  !> The name of PROPS slot (0-based, as C counts) into name (NUL-terminated, at most capacity bytes);
  !> returns the name's length, or 0 when slot is not a PROPS slot of the model (slot < 0 or >= 23).
  recursive integer(c_int) function camclay9_prop_name(slot, name, capacity) result(n) &
      bind(c, name='camclay9_prop_name')
    integer(c_int), intent(in), value :: slot, capacity
    character(kind=c_char), intent(out) :: name(*)
    integer :: i
    n = 0
    if (capacity > 0) name(1) = c_null_char
    if (slot < 0 .or. slot >= nprops_normal .or. capacity <= 0) return
    n = int(min(len_trim(prop_names(slot + 1)), capacity - 1), c_int)
    do i = 1, n
      name(i) = prop_names(slot + 1)(i:i)
    end do
    name(n + 1) = c_null_char
  end function camclay9_prop_name

  !> STATEV block k (0-based) of the model: its name into name (NUL-terminated, at most capacity bytes),
  !> its first slot (0-based, as C counts) and its number of slots. Returns 1, or 0 when there is no
  !> block k (then first = -1, size = 0).
  recursive integer(c_int) function camclay9_statev_block(k, name, capacity, first, size) result(found) &
      bind(c, name='camclay9_statev_block')
    integer(c_int), intent(in), value :: k, capacity
    character(kind=c_char), intent(out) :: name(*)
    integer(c_int), intent(out) :: first, size
    integer :: i, n
    found = 0
    first = -1
    size = 0
    if (capacity > 0) name(1) = c_null_char
    if (k < 0 .or. k >= n_statev_blocks) return
    found = 1
    first = int(statev_block_first(k + 1) - 1, c_int)
    size = int(statev_block_size(k + 1), c_int)
    if (capacity <= 0) return
    n = min(len_trim(statev_block_names(k + 1)), capacity - 1)
    do i = 1, n
      name(i) = statev_block_names(k + 1)(i:i)
    end do
    name(n + 1) = c_null_char
  end function camclay9_statev_block

end module ccix_capi
