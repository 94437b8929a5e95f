!> C-callable entry points besides the UMAT itself (which C calls as umat_ with the Abaqus list).
module ccix_capi
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_null_char
  use ccix_props, only: check_props, message_len, prop_table, nprops_normal, n_statev_blocks, &
                        statev_block_names, statev_block_first, statev_block_size
  implicit none
  private
  public :: camclay9_check_props, camclay9_prop_name, camclay9_prop_info, camclay9_statev_block

  !> One PROPS slot of ccix_props' prop_table, as C reads it (camclay9.h, camclay9_prop_info_t): the
  !> strings NUL-terminated.
  type, bind(c), public :: c_prop_info_t
    character(kind=c_char) :: name(16), symbol(16), unit(16), meaning(80)
    real(c_double) :: lo, hi
    integer(c_int) :: bounds
  end type c_prop_info_t

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
    integer :: icode, n
    call check_props(props, int(nprops), int(nstatv), int(ntens), int(ndi), icode, msg)
    code = icode
    n = c_string(msg, message, message_capacity)
  end subroutine camclay9_check_props

  !> The name of PROPS slot (0-based, as C counts) into name (NUL-terminated, at most capacity bytes);
  !> returns the name's length, or 0 when slot is not a PROPS slot of the model (slot < 0 or >= 23).
  recursive integer(c_int) function camclay9_prop_name(slot, name, capacity) result(n) &
      bind(c, name='camclay9_prop_name')
    integer(c_int), intent(in), value :: slot, capacity
    character(kind=c_char), intent(out) :: name(*)
    n = c_string('', name, capacity)
    if (slot < 0 .or. slot >= nprops_normal) return
    n = c_string(prop_table(slot + 1)%name, name, capacity)
  end function camclay9_prop_name

  !> PROPS slot (0-based) of the contract into info: name, symbol, unit, meaning, the slot's own bounds
  !> lo and hi (-DBL_MAX, DBL_MAX where it has none) and the bits saying which apply and whether they
  !> are closed (CAMCLAY9_BOUND_*). Returns 1, or 0 when slot is not a PROPS slot (info then empty).
  recursive integer(c_int) function camclay9_prop_info(slot, info) result(found) &
      bind(c, name='camclay9_prop_info')
    integer(c_int), intent(in), value :: slot
    type(c_prop_info_t), intent(out) :: info
    integer :: n
    found = 0
    info%lo = 0
    info%hi = 0
    info%bounds = 0
    n = c_string('', info%name, size(info%name))
    n = c_string('', info%symbol, size(info%symbol))
    n = c_string('', info%unit, size(info%unit))
    n = c_string('', info%meaning, size(info%meaning))
    if (slot < 0 .or. slot >= nprops_normal) return
    found = 1
    associate (pr => prop_table(slot + 1))
      n = c_string(pr%name, info%name, size(info%name))
      n = c_string(pr%symbol, info%symbol, size(info%symbol))
      n = c_string(pr%unit, info%unit, size(info%unit))
      n = c_string(pr%meaning, info%meaning, size(info%meaning))
      info%lo = pr%lo
      info%hi = pr%hi
      info%bounds = pr%bounds
    end associate
  end function camclay9_prop_info

  !> STATEV block k (0-based) of the model: its name into name (NUL-terminated, at most capacity bytes),
  !> its first slot (0-based, as C counts) and its number of slots. Returns 1, or 0 when there is no
  !> block k (then first = -1, size = 0).
  recursive integer(c_int) function camclay9_statev_block(k, name, capacity, first, size) result(found) &
      bind(c, name='camclay9_statev_block')
    integer(c_int), intent(in), value :: k, capacity
    character(kind=c_char), intent(out) :: name(*)
    integer(c_int), intent(out) :: first, size
    integer :: n
    found = 0
    first = -1
    size = 0
    n = c_string('', name, capacity)
    if (k < 0 .or. k >= n_statev_blocks) return
    found = 1
    first = int(statev_block_first(k + 1) - 1, c_int)
    size = int(statev_block_size(k + 1), c_int)
    n = c_string(statev_block_names(k + 1), name, capacity)
  end function camclay9_statev_block

  !> text without its trailing blanks into the C string buf of capacity bytes (NUL-terminated,
  !> truncated to fit; nothing when capacity <= 0). Returns the number of characters copied.
  recursive integer(c_int) function c_string(text, buf, capacity) result(n)
    character(len=*), intent(in) :: text
    character(kind=c_char), intent(out) :: buf(*)
    integer(c_int), intent(in) :: capacity
    integer :: i
    n = 0
    if (capacity <= 0) return
    n = int(min(len_trim(text), capacity - 1), c_int)
    do i = 1, n
      buf(i) = text(i:i)
    end do
    buf(n + 1) = c_null_char
  end function c_string

end module ccix_capi
