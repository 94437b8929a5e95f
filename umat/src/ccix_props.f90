!> The PROPS and STATEV contract of the Cam-Clay IX UMAT (../shared/docs/umat-interface.md): slot
!> numbers, the property checks with their messages, and the frames built from PROPS.
module ccix_props
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: is_finite
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
  !> The PROPS slots' names (docs/umat.md "PROPS"), in slot order: the one spelling of every host and
  !> scene (material.set, -material_set, calibrate's parameters; C: camclay9_prop_name).
  character(len=13), parameter, public :: prop_names(nprops_normal) = [character(len=13) :: &
    'phi', 'lambda_hard', 'muT_hard', 'muL_hard', 'a_hard', 'b_hard', 'M_hard', 'lambda_p_hard', &
    'c1', 'c2', 'c3', 'pc0_hard', 'eta_hard', 'lambda_soft', 'mu_soft', 'M_soft', 'lambda_p_soft', &
    'pc0_soft', 'eta_soft', 'tol', 'n1', 'n2', 'n3']

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
    logical :: finite

    code = 0
    message = ''
    call check_sizes(nprops, nstatv, ntens, ndi, code, message)
    if (code /= 0) return
    ! All finite (NaN compares false), in one pass without branches; the slot only when one is not.
    n = min(nprops, nprops_normal)
    finite = .true.
    do i = 1, n
      finite = finite .and. abs(props(i)) <= huge(1.0_real64)
    end do
    if (.not. finite) then
      do i = 1, n
        call require(code, message, props, is_finite(props(i)), i, 'a finite number')
      end do
      return
    end if

    ! Each check acts only while no earlier one has failed, so the first offending slot is reported.
    call check_hard(props, code, message)
    call check_soft(props, code, message)
    if (code /= 0) return
    if (nprops >= ip_tol) call require(code, message, props, props(ip_tol) >= 0, ip_tol, &
                 'tol >= 0 (0: no step control)')
    if (code /= 0) return
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

  !> phi and the hard frame's PROPS 2-13.
  pure recursive subroutine check_hard(props, code, message)
    real(real64), intent(in) :: props(*)
    integer, intent(inout) :: code
    character(len=message_len), intent(inout) :: message
    real(real64) :: lam, mu_t, mu_l, a, b, c33
    call require(code, message, props, props(ip_phi) >= 0 .and. props(ip_phi) <= 1, ip_phi, &
                 'phi, the volume fraction of the hard frame, in [0, 1]')
    ! Hard frame: positive-definite TI stiffness. In bedding axes the Mandel stiffness splits into
    ! 2 mu_T, 2 mu_T, 2 mu_L, 2 mu_L and the 2x2 block [[2(lam + mu_T), sqrt2 (lam + a)], [., C33]]
    ! (theory.md sec. 4.2), so it is positive definite iff these are.
    lam = props(2); mu_t = props(3); mu_l = props(4); a = props(5); b = props(6)
    c33 = lam + 2 * mu_t + 2 * a + b + 4 * (mu_l - mu_t)
    call require(code, message, props, mu_t > 0, 3, &
                 'mu_T > 0 (hard frame, shear modulus in the bedding plane)')
    call require(code, message, props, mu_l > 0, 4, &
                 'mu_L > 0 (hard frame, shear modulus normal to the bedding)')
    call require(code, message, props, lam + mu_t > 0, 2, &
                 'lambda > -mu_T (hard frame stiffness positive definite)')
    call require(code, message, props, c33 > 0 .and. 2 * (lam + mu_t) * c33 > 2 * (lam + a)**2, 6, &
                 'b such that the hard-frame stiffness is positive definite: ' // &
                 'C33 = lambda + 2 mu_T + 2a + b + 4(mu_L - mu_T) > 0 ' // &
                 'and (lambda + mu_T) C33 > (lambda + a)^2')
    call require(code, message, props, props(7) > 0, 7, 'M > 0 (hard frame)')
    call require(code, message, props, props(8) > 0, 8, 'lambda_p > 0 (hard frame)')
    ! Projection tensor positive definite: c1 > 0, c1 + c2 + c3 > 0, c1 + c3/2 > 0 (theory.md sec. 1.2).
    call require(code, message, props, props(9) > 0, 9, &
                 'c1 > 0 (hard frame projection tensor positive definite)')
    call require(code, message, props, props(9) + props(10) + props(11) > 0, 10, &
                 'c1 + c2 + c3 > 0 ' // '(hard frame projection tensor positive definite)')
    call require(code, message, props, props(9) + props(11) / 2 > 0, 11, &
                 'c1 + c3/2 > 0 (hard frame projection tensor positive definite)')
    call require(code, message, props, props(12) > 0, 12, 'pc0 > 0 (hard frame)')
    call require(code, message, props, props(13) >= 0, 13, &
                 'eta >= 0 (hard frame; 0 is rate independent)')
  end subroutine check_hard

  !> The soft frame's PROPS 14-19.
  pure recursive subroutine check_soft(props, code, message)
    real(real64), intent(in) :: props(*)
    integer, intent(inout) :: code
    character(len=message_len), intent(inout) :: message
    ! Soft frame: isotropic, positive definite iff mu > 0 and 3 lambda + 2 mu > 0.
    call require(code, message, props, props(15) > 0, 15, 'mu > 0 (soft frame shear modulus)')
    call require(code, message, props, 3 * props(14) + 2 * props(15) > 0, 14, &
                 'lambda > -2 mu/3 (soft frame bulk modulus positive)')
    call require(code, message, props, props(16) > 0, 16, 'M > 0 (soft frame)')
    call require(code, message, props, props(17) > 0, 17, 'lambda_p > 0 (soft frame)')
    call require(code, message, props, props(18) > 0, 18, 'pc0 > 0 (soft frame)')
    call require(code, message, props, props(19) >= 0, 19, &
                 'eta >= 0 (soft frame; 0 is rate independent)')
  end subroutine check_soft

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
