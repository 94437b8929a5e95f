!> The consistent tangent: DDSDDE equals central finite differences of the stress update (theory.md
!> §3.5) for elastic, viscoplastic and rate-independent steps, each frame alone and both, anisotropic
!> normals, NTENS = 6 and 4. Also: inside the yield surface the UMAT returns sigma + C:deps and C.
program test_tangent
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use test_support
  implicit none
  real(real64) :: n30(3), n30_plane(3), deps6(6), deps4(4), s6(6), s4(4)
  real(real64), parameter :: th = 30 * pi / 180

  n30 = [sin(th), 0.0_real64, cos(th)]
  n30_plane = [sin(th), cos(th), 0.0_real64]
  ! A compressive, mostly axial strain increment with some shear, ~1e-4.
  deps6 = [-2.0e-5_real64, 1.0e-5_real64, -1.2e-4_real64, 3.0e-5_real64, -2.0e-5_real64, 1.5e-5_real64]
  deps4 = [2.0e-5_real64, -1.2e-4_real64, 0.0_real64, 3.0e-5_real64]
  s6 = -35
  s6(4:6) = 0
  s4 = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64]

  ! Viscoplastic (Perzyna) steps from both frames at -35 MPa: hard frame far outside (f = 745 MPa^2).
  call fd_check('vp both 3D dt=100', props_with(0.5_real64, n30), 6, s6, deps6, 100.0_real64)
  call fd_check('vp both 3D dt=1e4', props_with(0.5_real64, n30), 6, s6, deps6, 1.0e4_real64)
  call fd_check('vp hard only 3D', props_with(1.0_real64, n30), 6, s6, deps6, 1.0e3_real64)
  call fd_check('vp soft only 3D', props_with(0.0_real64, n30), 6, s6, deps6, 10.0_real64)
  call fd_check('vp both NTENS=4', props_with(0.5_real64, n30_plane), 4, s4, deps4, 100.0_real64)
  call fd_check('vp both 3D dt=1e-6', props_with(0.5_real64, n30), 6, s6, deps6, 1.0e-6_real64)
  ! Rate-independent (eta = 0) steps.
  call fd_check('ri both 3D', props_with(0.5_real64, n30, 0.0_real64, 0.0_real64), 6, s6, deps6, 1.0_real64)
  call fd_check('ri hard only 3D', props_with(1.0_real64, n30, 0.0_real64, 0.0_real64), 6, s6, deps6, 1.0_real64)
  call fd_check('ri soft only NTENS=4', props_with(0.0_real64, n30_plane, 0.0_real64, 0.0_real64), 4, s4, deps4, &
                1.0_real64)
  call fd_check('ri both NTENS=4', props_with(0.5_real64, n30_plane, 0.0_real64, 0.0_real64), 4, s4, deps4, &
                1.0_real64)
  ! Elastic steps: soft frame inside its surface (p = 20 < pc = 35, q small).
  call fd_check('elastic soft', props_with(0.0_real64, n30), 6, [-20.0_real64, -20.0_real64, -20.0_real64, &
                0.0_real64, 0.0_real64, 0.0_real64], deps6, 10.0_real64)
  call elastic_step_check()

  call finish('test_tangent')

