!> Objectivity: rotating the bedding normal, the initial stress and the strain path together rotates
!> the stress and every stored tensor, and leaves pc unchanged (1e-10). DROT rotates the stored
!> tensors of an increment (umat-interface.md).
program test_objectivity
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use test_support
  implicit none
  real(real64) :: r(3, 3)
  real(real64), parameter :: th = 30 * pi / 180

  r = rotation([0.3_real64, -0.8_real64, 0.5_real64], 1.1_real64)
  call rotated_path('viscoplastic', 100.0_real64, 1.3e13_real64, 1.3e10_real64)
  call rotated_path('rate independent', 1.0_real64, 0.0_real64, 0.0_real64)
  call drot_rotates_state()
  call finish('test_objectivity')

contains

  subroutine rotated_path(name, dtime, eta_h, eta_s)
    character(len=*), intent(in) :: name
    real(real64), intent(in) :: dtime, eta_h, eta_s
    real(real64) :: n(3), pa(23), pb(23), sa(6), sb(6), va(nstatv_test), vb(nstatv_test), da(6, 6), db(6, 6)
    real(real64) :: de(6), pn, ea(6), eb(6), err_s, err_v, err_pc
    integer :: k, blk
    n = [sin(th), 0.0_real64, cos(th)]
    pa = props_with(0.5_real64, n, eta_h, eta_s)
    pb = props_with(0.5_real64, matmul(r, n), eta_h, eta_s)
    sa = [-30.0_real64, -35.0_real64, -40.0_real64, 2.0_real64, -1.0_real64, 3.0_real64]
    sb = rot_stress(sa)
    va = 0; vb = 0; ea = 0; eb = 0
    do k = 1, 20
      de = 1.0e-5_real64 * [-1.0_real64 - 0.1_real64 * k, 0.5_real64, -3.0_real64, 0.7_real64, &
                           -0.2_real64 * mod(k, 3), 0.4_real64]
      pn = 1
      call call_umat(pa, 6, sa, va, ea, de, dtime, da, pn)
      call call_umat(pb, 6, sb, vb, eb, rot_strain(de), dtime, db, pn)
      ea = ea + de; eb = eb + rot_strain(de)
    end do
    err_s = maxval(abs(sb - rot_stress(sa))) / maxval(abs(sa))
    err_v = 0
    do blk = 0, 1
      err_v = max(err_v, maxval(abs(vb(1 + 13 * blk:6 + 13 * blk) - rot_stress(va(1 + 13 * blk:6 + 13 * blk)))) &
                         / maxval(abs(va(1 + 13 * blk:6 + 13 * blk))))
      err_v = max(err_v, maxval(abs(vb(7 + 13 * blk:12 + 13 * blk) - rot_strain(va(7 + 13 * blk:12 + 13 * blk)))) &
                         / maxval(abs(va(7 + 13 * blk:12 + 13 * blk))))
    end do
    err_v = max(err_v, maxval(abs(vb(27:32) - rot_strain(va(27:32)))) / maxval(abs(va(27:32))))
    err_pc = max(abs(vb(13) - va(13)) / va(13), abs(vb(26) - va(26)) / va(26))
    write (output_unit, '(a,a,a,3es10.2)') 'objectivity ', name, ': stress, tensors, pc errors ', err_s, err_v, err_pc
    call check_true('objectivity ' // name // ': stress rotates', err_s <= 1e-10_real64)
    call check_true('objectivity ' // name // ': state tensors rotate', err_v <= 1e-10_real64)
    call check_true('objectivity ' // name // ': pc invariant', err_pc <= 1e-10_real64)
    call check_true('objectivity ' // name // ': path was viscoplastic', maxval(abs(va(27:32))) > 1e-7_real64)
  end subroutine rotated_path

  !> DSTRAN = 0, DTIME = 0 with DROT = R: the stored frame stresses and strains become R A R^T.
  subroutine drot_rotates_state()
    real(real64) :: p(23), s(6), v(nstatv_test), v0(nstatv_test), d(6, 6), pn
    p = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64])
    v0 = 0
    v0(1:6) = [-30.0_real64, -35.0_real64, -40.0_real64, 2.0_real64, -1.0_real64, 3.0_real64]
    v0(7:12) = [1e-4_real64, -2e-4_real64, 3e-4_real64, 4e-4_real64, 0.0_real64, -1e-4_real64]
    v0(13) = 20
    v0(14:19) = [-10.0_real64, -5.0_real64, -20.0_real64, 1.0_real64, 2.0_real64, 0.0_real64]
    v0(20:25) = -v0(7:12)
    v0(26) = 35
    v0(27:32) = 0.5_real64 * v0(7:12)
    s = 0.5_real64 * (v0(1:6) + v0(14:19))
    v = v0; pn = 1
    call call_umat(p, 6, s, v, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], 0.0_real64, &
                   d, pn, drot=r)
    call check_close('DROT: hard stress', maxval(abs(v(1:6) - rot_stress(v0(1:6)))), 0.0_real64, 1e-12_real64 * 40)
    call check_close('DROT: hard vp strain', maxval(abs(v(7:12) - rot_strain(v0(7:12)))), 0.0_real64, 1e-18_real64)
    call check_close('DROT: soft vp strain', maxval(abs(v(20:25) - rot_strain(v0(20:25)))), 0.0_real64, 1e-18_real64)
    call check_close('DROT: soft stress', maxval(abs(v(14:19) - rot_stress(v0(14:19)))), 0.0_real64, 1e-12_real64 * 40)
    call check_close('DROT: overall vp strain', maxval(abs(v(27:32) - rot_strain(v0(27:32)))), 0.0_real64, 1e-18_real64)
    call check_close('DROT: pc hard unchanged', v(13), v0(13), 0.0_real64)
    call check_close('DROT: pc soft unchanged', v(26), v0(26), 0.0_real64)
  end subroutine drot_rotates_state

  !> Rotation by angle about an axis (Rodrigues).
  pure function rotation(axis, angle) result(q)
    real(real64), intent(in) :: axis(3), angle
    real(real64) :: q(3, 3), k(3, 3), u(3)
    integer :: i
    u = axis / norm2(axis)
    k = reshape([0.0_real64, u(3), -u(2), -u(3), 0.0_real64, u(1), u(2), -u(1), 0.0_real64], [3, 3])
    q = sin(angle) * k + (1 - cos(angle)) * matmul(k, k)
    do i = 1, 3
      q(i, i) = q(i, i) + 1
    end do
  end function rotation

  !> R A R^T for a Voigt stress (tensor shears) and an engineering-shear Voigt strain.
  function rot_stress(v) result(w)
    real(real64), intent(in) :: v(6)
    real(real64) :: w(6), a(3, 3)
    a = reshape([v(1), v(4), v(5), v(4), v(2), v(6), v(5), v(6), v(3)], [3, 3])
    a = matmul(r, matmul(a, transpose(r)))
    w = [a(1, 1), a(2, 2), a(3, 3), a(1, 2), a(1, 3), a(2, 3)]
  end function rot_stress

  function rot_strain(v) result(w)
    real(real64), intent(in) :: v(6)
    real(real64) :: w(6)
    w = rot_stress([v(1:3), 0.5_real64 * v(4:6)])
    w(4:6) = 2 * w(4:6)
  end function rot_strain

end program test_objectivity
