!> The UMAT with the closed-form material (Walpole's basis, ccix_pencil) against the UMAT with the 6 x 6
!> Cholesky + Jacobi derivation it replaced: STRESS, STATEV 1-36, DDSDDE and PNEWDT of 64 calls, each
!> within 1e-12 of the stored numbers, relative to the largest of its group (the stress, the frame
!> stresses, the frame viscoplastic strains, each pc, the overall viscoplastic strain, the iterations
!> and flags, the tangent) and the yield function values of slots 35-36 relative to pc^2 of their
!> frame (their scale: f = q'^2/M^2 + p'(p' - pc); at the end of a rate-independent step f is 0 to
!> round-off, around 1e-13 MPa^2).
!>
!> The calls: 16 cases of 4 increments each, from an uninitialised state at -35 MPa: phi = 0, 0.5, 1;
!> NTENS = 6 with the normals e3 and (sin 30, 0, cos 30), NTENS = 4 with e2 and (sin 30, cos 30, 0);
!> Woodford viscosities with step control (tol = 1e-6), and for phi = 0.5 also eta = 0. The increments:
!> compaction with shear (dt = 10 s, the hard frame far outside: viscoplastic), more of it (dt = 100 s),
!> a small unloading (dt = 1 s) and a dilation of 5e-4 (tension: the hard frame's pc falls).
!> Every call starts from the stored state of the call before it, so each comparison is of one call.
!>
!> The stored numbers (tests/umat/data/jacobi_reference.txt) were written by this program, linked with
!> the single-file UMAT of revision a309f2a (the Jacobi derivation):
!>   test_against_jacobi write jacobi_reference.txt
!> Usage: test_against_jacobi check <file> | write <file>
program test_against_jacobi
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  implicit none
  integer, parameter :: nstatv = 36, nsteps = 4
  real(real64), parameter :: pi = 3.141592653589793_real64, tol = 1.0e-12_real64
  real(real64) :: woodford(23), worst(8)
  character(len=512) :: mode, path
  integer :: unit, failures, ncalls
  character(len=*), parameter :: groups(8) = [character(len=32) :: 'STRESS', 'STATEV frame stresses', &
    'STATEV frame evp', 'STATEV pc', 'STATEV overall evp', 'STATEV 33-34 iterations, flags', &
    'STATEV 35-36 f / pc^2', 'DDSDDE']

  woodford = [0.5_real64, 2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, 6900.0_real64, &
    1.46_real64, 0.00013_real64, 0.73_real64, -0.20_real64, 0.40_real64, 2.0_real64, 1.3e13_real64, &
    4600.0_real64, 3100.0_real64, 1.46_real64, 0.0026_real64, 35.0_real64, 1.3e10_real64, 1.0e-6_real64, &
    0.0_real64, 0.0_real64, 1.0_real64]
  call get_command_argument(1, mode)
  call get_command_argument(2, path)
  if ((mode /= 'check' .and. mode /= 'write') .or. len_trim(path) == 0) then
    write (output_unit, '(a)') 'usage: test_against_jacobi check|write <file>'
    stop 2
  end if
  if (mode == 'write') then
    open (newunit=unit, file=path, status='replace', action='write')
  else
    open (newunit=unit, file=path, status='old', action='read')
  end if
  failures = 0
  ncalls = 0
  worst = 0
  call all_cases()
  close (unit)
  if (mode == 'check') then
    write (output_unit, '(a,i0,a)') 'largest differences over ', ncalls, ' calls (relative to each group):'
    block
      integer :: g
      do g = 1, size(groups)
        write (output_unit, '(2x,a32,es10.2)') groups(g), worst(g)
      end do
    end block
    write (output_unit, '(a,i0,a)') 'test_against_jacobi: ', failures, ' failed'
    if (failures > 0) stop 1
  end if

contains

  subroutine all_cases()
    real(real64) :: th, phis(3), normal3(3, 2), normal2(3, 2)
    integer :: i, k
    th = 30 * pi / 180
    phis = [0.0_real64, 0.5_real64, 1.0_real64]
    normal3(:, 1) = [0.0_real64, 0.0_real64, 1.0_real64]
    normal3(:, 2) = [sin(th), 0.0_real64, cos(th)]
    normal2(:, 1) = [0.0_real64, 1.0_real64, 0.0_real64]
    normal2(:, 2) = [sin(th), cos(th), 0.0_real64]
    do i = 1, 3
      do k = 1, 2
        call run_case(6, phis(i), normal3(:, k), .false.)
        call run_case(4, phis(i), normal2(:, k), .false.)
      end do
    end do
    do k = 1, 2
      call run_case(6, 0.5_real64, normal3(:, k), .true.)
      call run_case(4, 0.5_real64, normal2(:, k), .true.)
    end do
  end subroutine all_cases

  !> Four increments of one case; in check mode each from the stored state of the increment before.
  subroutine run_case(ntens, phi, normal, rate_independent)
    integer, intent(in) :: ntens
    real(real64), intent(in) :: phi, normal(3)
    logical, intent(in) :: rate_independent
    real(real64) :: props(23), stress(ntens), statev(nstatv), ddsdde(ntens, ntens), pnewdt, dstran(6), &
                    dtime, ref_stress(ntens), ref_statev(nstatv), ref_ddsdde(ntens, ntens), ref_pnewdt
    real(real64), parameter :: shape(6) = [-0.2_real64, -0.2_real64, -1.0_real64, 0.3_real64, &
                                           0.2_real64, 0.1_real64]
    integer :: step
    props = woodford
    props(1) = phi
    props(21:23) = normal
    if (rate_independent) then
      props(13) = 0
      props(19) = 0
    end if
    stress = -35
    stress(4:ntens) = 0
    statev = 0
    do step = 1, nsteps
      select case (step)
      case (1)
        dstran = 1.0e-4_real64 * shape; dtime = 10
      case (2)
        dstran = 0.5e-4_real64 * shape; dtime = 100
      case (3)
        dstran = -1.0e-6_real64 * shape; dtime = 1
      case default
        dstran = 5.0e-4_real64 * [1.0_real64, 1.0_real64, 1.0_real64, 0.0_real64, 0.1_real64, 0.0_real64]
        dtime = 10
      end select
      pnewdt = 1.0e36_real64
      call call_umat(props, ntens, stress, statev, dstran(1:ntens), dtime, ddsdde, pnewdt)
      ncalls = ncalls + 1
      if (mode == 'write') then
        write (unit, '(3i4)') ncalls, ntens, step
        write (unit, '(4(1x,es24.16e3))') stress, statev, ddsdde, pnewdt
      else
        call read_record(ntens, ref_stress, ref_statev, ref_ddsdde, ref_pnewdt)
        call compare(ntens, stress, statev, ddsdde, pnewdt, ref_stress, ref_statev, ref_ddsdde, ref_pnewdt)
        ! The next call starts where the stored (Jacobi) run went, not where this one went.
        stress = ref_stress
        statev = ref_statev
      end if
    end do
  end subroutine run_case

  subroutine read_record(ntens, s, v, d, p)
    integer, intent(in) :: ntens
    real(real64), intent(out) :: s(ntens), v(nstatv), d(ntens, ntens), p
    integer :: id, nt, st
    read (unit, *) id, nt, st
    if (id /= ncalls .or. nt /= ntens) then
      write (output_unit, '(a,i0)') 'FAIL the stored file does not match the calls at record ', ncalls
      stop 1
    end if
    read (unit, *) s, v, d, p
  end subroutine read_record

  subroutine compare(ntens, s, v, d, p, rs, rv, rd, rp)
    integer, intent(in) :: ntens
    real(real64), intent(in) :: s(ntens), v(nstatv), d(ntens, ntens), p, rs(ntens), rv(nstatv), &
                                rd(ntens, ntens), rp
    real(real64) :: e(8)
    integer :: g
    e(1) = rel(s, rs)
    e(2) = max(rel(v(1:6), rv(1:6)), rel(v(14:19), rv(14:19)))
    e(3) = max(rel(v(7:12), rv(7:12)), rel(v(20:25), rv(20:25)))
    e(4) = max(rel(v(13:13), rv(13:13)), rel(v(26:26), rv(26:26)))
    e(5) = rel(v(27:32), rv(27:32))
    e(6) = max(rel(v(33:33), rv(33:33)), rel(v(34:34), rv(34:34)))
    e(7) = max(abs(v(35) - rv(35)) / rv(13)**2, abs(v(36) - rv(36)) / rv(26)**2)
    e(8) = rel(reshape(d, [ntens * ntens]), reshape(rd, [ntens * ntens]))
    worst = max(worst, e)
    do g = 1, size(e)
      if (.not. (e(g) <= tol)) then
        failures = failures + 1
        write (output_unit, '(a,i0,a,a,a,es10.2)') 'FAIL call ', ncalls, ': ', trim(groups(g)), &
          ' differs by ', e(g)
      end if
    end do
    if (.not. (abs(p - rp) <= tol * abs(rp))) then
      failures = failures + 1
      write (output_unit, '(a,i0,a,2es25.17)') 'FAIL call ', ncalls, ': PNEWDT ', p, rp
    end if
  end subroutine compare

  !> max |a - b| / max |b| (0 when both vanish).
  pure real(real64) function rel(a, b)
    real(real64), intent(in) :: a(:), b(:)
    rel = maxval(abs(a - b))
    if (rel > 0) rel = rel / max(maxval(abs(b)), tiny(1.0_real64))
  end function rel

  subroutine call_umat(props, ntens, stress, statev, dstran, dtime, ddsdde, pnewdt)
    integer, intent(in) :: ntens
    real(real64), intent(in) :: props(23), dstran(ntens), dtime
    real(real64), intent(inout) :: stress(ntens), statev(nstatv), pnewdt
    real(real64), intent(out) :: ddsdde(ntens, ntens)
    real(real64) :: sse, spd, scd, rpl, ddsddt(ntens), drplde(ntens), drpldt, stran(ntens), time(2), &
                    temp, dtemp, predef(1), dpred(1), coords(3), drot(3, 3), celent, f0(3, 3), f1(3, 3)
    integer :: jstep(4)
    character(len=80) :: cmname
    external :: umat
    sse = 0; spd = 0; scd = 0; stran = 0; time = 0; temp = 0; dtemp = 0; predef = 0; dpred = 0
    coords = 0; celent = 1; f0 = 0; f1 = 0; jstep = 1; cmname = 'CAMCLAY9'
    drot = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3])
    call umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran, &
              time, dtime, temp, dtemp, predef, dpred, cmname, 3, ntens - 3, ntens, nstatv, props, 23, &
              coords, drot, pnewdt, celent, f0, f1, 1, 1, 1, 1, jstep, 1)
  end subroutine call_umat

end program test_against_jacobi