contains

  !> Start a fresh state at stress0, take the step, compare DDSDDE with central differences.
  subroutine fd_check(name, props, ntens, stress0, dstran, dtime)
    character(len=*), intent(in) :: name
    real(real64), intent(in) :: props(:), stress0(ntens), dstran(ntens), dtime
    integer, intent(in) :: ntens
    real(real64) :: stress(ntens), statev(nstatv_test), d(ntens, ntens), d_fd(ntens, ntens)
    real(real64) :: sp(ntens), sm(ntens), vp(nstatv_test), dd(ntens, ntens), pnewdt, e(ntens), h, err
    integer :: j
    h = 1.0e-7_real64
    stress = stress0; statev = 0; pnewdt = 1; e = 0
    call call_umat(props, ntens, stress, statev, e, dstran, dtime, d, pnewdt)
    do j = 1, ntens
      e = dstran; e(j) = e(j) + h
      sp = stress0; vp = 0; pnewdt = 1
      call call_umat(props, ntens, sp, vp, 0 * e, e, dtime, dd, pnewdt)
      e = dstran; e(j) = e(j) - h
      sm = stress0; vp = 0; pnewdt = 1
      call call_umat(props, ntens, sm, vp, 0 * e, e, dtime, dd, pnewdt)
      d_fd(:, j) = (sp - sm) / (2 * h)
    end do
    err = maxval(abs(d - d_fd)) / maxval(abs(d))
    write (output_unit, '(a,a,a,es9.2,a,f7.1,a,es9.2)') 'tangent ', name, ': |D - D_fd|/|D| = ', err, &
      '  iterations ', statev(33), '  asymmetry ', maxval(abs(d - transpose(d))) / maxval(abs(d))
    ! Measured 3e-13 .. 6e-10; a symmetrised tangent errs by half the asymmetry (4e-8 .. 1.6e-5 in the
    ! viscoplastic cases), so 5e-9 catches it in every case.
    call check_true('tangent ' // name, err <= 5e-9_real64 .and. pnewdt >= 1)
  end subroutine fd_check

  !> Inside the surface: sigma + C:deps and DDSDDE = C (round-off), for the mixture at theta = 30.
  subroutine elastic_step_check()
    real(real64) :: props(23), stress(6), statev(nstatv_test), d(6, 6), pnewdt, sig_expect(6), c(6, 6)
    real(real64) :: p4(23), s4(4), v4(nstatv_test), d4(4, 4)
    ! Both frames inside: soft with pc0 = 35 at p = 20; hard pc0 raised to 200 so that p' = 20 is inside.
    props = props_with(0.5_real64, n30)
    props(12) = 200
    c = mixture_voigt(props)
    stress = [-20.0_real64, -21.0_real64, -19.0_real64, 1.0_real64, -0.5_real64, 0.3_real64]
    statev = 0; pnewdt = 1
    sig_expect = stress + matmul(c, deps6)
    call call_umat(props, 6, stress, statev, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], deps6, 50.0_real64, d, pnewdt)
    call check_close('elastic stress = sigma + C:deps', maxval(abs(stress - sig_expect)), 0.0_real64, &
                     1e-13_real64 * 40)
    call check_close('elastic DDSDDE = C', maxval(abs(d - c)), 0.0_real64, 1e-15_real64 * maxval(abs(c)))
    call check_close('elastic: no viscoplastic strain', maxval(abs(statev(27:32))), 0.0_real64, 0.0_real64)
    ! NTENS = 4: the {11, 22, 33, 12} block.
    p4 = props_with(0.5_real64, n30_plane)
    p4(12) = 200
    c = mixture_voigt(p4)
    s4 = [-20.0_real64, -21.0_real64, -19.0_real64, 1.0_real64]
    v4 = 0; pnewdt = 1
    call call_umat(p4, 4, s4, v4, [0d0, 0d0, 0d0, 0d0], deps4, 50.0_real64, d4, pnewdt)
    call check_close('elastic NTENS=4 stress', maxval(abs(s4 - ([-20.0_real64, -21.0_real64, -19.0_real64, &
                     1.0_real64] + matmul(c(1:4, 1:4), deps4)))), 0.0_real64, 1e-13_real64 * 40)
    call check_close('elastic NTENS=4 DDSDDE', maxval(abs(d4 - c(1:4, 1:4))), 0.0_real64, &
                     1e-15_real64 * maxval(abs(c)))
    ! DTIME = 0 (a host asking for a stiffness) is elastic even far outside the surface.
    stress = s6; statev = 0; pnewdt = 1
    call call_umat(props_with(0.5_real64, n30), 6, stress, statev, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], &
                   [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], 0.0_real64, d, pnewdt)
    call check_close('DTIME = 0: DDSDDE = C', maxval(abs(d - mixture_voigt(props_with(0.5_real64, n30)))), &
                     0.0_real64, 1e-15_real64 * maxval(abs(c)))
    call check_close('DTIME = 0: stress unchanged', maxval(abs(stress - s6)), 0.0_real64, 0.0_real64)
  end subroutine elastic_step_check

  !> The mixture stiffness in Abaqus Voigt form, from theory.md §4.2 directly (bedding axes, rotated).
  function mixture_voigt(props) result(cv)
    real(real64), intent(in) :: props(23)
    real(real64) :: cv(6, 6), n(3), lam, mt, ml, a, b
    integer :: i, j, k, l, p, q, ii(6), jj(6)
    ii = [1, 2, 3, 1, 1, 2]; jj = [1, 2, 3, 2, 3, 3]
    n = props(21:23) / norm2(props(21:23))
    lam = props(2); mt = props(3); ml = props(4); a = props(5); b = props(6)
    do q = 1, 6
      do p = 1, 6
        i = ii(p); j = jj(p); k = ii(q); l = jj(q)
        cv(p, q) = props(1) * (lam * dl(i, j) * dl(k, l) + mt * (dl(i, k) * dl(j, l) + dl(i, l) * dl(j, k)) &
                 + a * (dl(i, j) * n(k) * n(l) + n(i) * n(j) * dl(k, l)) + b * n(i) * n(j) * n(k) * n(l) &
                 + (ml - mt) * (dl(j, l) * n(i) * n(k) + dl(i, k) * n(j) * n(l) + dl(i, l) * n(j) * n(k) &
                 + dl(j, k) * n(i) * n(l))) &
                 + (1 - props(1)) * (props(14) * dl(i, j) * dl(k, l) + props(15) * (dl(i, k) * dl(j, l) &
                 + dl(i, l) * dl(j, k)))
      end do
    end do
  end function mixture_voigt

  pure real(real64) function dl(i, j)
    integer, intent(in) :: i, j
    dl = merge(1.0_real64, 0.0_real64, i == j)
  end function dl

end program test_tangent
