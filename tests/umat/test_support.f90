!> Shared helpers of the UMAT test programs: the paper's properties, a UMAT call with the usual
!> arguments, assertions that count failures, and a mixed stress/strain controlled step.
module test_support
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use reference_algebra, only: lu_factor, lu_solve
  implicit none
  private

  !> Woodford shale, Yin et al. 2021 Tables 1-2 (umat-interface.md), PROPS 1-19.
  real(real64), parameter, public :: woodford(19) = [0.5_real64, &
    2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, 6900.0_real64, &
    1.46_real64, 0.00013_real64, 0.73_real64, -0.20_real64, 0.40_real64, 2.0_real64, 1.3e13_real64, &
    4600.0_real64, 3100.0_real64, 1.46_real64, 0.0026_real64, 35.0_real64, 1.3e10_real64]
  real(real64), parameter, public :: pi = 3.141592653589793_real64
  integer, parameter, public :: nstatv_test = 36
  !> A call of loading_rate_a1's hold where the UMAT's fallback solver fired (element 4204, point 3,
  !> t = 262.9 s, phi = 0, NTENS 4; a replay the driver wrote): the soft frame's stress at the start (the
  !> point's stress), its pc, the strain increment and the time increment.
  real(real64), parameter, public :: hold_stress(4) = [-69.305637224803831_real64, -878.79489119693403_real64, &
                                                        -389.64811118685145_real64, 87.692606338054048_real64]
  real(real64), parameter, public :: hold_pc_soft = 994.95049752445016_real64
  real(real64), parameter, public :: hold_dstran(4) = [1.4972230605833636e-4_real64, -5.3482132682525219e-6_real64, &
                                                        0.0_real64, -4.7599391857788831e-4_real64]
  real(real64), parameter, public :: hold_dtime = 0.9838199913588368_real64

  integer, public, save :: failures = 0, checks = 0

  public :: props_with, call_umat, check_close, check_true, finish, mixed_step, rel_diff

