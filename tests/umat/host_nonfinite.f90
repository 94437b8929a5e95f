!> A host that passes NaN and +-Inf in every real argument of the UMAT, built with floating-point traps
!> on (-ffpe-trap=invalid,zero,overflow: SIGFPE on the first invalid operation, division by zero or
!> overflow), as debug builds of hosts run (issue 34). It is linked with each form the project ships:
!> the library, an object of camclay9_umat.f90 and one of camclay9_umat_abaqus.for with the mock Abaqus
!> (tests/umat/host_nonfinite.cmake; compiled with -cpp, and for the mock Abaqus with
!> -DHOST_NONFINITE_MOCK_ABAQUS, which opens its message file first). It calls UMAT through its
!> implicit interface, as hosts do, and itself never compares a NaN (bits and ieee_is_finite only).
!> Modes:
!>
!>   rejections    one call per argument, slot and value (NaN, +Inf, -Inf), each from the same state
!>                 (both frames flowing), and after each call the line "host: <argument> returned" on
!>                 file descriptor 2 (POSIX write, unbuffered: the UMAT's line about the call must come
!>                 before it, also when standard error is a file). Asserts, per docs/umat.md ("Rejected
!>                 calls", "Arguments the routine does not read"):
!>                   DTIME, DSTRAN(i), DROT(i,j), STATEV(1-32), STRESS(i) of an uninitialised state:
!>                     rejected: PNEWDT = 0.25, STRESS and STATEV bit for bit as passed, DDSDDE finite;
!>                   STRESS of an initialised state, STRAN, TIME, TEMP, DTEMP, PREDEF, DPRED, COORDS,
!>                     CELENT, DFGRD0, DFGRD1, SCD: not read, every output bit for bit the clean call's;
!>                   SSE, SPD: added to (the non-finite value stays), the rest the clean call's;
!>                   PNEWDT on entry: NaN and -Inf are "no request" (an accepted call leaves them,
!>                     a step rejected by the error control writes its cutback), +Inf "no limit".
!>                 Prints "host_nonfinite: <n> cases, <f> failed" and exits 1 if any failed.
!>   props K V     one rejected call (DSTRAN(1) = NaN, then "host: DSTRAN(1) returned"), then one call
!>                 with PROPS(K) = V (nan, inf, -inf): the UMAT must stop with its message; if it
!>                 returns, "host: PROPS returned" and exit 0, which the test counts as a failure.
program host_nonfinite
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
                                           ieee_negative_inf, ieee_is_finite
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_size_t, c_long
  implicit none
  interface
    function c_write(fd, buf, n) bind(c, name='write') result(written)
      import :: c_int, c_char, c_size_t, c_long
      integer(c_int), value :: fd
      character(kind=c_char), intent(in) :: buf(*)
      integer(c_size_t), value :: n
      integer(c_long) :: written
    end function c_write
  end interface
  integer, parameter :: nstatv = 36
  real(real64), parameter :: zero6(6) = 0

  !> Every real argument of one call.
  type :: call_t
    real(real64) :: stress(6), statev(nstatv), ddsdde(6, 6), sse, spd, scd, rpl, ddsddt(6), drplde(6), &
                    drpldt, stran(6), dstran(6), time(2), dtime, temp, dtemp, predef(1), dpred(1), &
                    props(23), coords(3), drot(3, 3), pnewdt, celent, dfgrd0(3, 3), dfgrd1(3, 3)
  end type call_t

  type(call_t) :: base, clean
  real(real64) :: bad(3)
  character(len=8), parameter :: bad_name(3) = [character(len=8) :: 'NaN', '+Inf', '-Inf']
  character(len=32) :: mode, arg
  integer :: cases = 0, failures = 0, slot, kind

#ifdef HOST_NONFINITE_MOCK_ABAQUS
  call mock_abaqus_start()   ! the mock Abaqus (tests/umat/mock_abaqus) opens its message file, unit 7
#endif
  bad = [ieee_value(1.0_real64, ieee_quiet_nan), ieee_value(1.0_real64, ieee_positive_inf), &
         ieee_value(1.0_real64, ieee_negative_inf)]
  call setup(base)
  clean = base
  call run(clean)
  mode = 'rejections'
  if (command_argument_count() >= 1) call get_command_argument(1, mode)

  select case (trim(mode))
  case ('props')
    call get_command_argument(2, arg)
    read (arg, *) slot
    call get_command_argument(3, arg)
    kind = findloc(['nan ', 'inf ', '-inf'], trim(arg), 1)
    call rejected_call(set_dstran(base, 1, bad(1)), 'DSTRAN(1)')
    clean = set_props(base, slot, bad(kind))
    call run(clean)
    call say('host: PROPS returned')
    write (output_unit, '(a)') 'host_nonfinite: the UMAT returned instead of stopping'
  case ('rejections')
    call rejections()
    write (output_unit, '(a,i0,a,i0,a)') 'host_nonfinite: ', cases, ' cases, ', failures, ' failed'
    if (failures > 0) error stop 1
  case default
    error stop 'host_nonfinite: mode rejections or props K nan|inf|-inf'
  end select

contains

  !> Every case that does not stop the analysis (see the header).
  subroutine rejections()
    type(call_t) :: c
    integer :: k, i
    character(len=24) :: name
    do k = 1, 3
      call rejected_call(set_scalar(base, 'DTIME', bad(k)), 'DTIME')
      do i = 1, 6
        write (name, '(a,i0,a)') 'DSTRAN(', i, ')'
        call rejected_call(set_dstran(base, i, bad(k)), trim(name))
      end do
      do i = 1, 9
        c = base
        c%drot(mod(i - 1, 3) + 1, (i - 1) / 3 + 1) = bad(k)
        write (name, '(a,i0,a,i0,a)') 'DROT(', mod(i - 1, 3) + 1, ',', (i - 1) / 3 + 1, ')'
        call rejected_call(c, trim(name))
      end do
      do i = 1, 32
        c = base
        c%statev(i) = bad(k)
        write (name, '(a,i0,a)') 'STATEV(', i, ')'
        call rejected_call(c, trim(name))
      end do
      do i = 1, 6   ! an uninitialised state (slot 13 = 0) starts from STRESS
        c = base
        c%statev = 0
        c%stress(i) = bad(k)
        write (name, '(a,i0,a)') 'STRESS(', i, ')'
        call rejected_call(c, trim(name))
      end do
      call ignored_calls(k)
      call pnewdt_calls(k)
    end do
  end subroutine rejections

  !> The arguments the UMAT does not read, and SSE and SPD, which it adds to.
  subroutine ignored_calls(k)
    integer, intent(in) :: k
    type(call_t) :: c
    c = base; c%stress(2) = bad(k); call ignored_call(c, 'STRESS(2) of an initialised state')
    c = base; c%stran(3) = bad(k); call ignored_call(c, 'STRAN(3)')
    c = base; c%time(2) = bad(k); call ignored_call(c, 'TIME(2)')
    c = base; c%temp = bad(k); call ignored_call(c, 'TEMP')
    c = base; c%dtemp = bad(k); call ignored_call(c, 'DTEMP')
    c = base; c%predef(1) = bad(k); call ignored_call(c, 'PREDEF(1)')
    c = base; c%dpred(1) = bad(k); call ignored_call(c, 'DPRED(1)')
    c = base; c%coords(1) = bad(k); call ignored_call(c, 'COORDS(1)')
    c = base; c%celent = bad(k); call ignored_call(c, 'CELENT')
    c = base; c%dfgrd0(2, 1) = bad(k); call ignored_call(c, 'DFGRD0(2,1)')
    c = base; c%dfgrd1(3, 3) = bad(k); call ignored_call(c, 'DFGRD1(3,3)')
    c = base; c%scd = bad(k); call ignored_call(c, 'SCD')
    c = base; c%sse = bad(k); call ignored_call(c, 'SSE', energy=1)
    c = base; c%spd = bad(k); call ignored_call(c, 'SPD', energy=2)
  end subroutine ignored_calls

  !> PNEWDT on entry: an accepted call with error control, and a step rejected by it (tol tiny).
  subroutine pnewdt_calls(k)
    integer, intent(in) :: k
    type(call_t) :: c
    logical :: ok
    c = base
    c%props(20) = 1.0e-3_real64   ! a tolerance the step meets: PNEWDT >= 1 advised
    c%pnewdt = bad(k)
    call run(c)
    call say('host: PNEWDT ' // trim(bad_name(k)) // ', accepted, returned')
    if (k == 2) then   ! +Inf: no limit, so the advice (in [1, 1.5]) is written
      ok = ieee_is_finite(c%pnewdt)
      if (ok) ok = c%pnewdt >= 1 .and. c%pnewdt <= 1.5_real64
    else               ! NaN, -Inf: no request, and no cutback: left as it came
      ok = same(c%pnewdt, bad(k))
    end if
    call check(ok, 'PNEWDT ' // trim(bad_name(k)) // ' on entry, accepted step')
    c = base
    c%props(20) = 1.0e-12_real64  ! a tolerance the step misses: rejected, PNEWDT < 1
    c%pnewdt = bad(k)
    call run(c)
    call say('host: PNEWDT ' // trim(bad_name(k)) // ', step control, returned')
    ok = ieee_is_finite(c%pnewdt)
    if (ok) ok = c%pnewdt >= 0.25_real64 .and. c%pnewdt < 1
    call check(ok .and. same_array(c%statev, base%statev) .and. same_array(c%stress, base%stress), &
               'PNEWDT ' // trim(bad_name(k)) // ' on entry, step rejected by the error control')
  end subroutine pnewdt_calls

  !> A call that must be rejected: PNEWDT = 0.25, STRESS and STATEV as passed, DDSDDE finite.
  subroutine rejected_call(c_in, name)
    type(call_t), intent(in) :: c_in
    character(len=*), intent(in) :: name
    type(call_t) :: c
    logical :: ok
    c = c_in
    call run(c)
    call say('host: ' // name // ' returned')
    ok = ieee_is_finite(c%pnewdt)
    if (ok) ok = c%pnewdt == 0.25_real64
    call check(ok .and. same_array(c%stress, c_in%stress) .and. same_array(c%statev, c_in%statev) .and. &
               all(ieee_is_finite(c%ddsdde)), name // ' rejected, state as passed')
  end subroutine rejected_call

  !> A call whose non-finite argument the UMAT does not read (energy = 0), or adds to (1: SSE, 2: SPD):
  !> every output bit for bit the clean call's, the energy aside.
  subroutine ignored_call(c_in, name, energy)
    type(call_t), intent(in) :: c_in
    character(len=*), intent(in) :: name
    integer, intent(in), optional :: energy
    type(call_t) :: c
    logical :: ok
    c = c_in
    call run(c)
    call say('host: ' // name // ' returned')
    ok = same_array(c%stress, clean%stress) .and. same_array(c%statev, clean%statev) .and. &
         same_array(reshape(c%ddsdde, [36]), reshape(clean%ddsdde, [36])) .and. same(c%pnewdt, clean%pnewdt)
    if (present(energy)) then   ! the non-finite energy stays non-finite, the other is the clean call's
      if (energy == 1) ok = ok .and. .not. ieee_is_finite(c%sse) .and. same(c%spd, clean%spd)
      if (energy == 2) ok = ok .and. .not. ieee_is_finite(c%spd) .and. same(c%sse, clean%sse)
    else
      ok = ok .and. same(c%sse, clean%sse) .and. same(c%spd, clean%spd)
    end if
    call check(ok, name // ' not read: the clean call''s outputs')
  end subroutine ignored_call

  !> The state every case starts from: both frames with viscoplastic strain (a deviatoric start
  !> outside both surfaces, one step of 10 s), and a viscoplastic step of 10 s to take from it.
  subroutine setup(c)
    type(call_t), intent(out) :: c
    c%props = [0.5_real64, 2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, 6900.0_real64, &
               1.46_real64, 0.00013_real64, 0.73_real64, -0.20_real64, 0.40_real64, 2.0_real64, &
               1.3e13_real64, 4600.0_real64, 3100.0_real64, 1.46_real64, 0.0026_real64, 35.0_real64, &
               1.3e10_real64, 0.0_real64, 0.6_real64, 0.0_real64, 0.8_real64]
    c%stress = [-10.0_real64, -10.0_real64, -60.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    c%statev = 0
    c%ddsdde = 0; c%sse = 0; c%spd = 0; c%scd = 0; c%stran = 0; c%time = [1.0_real64, 1.0_real64]
    c%temp = 20; c%dtemp = 0; c%predef = 0; c%dpred = 0; c%coords = [1.0_real64, 2.0_real64, 3.0_real64]
    c%drot = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3]); c%celent = 1
    c%dfgrd0 = c%drot; c%dfgrd1 = c%drot
    c%dstran = [-1.0e-4_real64, 2.0e-5_real64, -3.0e-4_real64, 4.0e-5_real64, 1.0e-5_real64, -2.0e-5_real64]
    c%dtime = 10
    c%pnewdt = 1
    call run(c)
    c%sse = 0; c%spd = 0; c%pnewdt = 1
    c%dstran = [-2.0e-5_real64, 1.0e-5_real64, -6.0e-5_real64, 1.4e-5_real64, -4.0e-6_real64, 8.0e-6_real64]
  end subroutine setup

  !> One UMAT call with every argument of c (NTENS = 6, element 12, integration point 1).
  subroutine run(c)
    type(call_t), intent(inout) :: c
    external :: umat
    integer :: jstep(4)
    character(len=80) :: cmname
    jstep = [1, 1, 0, 0]
    cmname = 'WOODFORD'
    call umat(c%stress, c%statev, c%ddsdde, c%sse, c%spd, c%scd, c%rpl, c%ddsddt, c%drplde, c%drpldt, &
              c%stran, c%dstran, c%time, c%dtime, c%temp, c%dtemp, c%predef, c%dpred, cmname, 3, 3, 6, &
              nstatv, c%props, 23, c%coords, c%drot, c%pnewdt, c%celent, c%dfgrd0, c%dfgrd1, 12, 1, 1, 1, &
              jstep, 1)
  end subroutine run

  function set_scalar(c, which, v) result(r)
    type(call_t), intent(in) :: c
    character(len=*), intent(in) :: which
    real(real64), intent(in) :: v
    type(call_t) :: r
    r = c
    if (which == 'DTIME') r%dtime = v
  end function set_scalar

  function set_dstran(c, i, v) result(r)
    type(call_t), intent(in) :: c
    integer, intent(in) :: i
    real(real64), intent(in) :: v
    type(call_t) :: r
    r = c
    r%dstran(i) = v
  end function set_dstran

  function set_props(c, i, v) result(r)
    type(call_t), intent(in) :: c
    integer, intent(in) :: i
    real(real64), intent(in) :: v
    type(call_t) :: r
    r = c
    r%props(i) = v
  end function set_props

  !> Bit for bit equal (a NaN equals the same NaN): no comparison of reals.
  logical function same(a, b)
    real(real64), intent(in) :: a, b
    same = transfer(a, 1_int64) == transfer(b, 1_int64)
  end function same

  logical function same_array(a, b)
    real(real64), intent(in) :: a(:), b(:)
    same_array = all(transfer(a, 1_int64, size(a)) == transfer(b, 1_int64, size(b)))
  end function same_array

  subroutine check(ok, name)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: name
    cases = cases + 1
    if (ok) return
    failures = failures + 1
    write (output_unit, '(a)') 'FAIL: ' // name
  end subroutine check

  !> One line on file descriptor 2, unbuffered (POSIX write), as a C host's stderr.
  subroutine say(line)
    character(len=*), intent(in) :: line
    integer(c_long) :: written
    written = c_write(2_c_int, line // new_line('a'), int(len(line) + 1, c_size_t))
  end subroutine say

end program host_nonfinite
