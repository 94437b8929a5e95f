!> Bad PROPS and sizes (umat-interface.md "Bad properties"): each is rejected by the exported check
!> routine, without integrating anything, with its own message naming the slot, the value and the
!> allowed range.
program test_bad_props
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use ccix_props, only: check_props, message_len
  use test_support
  implicit none
  real(real64) :: p(23)

  p = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64])
  call expect('valid Woodford, NPROPS 23', p, 23, 32, 6, 3, 0, '')
  call expect('valid Woodford, NPROPS 19', p, 19, 36, 6, 3, 0, '')
  call expect('NPROPS too small', p, 18, 32, 6, 3, -1, 'NPROPS = 18')
  call expect('partial normal', p, 21, 32, 6, 3, -1, 'NPROPS = 21')
  call expect('NSTATV too small', p, 23, 31, 6, 3, -2, 'NSTATV = 31')
  call expect('plane stress', p, 23, 32, 3, 2, -4, 'plane stress is not supported')
  call expect('NTENS', p, 23, 32, 5, 3, -3, 'NTENS = 5')
  call bad(1, 1.5_real64, 'in [0, 1]')
  call bad(3, -1.0_real64, 'mu_T > 0')
  call bad(4, 0.0_real64, 'mu_L > 0')
  call bad(2, -20000.0_real64, 'lambda > -mu_T')
  call bad(6, -1.0e5_real64, 'positive definite')
  call bad(7, 0.0_real64, 'M > 0 (hard')
  call bad(8, 0.0_real64, 'lambda_p > 0 (hard')
  call bad(9, 0.0_real64, 'c1 > 0')
  call bad(10, -2.0_real64, 'c1 + c2 + c3 > 0')
  p = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64]); p(10) = 2
  call bad(11, -1.6_real64, 'c1 + c3/2 > 0', p)
  call bad(12, 0.0_real64, 'pc0 > 0 (hard')
  call bad(13, -1.0_real64, 'eta >= 0 (hard')
  call bad(14, -3000.0_real64, 'lambda > -2 mu/3')
  call bad(15, 0.0_real64, 'mu > 0 (soft')
  call bad(16, -1.0_real64, 'M > 0 (soft')
  call bad(17, 0.0_real64, 'lambda_p > 0 (soft')
  call bad(18, -5.0_real64, 'pc0 > 0 (soft')
  call bad(19, -1.0_real64, 'eta >= 0 (soft')
  call bad(20, -1.0_real64, 'tol >= 0')
  p = props_with(0.5_real64, [0.0_real64, 0.0_real64, 0.0_real64])
  call expect('zero normal', p, 23, 32, 6, 3, 21, 'non-zero bedding normal')
  p = props_with(0.5_real64, [0.6_real64, 0.0_real64, 0.8_real64])
  call expect('out-of-plane normal with NTENS 4', p, 23, 32, 4, 3, 23, 'n3 = 0')
  call expect('NTENS 4 without a normal', p, 19, 32, 4, 3, 21, 'give NPROPS = 23')
  p = props_with(0.0_real64, [0.6_real64, 0.0_real64, 0.8_real64])
  call expect('NTENS 4 without a normal, soft frame only', p, 19, 32, 4, 3, 0, '')
  call bad(5, ieee_value(1.0_real64, ieee_quiet_nan), 'a finite number')
  call finish('test_bad_props')

contains

  subroutine bad(slot, value, expected_text, base)
    integer, intent(in) :: slot
    real(real64), intent(in) :: value
    character(len=*), intent(in) :: expected_text
    real(real64), intent(in), optional :: base(23)
    real(real64) :: q(23)
    character(len=16) :: tag
    q = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64])
    if (present(base)) q = base
    q(slot) = value
    write (tag, '(a,i0,a)') 'PROPS(', slot, ')'
    call expect(trim(tag), q, 23, 32, 6, 3, slot, expected_text)
  end subroutine bad

  subroutine expect(name, q, nprops, nstatv, ntens, ndi, code_expected, text)
    character(len=*), intent(in) :: name, text
    real(real64), intent(in) :: q(23)
    integer, intent(in) :: nprops, nstatv, ntens, ndi, code_expected
    integer :: code
    character(len=message_len) :: message
    character(len=16) :: tag
    call check_props(q, nprops, nstatv, ntens, ndi, code, message)
    write (output_unit, '(a,a,a,i0,a,a)') 'bad props ', name, ': code ', code, ': ', trim(message)
    call check_true(name // ': code', code == code_expected)
    if (code_expected > 0) then
      write (tag, '(a,i0,a)') 'PROPS(', code_expected, ')'
      call check_true(name // ': message names the slot', index(message, trim(tag)) > 0, message)
    end if
    if (len(text) > 0) call check_true(name // ': message says the allowed range', index(message, text) > 0, message)
  end subroutine expect

end program test_bad_props