contains

  !> Woodford PROPS 1-23 with phi, the bedding normal and optionally eta and tol replaced.
  pure function props_with(phi, normal, eta_hard, eta_soft, tol) result(props)
    real(real64), intent(in) :: phi, normal(3)
    real(real64), intent(in), optional :: eta_hard, eta_soft, tol
    real(real64) :: props(23)
    props(1:19) = woodford
    props(1) = phi
    props(20) = 0
    props(21:23) = normal
    if (present(eta_hard)) props(13) = eta_hard
    if (present(eta_soft)) props(19) = eta_soft
    if (present(tol)) props(20) = tol
  end function props_with

  !> One UMAT call with the arguments a small-strain host passes (DROT = identity unless given).
  subroutine call_umat(props, ntens, stress, statev, stran, dstran, dtime, ddsdde, pnewdt, drot)
    real(real64), intent(in) :: props(:), stran(ntens), dstran(ntens), dtime
    integer, intent(in) :: ntens
    real(real64), intent(inout) :: stress(ntens), statev(nstatv_test)
    real(real64), intent(out) :: ddsdde(ntens, ntens)
    real(real64), intent(inout) :: pnewdt
    real(real64), intent(in), optional :: drot(3, 3)
    real(real64) :: sse, spd, scd, rpl, ddsddt(ntens), drplde(ntens), drpldt, time(2), temp, &
                    dtemp, predef(1), dpred(1), coords(3), rot(3, 3), celent, f0(3, 3), f1(3, 3)
    integer :: jstep(4)
    character(len=80) :: cmname
    external :: umat
    sse = 0; spd = 0; scd = 0; time = 0; temp = 0; dtemp = 0; predef = 0; dpred = 0; coords = 0
    celent = 1; f0 = 0; f1 = 0; jstep = 1; cmname = 'CAMCLAY9'
    rot = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3])
    if (present(drot)) rot = drot
    call umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran, &
              time, dtime, temp, dtemp, predef, dpred, cmname, 3, ntens - 3, ntens, nstatv_test, &
              props, size(props), coords, rot, pnewdt, celent, f0, f1, 1, 1, 1, 1, jstep, 1)
  end subroutine call_umat

  !> One step with components i where mask(i) is true under stress control (target sig_target(i))
  !> and the rest under strain control (dstran_known). Newton on the unknown strain components with
  !> DDSDDE; returns the converged dstran and the UMAT outputs; ok = .false. on failure or when the
  !> UMAT asks for a smaller step (PNEWDT < 1, returned in pnewdt_out).
  subroutine mixed_step(props, ntens, stress, statev, stran, dstran, mask, sig_target, dtime, &
                        ddsdde, ok, pnewdt_out)
    real(real64), intent(in) :: props(:), stran(ntens), sig_target(ntens), dtime
    integer, intent(in) :: ntens
    logical, intent(in) :: mask(ntens)
    real(real64), intent(inout) :: stress(ntens), statev(nstatv_test), dstran(ntens)
    real(real64), intent(out) :: ddsdde(ntens, ntens)
    logical, intent(out) :: ok
    real(real64), intent(out), optional :: pnewdt_out   !< the UMAT's PNEWDT of the last call
    real(real64) :: s_try(ntens), v_try(nstatv_test), pnewdt, r(ntens), k(ntens, ntens), scale
    integer :: it, idx(ntens), m, ipiv(ntens)
    logical :: factored
    m = count(mask)
    idx(1:m) = pack([(it, it = 1, ntens)], mask)
    ok = .false.
    scale = max(maxval(abs(sig_target)), 1.0_real64)
    do it = 1, 50
      s_try = stress; v_try = statev; pnewdt = huge(1.0_real64)   ! as Abaqus: large before each call
      call call_umat(props, ntens, s_try, v_try, stran, dstran, dtime, ddsdde, pnewdt)
      if (present(pnewdt_out)) pnewdt_out = pnewdt
      if (pnewdt < 1) return
      r(1:m) = s_try(idx(1:m)) - sig_target(idx(1:m))
      if (m == 0 .or. maxval(abs(r(1:m))) <= 1e-12_real64 * scale) then
        stress = s_try; statev = v_try; ok = .true.
        return
      end if
      k(1:m, 1:m) = ddsdde(idx(1:m), idx(1:m))
      call lu_factor(m, k(1:m, 1:m), ipiv(1:m), factored)
      if (.not. factored) return
      call lu_solve(m, k(1:m, 1:m), ipiv(1:m), r(1:m))
      dstran(idx(1:m)) = dstran(idx(1:m)) - r(1:m)
    end do
  end subroutine mixed_step

  pure real(real64) function rel_diff(a, b, floor)
    real(real64), intent(in) :: a(:), b(:), floor
    rel_diff = maxval(abs(a - b)) / max(maxval(abs(b)), floor)
  end function rel_diff

  !> Record a check that |actual - expected| <= tol (absolute, as the caller scales it).
  subroutine check_close(name, actual, expected, tol)
    character(len=*), intent(in) :: name
    real(real64), intent(in) :: actual, expected, tol
    checks = checks + 1
    if (.not. (abs(actual - expected) <= tol)) then
      failures = failures + 1
      write (output_unit, '(a,a,a,es23.15,a,es23.15,a,es10.3)') 'FAIL ', name, ': got ', actual, &
        ' expected ', expected, ' tol ', tol
    end if
  end subroutine check_close

  subroutine check_true(name, cond, detail)
    character(len=*), intent(in) :: name
    logical, intent(in) :: cond
    character(len=*), intent(in), optional :: detail
    checks = checks + 1
    if (.not. cond) then
      failures = failures + 1
      if (present(detail)) then
        write (output_unit, '(a,a,a,a)') 'FAIL ', name, ': ', detail
      else
        write (output_unit, '(a,a)') 'FAIL ', name
      end if
    end if
  end subroutine check_true

  !> Print the closing line and stop with a non-zero code if anything failed.
  subroutine finish(program_name)
    character(len=*), intent(in) :: program_name
    write (output_unit, '(a,a,i0,a,i0,a)') program_name, ': ', checks - failures, ' passed, ', &
      failures, ' failed'
    if (failures > 0) stop 1
  end subroutine finish

end module test_support
