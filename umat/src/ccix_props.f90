!> The PROPS and STATEV contract of the Cam-Clay IX UMAT (docs/umat-interface.md): slot
!> numbers, the property checks with their messages, and the frames built from PROPS.
module ccix_props
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use ccix_tensor, only: first_not_finite
  use ccix_walpole, only: walpole_basis
  use ccix_frame, only: frame_t, frame_new
  implicit none
  private

  ! PROPS slots.
  integer, parameter, public :: ip_phi = 1, ip_hard = 2, ip_soft = 14, ip_tol = 20, ip_normal = 21
  integer, parameter, public :: nprops_min = 19, nprops_normal = 23
  ! STATEV slots (first slot of each block); 6 components per tensor whatever NTENS is.
  integer, parameter, public :: is_sig_hard = 1, is_evp_hard = 7, is_pc_hard = 13, &
                                is_sig_soft = 14, is_evp_soft = 20, is_pc_soft = 26, &
                                is_evp_total = 27, nstatv_min = 32
  ! Optional diagnostics, written only when NSTATV >= nstatv_diag.
  integer, parameter, public :: is_iterations = 33, is_flags = 34, is_f_hard = 35, is_f_soft = 36, &
                                nstatv_diag = 36
  integer, parameter, public :: message_len = 256
  !> The STATEV blocks (docs/umat.md "STATEV"): name, first slot, number of slots. The C side reads
  !> them through camclay9_statev_block; the fields the driver writes carry these names.
  integer, parameter, public :: n_statev_blocks = 11
  character(len=10), parameter, public :: statev_block_names(n_statev_blocks) = [character(len=10) :: &
    'sig_hard', 'evp_hard', 'pc_hard', 'sig_soft', 'evp_soft', 'pc_soft', 'evp', 'iterations', 'flags', &
    'f_hard', 'f_soft']
  integer, parameter, public :: statev_block_first(n_statev_blocks) = [is_sig_hard, is_evp_hard, &
    is_pc_hard, is_sig_soft, is_evp_soft, is_pc_soft, is_evp_total, is_iterations, is_flags, is_f_hard, is_f_soft]
  integer, parameter, public :: statev_block_size(n_statev_blocks) = [6, 6, 1, 6, 6, 1, 6, 1, 1, 1, 1]
  !> How a PROPS slot is bounded (prop_t%bounds; C: CAMCLAY9_BOUND_*): it has a lower bound lo, closed
  !> (value >= lo) or open (value > lo); likewise an upper bound hi; and it enters conditions with other
  !> slots (check_props' named checks: positive-definite stiffness and projection tensor, the normal).
  integer, parameter, public :: bound_lo = 1, bound_lo_closed = 2, bound_hi = 4, bound_hi_closed = 8, &
                                bound_coupled = 16
  integer, parameter :: gt = bound_lo, ge = bound_lo + bound_lo_closed, &
                        closed01 = bound_lo + bound_lo_closed + bound_hi + bound_hi_closed, cp = bound_coupled
  real(real64), parameter :: none = huge(1.0_real64)   ! lo = -none, hi = none: no bound of the slot's own
  !> One PROPS slot of the contract (docs/umat.md "PROPS", MFront-style): its name, the symbol the
  !> messages write, its unit (with stresses in MPa and time in s: the routine takes any consistent set),
  !> its own bounds as check_props applies them, its meaning in one line, and what a message about it
  !> adds after the range. C reads the same table through camclay9_prop_info.
  type, public :: prop_t
    character(len=13) :: name      !< the one spelling of hosts and scenes (material.set, calibrate)
    character(len=8) :: symbol     !< as the messages write it
    character(len=7) :: unit       !< '-': none
    real(real64) :: lo, hi         !< -none, none where the slot has no bound of its own
    integer :: bounds              !< bound_* bits
    character(len=64) :: meaning   !< as docs/umat.md's PROPS table says it
    character(len=48) :: note      !< a message's words after the range
  end type prop_t
  !> The PROPS contract, in slot order.
  type(prop_t), parameter, public :: prop_table(nprops_normal) = [ &
    prop_t('phi', 'phi', '-', 0.0_real64, 1.0_real64, closed01, &
           'volume fraction of the hard frame (soft frame: 1 - phi)', 'the volume fraction of the hard frame'), &
    prop_t('lambda_hard', 'lambda', 'MPa', -none, none, cp, 'hard frame, Lame constant', ''), &
    prop_t('muT_hard', 'mu_T', 'MPa', 0.0_real64, none, gt + cp, 'hard frame, shear modulus in the bedding plane', &
           'hard frame, shear modulus in the bedding plane'), &
    prop_t('muL_hard', 'mu_L', 'MPa', 0.0_real64, none, gt + cp, 'hard frame, shear modulus normal to the bedding', &
           'hard frame, shear modulus normal to the bedding'), &
    prop_t('a_hard', 'a', 'MPa', -none, none, cp, 'hard frame, anisotropy constant (alpha)', ''), &
    prop_t('b_hard', 'b', 'MPa', -none, none, cp, 'hard frame, anisotropy constant (beta)', ''), &
    prop_t('M_hard', 'M', '-', 0.0_real64, none, gt, 'hard frame, slope of the critical state line', 'hard frame'), &
    prop_t('lambda_p_hard', 'lambda_p', '-', 0.0_real64, none, gt, 'hard frame, plastic compressibility', &
           'hard frame'), &
    prop_t('c1', 'c1', '-', 0.0_real64, none, gt + cp, 'hard frame, projection tensor constant c1', &
           'hard frame projection tensor positive definite'), &
    prop_t('c2', 'c2', '-', -none, none, cp, 'hard frame, projection tensor constant c2', ''), &
    prop_t('c3', 'c3', '-', -none, none, cp, 'hard frame, projection tensor constant c3', ''), &
    prop_t('pc0_hard', 'pc0', 'MPa', 0.0_real64, none, gt, 'hard frame, initial preconsolidation pressure', &
           'hard frame'), &
    prop_t('eta_hard', 'eta', 'MPa^3 s', 0.0_real64, none, ge, 'hard frame, viscosity (0: rate independent)', &
           'hard frame; 0 is rate independent'), &
    prop_t('lambda_soft', 'lambda', 'MPa', -none, none, cp, 'soft frame, Lame constant', ''), &
    prop_t('mu_soft', 'mu', 'MPa', 0.0_real64, none, gt + cp, 'soft frame, shear modulus', 'soft frame shear modulus'), &
    prop_t('M_soft', 'M', '-', 0.0_real64, none, gt, 'soft frame, slope of the critical state line', 'soft frame'), &
    prop_t('lambda_p_soft', 'lambda_p', '-', 0.0_real64, none, gt, 'soft frame, plastic compressibility', &
           'soft frame'), &
    prop_t('pc0_soft', 'pc0', 'MPa', 0.0_real64, none, gt, 'soft frame, initial preconsolidation pressure', &
           'soft frame'), &
    prop_t('eta_soft', 'eta', 'MPa^3 s', 0.0_real64, none, ge, 'soft frame, viscosity (0: rate independent)', &
           'soft frame; 0 is rate independent'), &
    prop_t('tol', 'tol', '-', 0.0_real64, none, ge, 'tolerance on the viscoplastic strain increment of a step', &
           '0: no step control'), &
    prop_t('n1', 'n1', '-', -none, none, cp, 'bedding-plane normal, component 1 (normalised inside)', ''), &
    prop_t('n2', 'n2', '-', -none, none, cp, 'bedding-plane normal, component 2 (normalised inside)', ''), &
    prop_t('n3', 'n3', '-', -none, none, cp, 'bedding-plane normal, component 3 (normalised inside)', '')]
  ! The bounds as arrays, for check_props' one pass over all slots: value > lo_of or value == lo_eq,
  ! where lo_eq is lo for a closed bound and none (no finite value above lo but none) for an open one;
  ! a missing bound is a closed -none, which every finite value passes. Likewise above.
  real(real64), parameter :: lo_of(nprops_normal) = prop_table%lo, hi_of(nprops_normal) = prop_table%hi
  real(real64), parameter :: lo_eq(nprops_normal) = merge(prop_table%lo, none, &
    iand(prop_table%bounds, bound_lo_closed) /= 0 .or. iand(prop_table%bounds, bound_lo) == 0)
  real(real64), parameter :: hi_eq(nprops_normal) = merge(prop_table%hi, -none, &
    iand(prop_table%bounds, bound_hi_closed) /= 0 .or. iand(prop_table%bounds, bound_hi) == 0)

  public :: check_props, bedding_normal, frames_from_props

contains

  !> The bedding normal in the UMAT's frame: PROPS(21:23) normalised, or e3 when NPROPS < 23.
  pure recursive function bedding_normal(props, nprops) result(n)
    integer, intent(in) :: nprops
    real(real64), intent(in) :: props(nprops)
    real(real64) :: n(3), s
    if (nprops >= nprops_normal) then
      n = props(ip_normal:ip_normal + 2)
      s = n(1)**2 + n(2)**2 + n(3)**2
      if (.not. (s > 1.0e-300_real64 .and. s < 1.0e300_real64)) then
        ! the squares could underflow or overflow: scaled by the largest component first
        n = n * (1 / maxval(abs(n)))
        s = n(1)**2 + n(2)**2 + n(3)**2
      end if
      n = n * (1 / sqrt(s))
    else
      n = [0.0_real64, 0.0_real64, 1.0_real64]
    end if
  end function bedding_normal

  !> The hard (transversely isotropic) and soft (isotropic) frames of PROPS, and q, Walpole's basis of
  !> their bedding normal (ccix_walpole), which serves both: the soft frame is isotropic. Call
  !> check_props first.
  pure recursive subroutine frames_from_props(props, nprops, hard, soft, q)
    integer, intent(in) :: nprops
    real(real64), intent(in) :: props(nprops)
    type(frame_t), intent(out) :: hard, soft
    real(real64), intent(out) :: q(6, 6)
    real(real64) :: n(3)
    associate (h => props(ip_hard:ip_hard + 11), s => props(ip_soft:ip_soft + 5))
      n = bedding_normal(props, nprops)
      call walpole_basis(n, q)
      !                    lambda mu_T  mu_L  a     b     M     lambda_p c1    c2    c3     pc0    eta
      call frame_new(hard, h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8), h(9), h(10), h(11), h(12), &
                     n)
      call frame_new(soft, s(1), s(2), s(2), 0.0_real64, 0.0_real64, s(3), s(4), &
                     1.0_real64, 0.0_real64, 0.0_real64, s(5), s(6), n)
    end associate
  end subroutine frames_from_props

  !> Check sizes and properties without integrating anything. code = 0 when valid; otherwise code is
  !> the first offending PROPS slot (or -1 NPROPS, -2 NSTATV, -3 NTENS, -4 NDI) and message says the
  !> slot, its value and the allowed range.
  pure recursive subroutine check_props(props, nprops, nstatv, ntens, ndi, code, message)
    integer, intent(in) :: nprops, nstatv, ntens, ndi
    real(real64), intent(in) :: props(*)
    integer, intent(out) :: code
    character(len=message_len), intent(out) :: message
    real(real64) :: n3(3)
    integer :: i, n
    logical :: within

    code = 0
    message = ''
    call check_sizes(nprops, nstatv, ntens, ndi, code, message)
    if (code /= 0) return
    ! All finite, then all within their own bounds (prop_table), the usual case, each in one pass
    ! without branches; each slot only when one is not: its bounds one by one in the order of the
    ! messages (check_hard, check_soft). Finiteness first and by a quiet test (first_not_finite): an
    ! ordered comparison of a NaN raises the invalid exception, SIGFPE in a host with traps on.
    n = min(nprops, nprops_normal)
    i = first_not_finite(n, props)
    if (i > 0) then
      call require(code, message, props, .false., i, 'a finite number')
      return
    end if
    within = .true.
    do i = 1, n
      within = within .and. (props(i) > lo_of(i) .or. props(i) == lo_eq(i)) .and. &
                            (props(i) < hi_of(i) .or. props(i) == hi_eq(i))
    end do

    ! Each check acts only while no earlier one has failed, so the first offending slot is reported.
    call check_hard(props, within, code, message)
    call check_soft(props, within, code, message)
    if (nprops >= ip_tol) call require_bounds(code, props, within, ip_tol)
    if (code /= 0) then
      ! A slot outside its own bounds has its code and no message yet (require_bounds).
      if (message == '') call bounds_message(props, code, message)
      return
    end if
    if (nprops >= nprops_normal) then
      call require(code, message, props, any(props(ip_normal:ip_normal + 2) /= 0), ip_normal, &
                   'a non-zero bedding normal (n1, n2, n3) in PROPS 21-23')
      if (code /= 0) return
      if (ntens == 4) then
        n3 = bedding_normal(props, nprops)
        call require(code, message, props, abs(n3(3)) <= 1.0e-12_real64, ip_normal + 2, &
                     'n3 = 0: with NTENS = 4 ' // 'the bedding normal must lie in the 1-2 plane')
      end if
    else if (ntens == 4 .and. props(ip_phi) > 0) then
      ! (With phi = 0 the hard frame is not used and its normal does not matter.)
      code = ip_normal
      write (message, '(a,i0,a)') 'Cam-Clay IX UMAT: PROPS(21) to PROPS(23), the bedding normal, ' // &
        'are missing (NPROPS = ', nprops, '): with NTENS = 4 and phi > 0 give NPROPS = 23 ' // &
        'with a normal (n1, n2, 0) in the 1-2 plane'
      return
    end if

  end subroutine check_props

  !> NPROPS, NSTATV, NDI and NTENS (umat-interface.md): code -1, -2, -4, -3 and a message when not allowed.
  pure recursive subroutine check_sizes(nprops, nstatv, ntens, ndi, code, message)
    integer, intent(in) :: nprops, nstatv, ntens, ndi
    integer, intent(inout) :: code
    character(len=message_len), intent(inout) :: message
    if (nprops < nprops_min .or. nprops == 21 .or. nprops == 22) then
      code = -1
      write (message, '(a,i0,a)') 'Cam-Clay IX UMAT: NPROPS = ', nprops, &
        ' is not allowed: expected 19 or 20 (normal = material 3-axis) ' // &
        'or >= 23 (normal in PROPS 21-23)'
      return
    end if
    if (nstatv < nstatv_min) then
      code = -2
      write (message, '(a,i0,a,i0,a)') 'Cam-Clay IX UMAT: NSTATV = ', nstatv, &
        ' is too small: expected >= ', nstatv_min, ' (*DEPVAR)'
      return
    end if
    if (ndi /= 3) then
      code = -4
      write (message, '(a,i0,a)') 'Cam-Clay IX UMAT: NDI = ', ndi, &
        ': plane stress is not supported; ' // &
        'expected NDI = 3 (3D, plane strain, axisymmetric)'
      return
    end if
    if (ntens /= 6 .and. ntens /= 4) then
      code = -3
      write (message, '(a,i0,a)') &
        'Cam-Clay IX UMAT: NTENS = ', ntens, ': expected 6 (3D) or 4 (plane strain, axisymmetric)'
      return
    end if
  end subroutine check_sizes

  !> phi and the hard frame's PROPS 2-13: each slot's own bounds (prop_table), and the two conditions
  !> across slots, a positive-definite stiffness and projection tensor, in the order of the messages.
  pure recursive subroutine check_hard(props, within, code, message)
    real(real64), intent(in) :: props(*)
    logical, intent(in) :: within   !< every slot within its own bounds
    integer, intent(inout) :: code
    character(len=message_len), intent(inout) :: message
    real(real64) :: lam, mu_t, mu_l, a, b, c33
    call require_bounds(code, props, within, ip_phi)
    ! Hard frame: positive-definite TI stiffness. In bedding axes the Mandel stiffness splits into
    ! 2 mu_T, 2 mu_T, 2 mu_L, 2 mu_L and the 2x2 block [[2(lam + mu_T), sqrt2 (lam + a)], [., C33]]
    ! (theory.md sec. 4.2), so it is positive definite iff these are: mu_T, mu_L > 0 (their bounds) and
    ! the block (slots 2 and 6).
    lam = props(2); mu_t = props(3); mu_l = props(4); a = props(5); b = props(6)
    c33 = lam + 2 * mu_t + 2 * a + b + 4 * (mu_l - mu_t)
    call require_bounds(code, props, within, 3)
    call require_bounds(code, props, within, 4)
    call require(code, message, props, lam + mu_t > 0, 2, &
                 'lambda > -mu_T (hard frame stiffness positive definite)')
    call require(code, message, props, c33 > 0 .and. 2 * (lam + mu_t) * c33 > 2 * (lam + a)**2, 6, &
                 'b such that the hard-frame stiffness is positive definite: ' // &
                 'C33 = lambda + 2 mu_T + 2a + b + 4(mu_L - mu_T) > 0 ' // &
                 'and (lambda + mu_T) C33 > (lambda + a)^2')
    call require_bounds(code, props, within, 7)
    call require_bounds(code, props, within, 8)
    ! Projection tensor positive definite: c1 > 0 (its bound), c1 + c2 + c3 > 0, c1 + c3/2 > 0
    ! (theory.md sec. 1.2).
    call require_bounds(code, props, within, 9)
    call require(code, message, props, props(9) + props(10) + props(11) > 0, 10, &
                 'c1 + c2 + c3 > 0 ' // '(hard frame projection tensor positive definite)')
    call require(code, message, props, props(9) + props(11) / 2 > 0, 11, &
                 'c1 + c3/2 > 0 (hard frame projection tensor positive definite)')
    call require_bounds(code, props, within, 12)
    call require_bounds(code, props, within, 13)
  end subroutine check_hard

  !> The soft frame's PROPS 14-19: their bounds (prop_table), and a positive bulk modulus across slots.
  pure recursive subroutine check_soft(props, within, code, message)
    real(real64), intent(in) :: props(*)
    logical, intent(in) :: within   !< every slot within its own bounds
    integer, intent(inout) :: code
    character(len=message_len), intent(inout) :: message
    integer :: slot
    ! Soft frame: isotropic, positive definite iff mu > 0 (its bound) and 3 lambda + 2 mu > 0.
    call require_bounds(code, props, within, 15)
    call require(code, message, props, 3 * props(14) + 2 * props(15) > 0, 14, &
                 'lambda > -2 mu/3 (soft frame bulk modulus positive)')
    do slot = 16, 19
      call require_bounds(code, props, within, slot)
    end do
  end subroutine check_soft

  !> If no check has failed yet (code = 0) and PROPS(slot) is outside the slot's own bounds
  !> (prop_table): code = slot, and the message is left to bounds_message. Nothing to test when every
  !> slot is within its bounds (check_props' one pass).
  pure recursive subroutine require_bounds(code, props, within, slot)
    integer, intent(inout) :: code
    real(real64), intent(in) :: props(*)
    logical, intent(in) :: within
    integer, intent(in) :: slot
    if (within .or. code /= 0) return
    if (.not. within_bounds(slot, props(slot))) code = slot
  end subroutine require_bounds

  !> The message of require_bounds' slot, as require writes it, with the range from prop_table.
  pure recursive subroutine bounds_message(props, slot, message)
    real(real64), intent(in) :: props(*)
    integer, intent(in) :: slot
    character(len=message_len), intent(inout) :: message
    character(len=message_len) :: range
    integer :: code
    call range_text(prop_table(slot), range)
    code = 0
    call require(code, message, props, .false., slot, trim(range))
  end subroutine bounds_message

  !> Whether x lies within the bounds of PROPS slot (NaN does not: check_props tests finiteness first).
  pure recursive logical function within_bounds(slot, x) result(ok)
    integer, intent(in) :: slot
    real(real64), intent(in) :: x
    ok = .true.
    if (iand(prop_table(slot)%bounds, bound_lo_closed) /= 0) then
      ok = x >= prop_table(slot)%lo
    else if (iand(prop_table(slot)%bounds, bound_lo) /= 0) then
      ok = x > prop_table(slot)%lo
    end if
    if (iand(prop_table(slot)%bounds, bound_hi_closed) /= 0) then
      ok = ok .and. x <= prop_table(slot)%hi
    else if (iand(prop_table(slot)%bounds, bound_hi) /= 0) then
      ok = ok .and. x < prop_table(slot)%hi
    end if
  end function within_bounds

  !> The range of the slot pr as a message says it: 'M > 0 (hard frame)', 'eta >= 0 (...)', or with two
  !> bounds 'phi, the volume fraction of the hard frame, in [0, 1]'.
  pure recursive subroutine range_text(pr, text)
    type(prop_t), intent(in) :: pr
    character(len=message_len), intent(out) :: text
    logical :: lo, hi
    lo = iand(pr%bounds, bound_lo) /= 0
    hi = iand(pr%bounds, bound_hi) /= 0
    if (lo .and. hi) then
      text = trim(pr%symbol) // ', ' // trim(pr%note) // ', in ' // &
             merge('[', '(', iand(pr%bounds, bound_lo_closed) /= 0) // trim(number_text(pr%lo)) // ', ' // &
             trim(number_text(pr%hi)) // merge(']', ')', iand(pr%bounds, bound_hi_closed) /= 0)
      return
    end if
    text = pr%symbol
    if (lo .and. iand(pr%bounds, bound_lo_closed) /= 0) then
      text = trim(text) // ' >= ' // number_text(pr%lo)
    else if (lo) then
      text = trim(text) // ' > ' // number_text(pr%lo)
    else if (hi .and. iand(pr%bounds, bound_hi_closed) /= 0) then
      text = trim(text) // ' <= ' // number_text(pr%hi)
    else if (hi) then
      text = trim(text) // ' < ' // number_text(pr%hi)
    end if
    if (len_trim(pr%note) > 0) text = trim(text) // ' (' // trim(pr%note) // ')'
  end subroutine range_text

  !> A bound as a message writes it: a whole number without a point (0, 1), else 1.500000E+00.
  pure recursive function number_text(x) result(text)
    real(real64), intent(in) :: x
    character(len=24) :: text
    if (abs(x) < 1.0e15_real64 .and. x == aint(x)) then
      write (text, '(i0)') nint(x, kind=int64)
    else
      write (text, '(es13.6)') x
      text = adjustl(text)
    end if
  end function number_text

  !> If no check has failed yet (code = 0) and ok is false: code = slot and the message names the
  !> slot, its value and what was expected.
  pure recursive subroutine require(code, message, props, ok, slot, expected)
    integer, intent(inout) :: code
    character(len=message_len), intent(inout) :: message
    real(real64), intent(in) :: props(*)
    logical, intent(in) :: ok
    integer, intent(in) :: slot
    character(len=*), intent(in) :: expected
    if (code /= 0 .or. ok) return
    code = slot
    write (message, '(a,i0,a,es13.6,a,a)') 'Cam-Clay IX UMAT: PROPS(', slot, ') = ', props(slot), &
      ': expected ', expected
  end subroutine require

end module ccix_props
